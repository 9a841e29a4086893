"""Audit oblique and normal impacts over the parameter matrix users have (issue 21).

Draws impacts from :func:`contactlab.testing.strategies.oblique_impacts` (grains 1-10 mm,
flat or 5-300 kHz sensors, every normal law ``simulate_oblique`` accepts, set by a
restitution of 0.05-1, spring and both Mindlin forms with friction 0-1, 0.1-10 m/s, any
incidence in [0, 90) deg, spin up to 3 V/R either way), runs the full audit
(:meth:`contactlab.ObliqueResult.audit`) and prints, per check, the worst value over the
matrix and over each normal x tangential pair, the failures, and the gross-sliding
impulse ratio's shortfall where rigid-body theory says the contact slides throughout.
Then the same for :func:`contactlab.simulate_impact` with every law of ``contactlab.laws``.

    python benchmarks/audit_matrix.py [--examples N] [--seed S]

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


def run_oblique(examples, seed_value):
    worst, shortfall = Worst(), [0.0, None]

    @seed(seed_value)
    @settings(**SETTINGS, max_examples=examples)
    @given(case=oblique_impacts())
    def one(case):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                res = cl.simulate_oblique(**case, audit=False)
            # a solver that gives up, or a contact refused as no impact, is listed too
            except (RuntimeError, ParameterError) as error:
                worst.failures.append((case, [str(error)]))
                return
        worst.add(res.audit(), (_name(case["normal_law"]), _name(case["tangential_law"])), case)
        mu = case["tangential_law"].friction
        slides = (
            mu >= MIN_FRICTION
            and res.restitution >= 0.0
            and analytic.slides_throughout(
                res.normal_velocity,
                res.incident_tangential_velocity,
                case["spin"],
                case["grain"].radius,
                min(res.restitution, 1.0),
                mu,
            )
        )
        if slides and res.slip_before != 0.0:
            sign = math.copysign(1.0, res.slip_before)
            gap = 1.0 + res.tangential_impulse / res.normal_impulse * sign / mu
            if gap > shortfall[0]:
                shortfall[:] = [gap, case]

    one()
    return worst, shortfall


def run_impact(examples, seed_value):
    worst = Worst()

    @seed(seed_value)
    @settings(**SETTINGS, max_examples=examples)
    @given(case=normal_impacts())
    def one(case):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                res = cl.simulate_impact(**case, audit=False)
            except (RuntimeError, ParameterError) as error:
                worst.failures.append((case, [str(error)]))
                return
        worst.add(res.audit(), (type(case["law"]).__name__,), case)

    one()
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--examples", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=21)
    args = parser.parse_args()
    t0 = time.perf_counter()
    worst, shortfall = run_oblique(args.examples, args.seed)
    worst.report("simulate_oblique")
    print(
        f"  gross sliding (rigid-body theory): largest impulse-ratio shortfall {shortfall[0]:.3g}"
    )
    print(f"    at {shortfall[1]}")
    run_impact(args.examples // 2, args.seed).report("simulate_impact")
    print(f"\n{time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
