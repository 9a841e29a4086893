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
"""

import math
import statistics
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.solver.oblique import ObliqueModel, _solve_contact
from contactlab.solver.oblique_phases import grid_signals
from contactlab.solver.system import System

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests/contactlab/solver"))
from oblique_reference import ObliqueReference
from timing import wall_times

REPEATS = 41
GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
NORMAL = cl.laws.Hertz.from_material(*GRAIN.material())
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


def main():
    print(f"oblique Hertz-Mindlin impact, R = {GRAIN.radius * 1e3} mm, {SPEED} m/s, rtol {RTOL}")
    for history in ("total", "incremental"):
        law = cl.laws.Mindlin.from_material(3.8e11, 0.23, GRAIN.radius, 0.092, history=history)
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
    main()
