"""Kratos DEM as an engine: time per impact against LAMMPS, the benchmark with both engines,
and the attribution of Kratos' test-4 differences rule by rule (issue 27).

1. Every law Kratos holds (linear, Hertz, damped Hertz) at the paper's scale, on a rigid
   plate and on the 40 kHz disc sensor, at the default step: median wall time of one
   whole ``drop_test`` in Kratos and in LAMMPS (same run, same cases), their ratio, and
   Kratos' relative errors against the exact solver. Target: < 1 s per Kratos impact.
2. ``contactlab benchmark chung-ooi`` alone, with LAMMPS, and with LAMMPS and Kratos
   (``--engines lammps,kratos``): wall time of each. Target: < 5 min with both engines.
3. Test 4 (aluminium oxide, 3.9 m/s, mu 0.092, 5-85 deg): Kratos against contactlab with
   each of Kratos' rules switched alone (the package's attribution, as the benchmark
   command runs it); with ``--damped`` the same at Kratos' own e = 0.98, where the tied
   tangential damping and the Coulomb cap act. ``--figure FOLDER`` also draws it.
"""

import math
import sys
import tempfile
import time
from pathlib import Path

from timing import median_time

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.benchmarks.chung_ooi.attribution import attribute, markdown
from contactlab.benchmarks.chung_ooi.cases import CASES
from contactlab.benchmarks.chung_ooi.figures import save_attribution_figure
from contactlab.benchmarks.chung_ooi.grading import grain, rebound
from contactlab.benchmarks.chung_ooi.oblique import ANGLES
from contactlab.cli import _benchmark_engines
from contactlab.config import ImpactConfig
from contactlab.solver import wall_impact
from contactlab.solver.conventions import DEM_CONVENTIONS
from dem_check.engines import kratos, lammps

REPEATS = 3
TARGET = 1.0  # [s] per Kratos impact
BENCHMARK_TARGET = 300.0  # [s] the benchmark with both engines
V0 = 2.0  # [m/s]
QUANTITIES = ("restitution", "contact_time", "peak_contact_force", "peak_sensor_force")


def drop_tests():
    body = cl.Grain(diameter=5e-3, density=765.0)
    k_hertz = analytic.hertz_stiffness(21.6e6, body.radius)
    laws = {
        "linear": cl.laws.LinearViscoelastic(1e5, 1.0),
        "hertz": cl.laws.Hertz(k_hertz),
        "hertz_damped": cl.laws.HertzDamped.from_material(
            cl.analytic.Material(21.6e6, 0.2, body.radius), 0.5, body.mass
        ),
    }
    sensors = {
        "rigid": cl.Sensor.rigid(),
        "40 kHz": cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02),
    }
    print("| law | sensor | Kratos [s] | LAMMPS [s] | Kratos/LAMMPS | worst error vs exact |")
    print("|---|---|---|---|---|---|")
    worst = 0.0
    for law_name, law in laws.items():
        for sensor_name, sensor in sensors.items():
            case = ImpactConfig(body, sensor, law, {"velocity": V0})
            t_kratos = median_time(lambda case=case: kratos.drop_test(case), REPEATS)
            t_lammps = median_time(lambda case=case: lammps.drop_test(case), REPEATS)
            res = kratos.drop_test(case)
            ref = cl.simulate_impact(body, sensor, law, V0)
            error = max(abs(getattr(res, q) / getattr(ref, q) - 1.0) for q in QUANTITIES)
            worst = max(worst, t_kratos)
            print(
                f"| {law_name} | {sensor_name} | {t_kratos:.3f} | {t_lammps:.3f} | "
                f"{t_kratos / t_lammps:.2f} | {error:.1e} |"
            )
    verdict = "met" if worst < TARGET else "MISSED"
    print(f"slowest Kratos drop test {worst:.3f} s: target < {TARGET} s {verdict}\n")


def benchmark_times():
    rows = []
    with tempfile.TemporaryDirectory() as out:
        for label, kwargs in (
            ("contactlab alone", {}),
            ("with LAMMPS (tests 4-6)", {"lammps": lammps.lammps_oblique}),
            (
                "with LAMMPS and Kratos",
                {
                    "lammps": lammps.lammps_oblique,
                    "engines": _benchmark_engines(["lammps", "kratos"]),
                },
            ),
        ):
            clock = time.perf_counter()
            report = run_chung_ooi(out, **kwargs)
            wall = time.perf_counter() - clock
            failed = sum(not r["passed"] for r in report["rows"])
            rows.append((label, wall, len(report["rows"]), failed))
    print("| benchmark | wall [s] | rows | failed |")
    print("|---|---|---|---|")
    for label, wall, count, failed in rows:
        print(f"| {label} | {wall:.1f} | {count} | {failed} |")
    both = rows[-1][1]
    verdict = "met" if both < BENCHMARK_TARGET else "MISSED"
    print(
        f"both engines {both:.1f} s = {both / rows[1][1]:.2f} x the LAMMPS run: target "
        f"< {BENCHMARK_TARGET:.0f} s {verdict}\n"
    )


def attribution(restitution=1.0, figure=None, steps=None):
    """Test 4 at restitution ``e``, alumina: Kratos (at ``steps`` per contact; default
    its own, 2000) against contactlab with each of its rules switched
    (:mod:`contactlab.benchmarks.chung_ooi.attribution`)."""
    case = next(c for c in CASES if c.number == 4)
    material = case.materials[0]
    body = grain(material, case.inputs["radius [m]"])
    mu, speed = case.inputs["friction [-]"], case.inputs["speed [m/s]"]
    normal = cl.laws.Hertz.from_material(body.material())
    if restitution < 1.0:
        damping = analytic.tsuji_damping_coefficient(
            normal.k_hertz, body.mass, restitution, "force"
        )
        normal = cl.laws.HertzDamped(normal.k_hertz, damping)
    mindlin = cl.laws.Mindlin.from_material(body.material(), mu)
    rebounds = []
    for degrees in ANGLES:
        angle = math.radians(degrees)
        step = None
        if steps is not None:
            step = wall_impact(normal, body.mass, speed * math.cos(angle)).contact_time / steps
        res = kratos.kratos_oblique(body, normal, mindlin, speed, angle, time_step=step)
        rebounds.append(rebound(res))
    found = attribute(
        body,
        material.name,
        normal,
        mindlin,
        speed,
        ANGLES,
        "kratos",
        rebounds,
        DEM_CONVENTIONS["kratos"],
    )
    at = "its own step" if steps is None else f"{steps} steps per contact"
    print(f"Test 4, e = {restitution:g}, {material.name}, Kratos at {at}: worst difference")
    print(markdown([found]))
    print()
    if figure is not None:
        Path(figure).mkdir(parents=True, exist_ok=True)
        print(f"figure: {save_attribution_figure(case, material.name, [found], figure)}")


if __name__ == "__main__":
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    if "--attribution-only" not in sys.argv:
        drop_tests()
        benchmark_times()
    attribution(figure=figure)
    if "--damped" in sys.argv:
        attribution(0.98, figure=figure and str(Path(figure) / "damped"))
        attribution(0.98, figure=figure and str(Path(figure) / "damped_fine"), steps=8000)
