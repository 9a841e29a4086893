"""LAMMPS as the DEM engine: time per impact and error against the exact solver.

1. Every mapped law (linear, Hertz, Tsuji's damped Hertz, Kuwabara-Kono) at the paper's
   scale, on a rigid plate and on the 40 kHz disc sensor, at the default step: wall time
   of one whole ``drop_test`` (median of several runs; the machine is shared), beside the
   exact solver's (:func:`contactlab.simulate_impact`) on the same case, and the relative
   errors of restitution, contact time and the two peaks.
2. The time-step convergence of the base case (linear law, 40 kHz sensor) and of Tsuji's
   law: errors per step and the observed order.
3. pybullet on the base case in the same run (its default step), the only law it holds.
4. The LAMMPS export realised by LAMMPS in a user's deck (rebound, contact time, peak).

Target: < 0.5 s per impact at default settings.
"""

import tempfile
from pathlib import Path

import numpy as np
from timing import median_time

import contactlab as cl
from contactlab import analytic
from contactlab.config import ImpactConfig
from contactlab.inverse import export_dem
from contactlab.solver.wall import wall_contact_time, wall_impact
from dem_check.engines import bullet
from dem_check.engines.lammps import convergence_study, drop_test
from dem_check.engines.lammps.realise import realise_snippet

REPEATS = 5
TARGET = 0.5  # [s] per impact
V0 = 2.0  # [m/s]
QUANTITIES = ("restitution", "contact_time", "peak_contact_force", "peak_sensor_force")


def _errors(res, ref):
    return [getattr(res, q) / getattr(ref, q) - 1.0 for q in QUANTITIES]


def _laws(grain):
    k_hertz = analytic.hertz_stiffness(21.6e6, grain.radius)
    return {
        "linear": cl.laws.LinearViscoelastic(1e5, 1.0),
        "hertz": cl.laws.Hertz(k_hertz),
        "hertz_damped": cl.laws.HertzDamped.from_material(
            cl.analytic.Material(21.6e6, 0.2, grain.radius), 0.5, grain.mass
        ),
        "kuwabara_kono": cl.laws.KuwabaraKono(k_hertz, 2e-6),
    }


def _impacts(grain, sensors, laws):
    print("1. LAMMPS impacts at the default step (relative errors vs the exact solver)")
    print(
        f"{'law':<14} {'sensor':<7} {'LAMMPS [s]':>10} {'exact [s]':>10} {'ratio':>6}  "
        + "  ".join(f"{q:>18}" for q in QUANTITIES)
    )
    worst = 0.0
    for name, law in laws.items():
        for label, sensor in sensors.items():
            res = drop_test(ImpactConfig(grain, sensor, law, {"velocity": V0}))
            ref = cl.simulate_impact(grain, sensor, law, V0)
            t_lammps = median_time(
                lambda law=law, sensor=sensor: drop_test(
                    ImpactConfig(grain, sensor, law, {"velocity": V0})
                ),
                REPEATS,
            )
            t_exact = median_time(
                lambda law=law, sensor=sensor: cl.simulate_impact(grain, sensor, law, V0),
                REPEATS,
            )
            worst = max(worst, t_lammps)
            errors = "  ".join(f"{e:>+18.2e}" for e in _errors(res, ref))
            print(
                f"{name:<14} {label:<7} {t_lammps:>10.4f} {t_exact:>10.4f} "
                f"{t_lammps / t_exact:>6.1f}  {errors}"
            )
    verdict = "meets" if worst < TARGET else "MISSES"
    print(f"slowest impact {worst:.3f} s: {verdict} the {TARGET} s target\n")


def _convergence(grain, sensor, laws):
    print("2. Time-step convergence (signed errors; restitution absolute)")
    for name in ("linear", "hertz_damped"):
        law = laws[name]
        contact = wall_contact_time(law, grain.mass, V0)
        base = min(contact, sensor.period)
        steps = [base / n for n in (50, 100, 200, 400, 800)]
        study = convergence_study(
            ImpactConfig(grain, sensor, law, {"velocity": V0}), time_steps=steps
        )
        columns = ["time_step [s]", *(f"{q} error [-]" for q in QUANTITIES), "wall_time [s]"]
        print(f"{name} on the 40 kHz sensor:")
        print(study[columns].to_string(index=False, float_format=lambda x: f"{x:.3e}"))
        orders = {q: round(study.attrs["order"][q], 2) for q in QUANTITIES}
        print(f"observed order: {orders}\n")


def _bullet(grain, sensor, laws):
    print("3. pybullet on the base case (linear law, 40 kHz sensor), same run")
    law = laws["linear"]
    ref = cl.simulate_impact(grain, sensor, law, V0)
    for engine, run in (
        ("pybullet", lambda: bullet.drop_test(ImpactConfig(grain, sensor, law, {"velocity": V0}))),
        ("LAMMPS", lambda: drop_test(ImpactConfig(grain, sensor, law, {"velocity": V0}))),
    ):
        res = run()
        seconds = median_time(run, REPEATS)
        errors = ", ".join(
            f"{q} {e:+.2e}" for q, e in zip(QUANTITIES, _errors(res, ref), strict=True)
        )
        print(f"{engine:<9} dt {res.time_step:.3g} s, {seconds:.4f} s per impact; {errors}")
    print()


def _export(grain, laws):
    print("4. The LAMMPS export run in a user's deck (errors vs the fitted law's wall impact)")
    k_hertz = laws["hertz"].k_hertz
    fits = {
        "linear": (laws["linear"], {"stiffness": (1e5, "N/m"), "damping": (1.0, "N*s/m")}),
        "hertz_damped": (
            cl.laws.HertzDamped(
                k_hertz, analytic.tsuji_damping_coefficient(k_hertz, grain.mass, 0.5)
            ),
            {"effective_modulus": (21.6e6, "Pa"), "restitution": (0.5, "-")},
        ),
    }
    folder = Path(tempfile.mkdtemp())
    for name, (law, fitted) in fits.items():
        entry = {"stderr": 0.0, "ci95": [None, None], "identifiable": True}
        fit = {
            "law": name,
            "law_parameters": law.parameters(),
            "parameters": {k: {"value": v, "unit": u, **entry} for k, (v, u) in fitted.items()},
            "velocity [m/s]": V0,
            "grain": grain.to_dict(),
        }
        snippet = folder / f"{name}.lmp"
        snippet.write_text(export_dem(fit, "lammps"), encoding="utf-8")
        exact = wall_impact(law, grain.mass, V0)
        impact = realise_snippet(snippet, grain, V0, exact.contact_time)
        print(
            f"{name:<13} rebound {impact.restitution:.5f} (fitted law {exact.restitution:.5f}, "
            f"{impact.restitution / exact.restitution - 1:+.2e}), contact time "
            f"{impact.contact_time / exact.contact_time - 1:+.2e}, peak "
            f"{impact.peak_force / exact.peak_contact_force - 1:+.2e}, min force "
            f"{impact.min_force:.3g} N"
        )


def main():
    paper = cl.study.StudySetup.paper()  # the paper's grain and 40 kHz disc sensor
    grain, disc = paper.grain, paper.sensor
    sensors = {"rigid": cl.Sensor.rigid(), "40 kHz": disc}
    laws = _laws(grain)
    np.set_printoptions(precision=3)
    _impacts(grain, sensors, laws)
    _convergence(grain, disc, laws)
    _bullet(grain, disc, laws)
    _export(grain, laws)


if __name__ == "__main__":
    main()
