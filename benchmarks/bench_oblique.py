"""Oblique Hertz-Mindlin impacts: contactlab against scipy's solve_ivp (issue 25 targets).

Chung & Ooi's test 4 grain (aluminium oxide, R = 2.5 mm, 3.9 m/s) on a rigid flat, Hertz
normal and Mindlin tangential ("total" and "incremental"), at 5 deg (stick and slip
phases) and 45 deg (gross sliding). Targets: one impact with its 20 001-sample output
grid (and the default cheap audit) in at most 1 ms and at least 10x scipy's
``solve_ivp`` on the same equations; a batch sweep over angle and spin at >= 2 000
impacts/s.

The reference is scipy's ``solve_ivp`` (DOP853, the same rtol 1e-9 and atol) on the same
equations written in Python from the laws' methods, with scipy's own terminal events
(``tests/contactlab/solver/oblique_reference.py``, also the tests' reference): its
rebound is printed beside ours. ``contactlab`` is timed twice: the full call and the
contact integration alone (``_solve_contact``, the same work as the reference).
Medians of repeated runs, and the fastest run (the machine is shared: the fastest is the
best estimate of the cost on a quiet one); ratios are of medians and of minima.

Kratos' elastic Coulomb cap (``Mindlin(coulomb_cap="elastic")``, :func:`elastic_cap`) is
timed on three damped cases (a Kratos-like impact on a sensor, 10 phases; Chung & Ooi's
grain with all of Kratos' rules at e = 0.98, 5 deg, 25 phases, and 30 deg, 170 phases)
against LAMMPS' cap on the same impacts in the same run; ``--before DIR`` times the same
cases on the code in ``DIR`` too (a checkout, e.g. ``git archive main | tar -x -C DIR``),
in a fresh process, and prints after / before. ``--elastic-only`` runs this part alone.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab import analytic
from contactlab.solver.conventions import DEM_CONVENTIONS
from contactlab.solver.oblique import ObliqueModel, _solve_contact
from contactlab.solver.oblique_phases import grid_signals
from contactlab.solver.system import System

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests/contactlab/solver"))
from oblique_reference import ObliqueReference
from timing import wall_times

REPEATS = 41


def _from_material(law, material, *rest, **options):
    """``law.from_material`` of the code running (``--before`` runs an older checkout): the
    grain's Material, or in a checkout from before ``analytic.Material`` its three numbers."""
    first = (cl.analytic.Material(*material),) if hasattr(cl.analytic, "Material") else material
    return law.from_material(*first, *rest, **options)


GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
NORMAL = _from_material(cl.laws.Hertz, GRAIN.material())
SPEED, RTOL = 3.9, 1e-9
SWEEP = 50
"""Angles and spins of the batch sweep (SWEEP**2 impacts)."""


def median_time(fn, repeats=REPEATS):
    """(median, fastest) wall time [s] of ``fn()``."""
    times = wall_times(fn, repeats)
    return statistics.median(times), min(times)


def ours(law, angle):
    res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), NORMAL, law, SPEED, angle, rtol=RTOL)
    assert res.t.size == 20_001
    return res.tangential_velocity, res.angular_velocity


def ours_contact_only(law, angle):
    """The contact integration alone: simulate_oblique without its output grid."""
    radius = GRAIN.radius
    model = ObliqueModel(
        System(GRAIN, cl.Sensor.rigid()), NORMAL, law, radius, 0.4 * GRAIN.mass * radius**2
    )
    y0 = np.array([0.0, 0.0, 0.0, SPEED * math.cos(angle), SPEED * math.sin(angle), 0.0, 0.0])
    return _solve_contact(model, y0, RTOL, (SPEED, GRAIN.mass * SPEED / 1e-6))[1][4:6]


def pieces(law, angle):
    """(median, fastest) [s] of the full call's pieces after the contact integration: the
    output grid (:func:`contactlab.solver.oblique_phases.grid_signals`), the peak search
    and the cheap audit without it."""
    res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), NORMAL, law, SPEED, angle, rtol=RTOL)
    contact, final = res._contact, res._final

    def grid():  # on a wall the compiled pass writes the free flight too
        grid_signals(contact, None, final, res.duration, res.sample_rate)

    def peaks():
        res.__dict__.pop("_peaks", None)
        return res._peaks

    res._peaks  # noqa: B018 (cached: the audit below reads it)
    return {
        "grid": median_time(grid),
        "peaks": median_time(peaks),
        "audit": median_time(lambda: res.audit(full=False)),
    }


def scipy_reference(law, angle):
    """The same equations and phases with solve_ivp."""
    length = SPEED * 1e-6
    history = length if law.history_kind == "displacement" else GRAIN.mass * SPEED / 1e-6
    scales = np.array([length, SPEED, length, SPEED, SPEED, SPEED / GRAIN.radius, history])
    reference = ObliqueReference(GRAIN, cl.Sensor.rigid(), NORMAL, law)
    y, _ = reference.solve(SPEED, angle, 0.0, RTOL, 1e-3 * RTOL * scales)
    return y[4], y[5]


def batch_sweep(law):
    """SWEEP angles in [0, 85] deg times SWEEP spins in [-2000, 2000] rad/s."""
    from contactlab.batch.oblique import oblique_impacts

    angles, spins = np.meshgrid(
        np.radians(np.linspace(0.0, 85.0, SWEEP)), np.linspace(-2e3, 2e3, SWEEP)
    )
    frame = pd.DataFrame(
        {
            "m1 [kg]": math.inf,
            "k1 [N/m]": math.inf,
            "c1 [N*s/m]": 0.0,
            "m2 [kg]": GRAIN.mass,
            "k_hertz [N/m**1.5]": NORMAL.k_hertz,
            "damping [N*s/m**1.25]": 0.0,
            "k_mindlin [N/m**1.5]": law.k_mindlin,
            "friction [-]": law.friction,
            "v0 [m/s]": SPEED,
            "radius [m]": GRAIN.radius,
            "angle [rad]": angles.ravel(),
            "spin [rad/s]": spins.ravel(),
        }
    )
    oblique_impacts(frame.iloc[:10], history=law.history, rtol=RTOL)  # compile
    elapsed, _ = median_time(lambda: oblique_impacts(frame, history=law.history, rtol=RTOL), 3)
    out = oblique_impacts(frame, history=law.history, rtol=RTOL)
    worst = 0.0
    for i in range(0, len(frame), len(frame) // 7):
        row = frame.iloc[i]
        res = cl.simulate_oblique(
            GRAIN,
            cl.Sensor.rigid(),
            NORMAL,
            law,
            SPEED,
            row["angle [rad]"],
            spin=row["spin [rad/s]"],
            rtol=RTOL,
        )
        worst = max(worst, abs(out["tangential_velocity [m/s]"].iloc[i] - res.tangential_velocity))
    return len(frame) / elapsed, worst


ELASTIC_REPEATS = 11
"""Calls per figure of :func:`elastic_cap` (the Python loop it replaced took 40-400 ms)."""


def kratos_cases():
    """``{name: (arguments, keywords)}`` of :func:`contactlab.simulate_oblique` with
    Kratos' elastic cap (the cases of ``tests/contactlab/solver/test_elastic_cap.py``)."""
    grain = cl.Grain(diameter=5e-3, density=2500.0, youngs_modulus=7e10, poisson_ratio=0.25)
    sensor = cl.Sensor(mass=2e-3, stiffness=5e7, damping=2.0)
    normal = _from_material(cl.laws.HertzDamped, grain.material(), 0.6, grain.mass)
    tangential = _from_material(
        cl.laws.Mindlin,
        grain.material(),
        0.3,
        history="incremental",
        damping="tied",
        coulomb_cap="elastic",
    )
    cases = {"sensor 20 deg": ((grain, sensor, normal, tangential, 1.0, math.radians(20)), {})}
    damped = cl.laws.HertzDamped(
        NORMAL.k_hertz,
        analytic.tsuji_damping_coefficient(NORMAL.k_hertz, GRAIN.mass, 0.98, "force"),
    )
    kratos = DEM_CONVENTIONS["kratos"].mindlin(
        _from_material(cl.laws.Mindlin, GRAIN.material(), 0.092)
    )
    for degrees in (5, 30):
        laws = (GRAIN, cl.Sensor.rigid(), damped, kratos, SPEED, math.radians(degrees))
        cases[f"test 4 {degrees} deg"] = (laws, {"lever_arm": "contact"})
    return cases


def _lammps_cap(law):
    """``law`` with LAMMPS' cap instead of Kratos'."""
    return cl.laws.Mindlin(law.k_mindlin, law.friction, law.history, law.damping_form, "total")


def _contact_alone(args, kwargs):
    """:func:`contactlab.simulate_oblique`'s contact integration alone (``_solve_contact``,
    no output grid and no audit) for its arguments."""
    grain, sensor, normal, tangential, speed, angle = args
    radius = grain.radius
    model = ObliqueModel(
        System(grain, sensor),
        normal,
        tangential,
        radius,
        0.4 * grain.mass * radius**2,
        kwargs.get("lever_arm", "radius"),
    )
    vn, vt = speed * math.cos(angle), speed * math.sin(angle)
    y0 = np.array([0.0, 0.0, 0.0, vn, vt, kwargs.get("spin", 0.0), 0.0])
    return _solve_contact(model, y0, RTOL, (speed, grain.mass * speed / 1e-6))


def elastic_cap(caps=("elastic", "total")):
    """``{case: {cap: (median, fastest) [s], cap + " contact": the same of the contact
    alone, "phases": n}}`` of the full call (with its default audit)."""
    out = {}
    for name, (args, kwargs) in kratos_cases().items():
        out[name] = {"phases": len(cl.simulate_oblique(*args, **kwargs).phases)}
        for cap in caps:
            laws = args if cap == "elastic" else (*args[:3], _lammps_cap(args[3]), *args[4:])
            call = lambda laws=laws, kwargs=kwargs: cl.simulate_oblique(*laws, **kwargs)  # noqa: E731
            out[name][cap] = median_time(call, ELASTIC_REPEATS)
            alone = lambda laws=laws, kwargs=kwargs: _contact_alone(laws, kwargs)  # noqa: E731
            out[name][f"{cap} contact"] = median_time(alone, ELASTIC_REPEATS)
    return out


def _before(directory):
    """:func:`elastic_cap`'s Kratos figures of the code in ``directory``, in a fresh
    process."""
    env = dict(os.environ, PYTHONPATH=str(Path(directory).resolve()))
    done = subprocess.run(
        [sys.executable, __file__, "--elastic-only", "--json"],
        env=env,
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(done.stdout.splitlines()[-1])


def print_elastic_cap(before=None):
    """Print :func:`elastic_cap` (and the code in ``before``'s, after / before)."""
    then = None if before is None else _before(before)
    print(
        "Kratos' elastic Coulomb cap: the full call with 20 001 samples and its default "
        "audit, and the contact alone, median (fastest) [ms]:"
    )
    for name, row in elastic_cap().items():
        print(f"  {name} ({row['phases']} phases):")
        for part in ("", " contact"):
            (t_e, m_e), (t_t, m_t) = row["elastic" + part], row["total" + part]
            line = (
                f"    {part.strip() or 'full call':9s} elastic cap {t_e * 1e3:8.3f} "
                f"({m_e * 1e3:8.3f}), LAMMPS' cap {t_t * 1e3:6.3f} ({m_t * 1e3:6.3f}), "
                f"elastic / LAMMPS' {t_e / t_t:6.2f}"
            )
            if then is not None:
                t_b, m_b = then[name]["elastic" + part]
                line += (
                    f"; before {t_b * 1e3:8.2f} ({m_b * 1e3:8.2f}), after / before "
                    f"{t_e / t_b:6.4f} ({m_e / m_b:6.4f})"
                )
            print(line)


def main():
    print(f"oblique Hertz-Mindlin impact, R = {GRAIN.radius * 1e3} mm, {SPEED} m/s, rtol {RTOL}")
    for history in ("total", "incremental"):
        law = _from_material(cl.laws.Mindlin, (3.8e11, 0.23, GRAIN.radius), 0.092, history=history)
        for degrees in (5.0, 45.0):
            angle = math.radians(degrees)
            a, b = ours(law, angle), scipy_reference(law, angle)
            t_ours, m_ours = median_time(lambda law=law, angle=angle: ours(law, angle))
            t_core, m_core = median_time(lambda law=law, angle=angle: ours_contact_only(law, angle))
            t_ref, m_ref = median_time(lambda law=law, angle=angle: scipy_reference(law, angle), 11)
            print(
                f"{history:12s} {degrees:4.0f} deg: contactlab {t_ours * 1e3:6.3f} ms (fastest "
                f"{m_ours * 1e3:6.3f}) with 20 001 samples (target <= 1); contact alone "
                f"{t_core * 1e3:6.3f} ms (fastest {m_core * 1e3:6.3f}); solve_ivp "
                f"{t_ref * 1e3:6.2f} ms (fastest {m_ref * 1e3:6.2f}); ratio solve_ivp / "
                f"contactlab {t_ref / t_ours:5.1f} (fastest {m_ref / m_ours:5.1f}; target >= 10),"
                f" / contact alone "
                f"{t_ref / t_core:5.1f}"
            )
            print(
                f"{'':12s} rebound: vt' {a[0]:.10f} vs {b[0]:.10f} m/s, spin' {a[1]:.7f} vs "
                f"{b[1]:.7f} rad/s"
            )
            parts = pieces(law, angle)
            print(
                f"{'':12s} pieces, median (fastest) [ms]: "
                + ", ".join(f"{k} {v[0] * 1e3:.3f} ({v[1] * 1e3:.3f})" for k, v in parts.items())
            )
        try:
            rate, worst = batch_sweep(law)
        except ImportError:
            print("batch: contactlab.batch.oblique not available in this version")
            continue
        print(
            f"{history:12s} batch over {SWEEP}x{SWEEP} angles and spins: {rate:7.0f} impacts/s "
            f"(target >= 2000); largest |vt' - single solver's| {worst:.2e} m/s"
        )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="a checkout of the code before a change")
    parser.add_argument("--elastic-only", action="store_true", help="Kratos' cap only")
    parser.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.json:
        print(json.dumps(elastic_cap(("elastic",))))
    else:
        print(f"load average {os.getloadavg()[0]:.1f}")
        if not args.elastic_only:
            main()
        print_elastic_cap(args.before)
