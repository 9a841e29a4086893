"""Audit oblique and normal impacts over the parameter matrix users have (issue 21).

Draws impacts from :func:`contactlab.testing.strategies.oblique_impacts` (grains 1-10 mm,
flat or 5-300 kHz sensors, every normal law ``simulate_oblique`` accepts, set by a
restitution of 0.05-1, spring and both Mindlin forms with friction 0-1, 0.1-10 m/s, any
incidence in [0, 90) deg, spin up to 3 V/R either way), runs the full audit
(:meth:`contactlab.ObliqueResult.audit`) and prints, per check, the worst value over the
matrix and over each normal x tangential pair, the failures, and the gross-sliding
impulse ratio's shortfall where rigid-body theory says the contact slides throughout.
Then the same for :func:`contactlab.simulate_impact` with every law of ``contactlab.laws``,
and the restitution of each drawn law, grain and speed on an immovable wall against the
law's closed form (the worst per law; laws of the exact method also through DOP853).

    python benchmarks/audit_matrix.py [--examples N] [--seed S] [--normal-only]

Hypothesis draws the cases (seeded: the same matrix every run); it favours the ends of
every range, which is where invariants break.
"""

import argparse
import collections
import math
import time
import warnings

from hypothesis import HealthCheck, Phase, given, seed, settings

import contactlab as cl
from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.testing import closed_forms_for
from contactlab.testing.strategies import normal_impacts, oblique_impacts

MIN_FRICTION = 0.01
"""Smallest friction at which the gross-sliding impulse ratio is read: below it the
tangential impulse is a tiny difference of two momenta (1e-153 at mu 1e-153)."""

SETTINGS = {
    "deadline": None,
    "database": None,
    "phases": [Phase.generate],  # a sweep: every case is recorded, none is shrunk
    "suppress_health_check": [HealthCheck.too_slow, HealthCheck.data_too_large],
}


def _name(law):
    if isinstance(law, cl.laws.Mindlin):
        return f"Mindlin/{law.history}"
    return type(law).__name__


class Worst:
    """Largest value of each check, overall and per key, with the case that gave it."""

    def __init__(self):
        self.values = collections.defaultdict(lambda: (-math.inf, None))
        self.failures = []
        self.count = 0

    def solve(self, simulate, case):
        """``simulate(**case, audit=False)`` with its warnings silenced, or None after
        listing a solver that gives up, or a contact refused as no impact, as a failure."""
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                return simulate(**case, audit=False)
            except (RuntimeError, ParameterError) as error:
                self.failures.append((case, [str(error)]))
                return None

    def add(self, audit, key, case):
        self.count += 1
        for check in audit.checks:
            for where in (check.name, (check.name, *key)):
                if check.worst > self.values[where][0]:
                    self.values[where] = (check.worst, case)
        if not audit.ok:
            self.failures.append((case, [c.describe() for c in audit.failures]))

    def report(self, title):
        print(f"\n## {title}, {self.count} impacts: worst value of each check")
        for name in sorted(k for k in self.values if isinstance(k, str)):
            print(f"  {name:22s} {self.values[name][0]: .3g}")
        print("  by law:")
        for key in sorted((k for k in self.values if not isinstance(k, str)), key=str):
            print(f"    {' / '.join(key):60s} {self.values[key][0]: .3g}")
        print(f"  failures: {len(self.failures)}")
        for case, lines in self.failures[:10]:
            print("   ", case, lines)


def _sweep(worst, cases, simulate, key, then, examples, seed_value):
    """Run ``examples`` hypothesis cases of the strategy ``cases`` through ``simulate``:
    each audit goes into ``worst`` under ``key(case)``, then ``then(case, result)``."""

    @seed(seed_value)
    @settings(**SETTINGS, max_examples=examples)
    @given(case=cases)
    def one(case):
        res = worst.solve(simulate, case)
        if res is not None:
            worst.add(res.audit(), key(case), case)
            then(case, res)

    one()


def run_oblique(examples, seed_value):
    worst, shortfall = Worst(), [0.0, None]

    def slide(case, res):
        mu = case["tangential_law"].friction
        slides = (
            mu >= MIN_FRICTION
            and res.restitution >= 0.0
            and analytic.slides_throughout(
                analytic.ObliqueImpact(
                    res.normal_velocity,
                    res.incident_tangential_velocity,
                    case["spin"],
                    case["grain"].radius,
                    min(res.restitution, 1.0),
                    mu,
                )
            )
        )
        if slides and res.slip_before != 0.0:
            sign = math.copysign(1.0, res.slip_before)
            gap = 1.0 + res.tangential_impulse / res.normal_impulse * sign / mu
            if gap > shortfall[0]:
                shortfall[:] = [gap, case]

    def key(case):
        return _name(case["normal_law"]), _name(case["tangential_law"])

    _sweep(worst, oblique_impacts(), cl.simulate_oblique, key, slide, examples, seed_value)
    return worst, shortfall


class Rebounds:
    """Largest restitution error on an immovable wall against the law's closed form
    (:func:`contactlab.testing.closed_forms_for`), per law and method: ``|e - e_cf|``, the
    rebound speed's error in units of the impact speed (the scale of the solver's
    tolerance), with the relative error at that case, and for a closed form with an
    allowance (Kuwabara-Kono's truncated series) the error as a share of it."""

    def __init__(self):
        self.worst = collections.defaultdict(lambda: (-math.inf, None, None))
        self.count = collections.Counter()
        self.skipped = collections.Counter()

    def add(self, case, method):
        law, grain, velocity = case["law"], case["grain"], case["velocity"]
        key = (type(law).__name__, method)
        try:
            forms = closed_forms_for(law, grain.mass, velocity)
        except ParameterError:  # Kuwabara-Kono beyond its series' range: no closed form
            self.skipped[key] += 1
            return
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = cl.simulate_impact(
                grain, cl.Sensor.rigid(), law, velocity, method=method, audit=False
            )
        self.count[key] += 1
        for form in (f for f in forms if f.quantity == "restitution"):
            gap = abs(res.restitution - form.value)
            relative = gap / abs(form.value) if form.value else math.nan
            share = gap / form.atol if form.atol else None
            if gap > self.worst[key][0]:
                self.worst[key] = (gap, (relative, share), case)

    def report(self):
        print("\n## restitution on a wall against the closed form: worst per law and method")
        for key in sorted(self.worst):
            gap, (relative, share), case = self.worst[key]
            allowance = "" if share is None else f", {share:.3g} of its allowance"
            skipped = f", {self.skipped[key]} beyond the series" if self.skipped[key] else ""
            print(
                f"  {key[0]:18s} {key[1]:9s} |e - e_cf| {gap:.3g} (relative {relative:.3g}"
                f"{allowance}) [{self.count[key]}{skipped}]"
            )
            print(f"      at {case}")


def run_impact(examples, seed_value):
    worst, rebounds = Worst(), Rebounds()

    def rebound(case, res):
        law = case["law"]
        # the exact method's laws through DOP853 too: the Python piece path with exits
        methods = ["auto"] if law.prescribed or not law.piecewise_linear else ["auto", "adaptive"]
        for method in methods:
            rebounds.add(case, method)

    def key(case):
        return (type(case["law"]).__name__,)

    _sweep(worst, normal_impacts(), cl.simulate_impact, key, rebound, examples, seed_value)
    return worst, rebounds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--examples", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=21)
    parser.add_argument(
        "--normal-only", action="store_true", help="only simulate_impact (skip the oblique)"
    )
    args = parser.parse_args()
    t0 = time.perf_counter()
    if not args.normal_only:
        worst, shortfall = run_oblique(args.examples, args.seed)
        worst.report("simulate_oblique")
        print(
            "  gross sliding (rigid-body theory): largest impulse-ratio shortfall "
            f"{shortfall[0]:.3g}"
        )
        print(f"    at {shortfall[1]}")
    worst, rebounds = run_impact(args.examples // 2, args.seed)
    worst.report("simulate_impact")
    rebounds.report()
    print(f"\n{time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
