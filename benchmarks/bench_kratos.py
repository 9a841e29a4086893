"""Kratos DEM as an engine: time per impact against LAMMPS, the benchmark with both engines,
and the attribution of Kratos' test-4 differences rule by rule (issue 27).

1. Every law Kratos holds (linear, Hertz, damped Hertz) at the paper's scale, on a rigid
   plate and on the 40 kHz disc sensor, at the default step: median wall time of one
   whole ``drop_test`` in Kratos and in LAMMPS (same run, same cases), their ratio, and
   Kratos' relative errors against the exact solver. Target: < 1 s per Kratos impact.
2. ``contactlab benchmark chung-ooi`` alone, with LAMMPS, and with LAMMPS and Kratos
   (``--engines lammps,kratos``): wall time of each. Target: < 5 min with both engines.
3. Test 4 (aluminium oxide, 3.9 m/s, mu 0.092, 5-85 deg): vt'/vt and the spin of Kratos,
   of its replica with one rule switched to contactlab's at a time (lever arm R; history
   incremental without rescaling; history total), contactlab's two Mindlin forms and
   LAMMPS' (``benchmarks/kratos_rules.py``); with ``--damped`` the same at Kratos' own
   e = 0.98, where the tied tangential damping acts. Printed as a Markdown table (the one
   in ``docs/dem-conventions.md``); ``--figure PATH`` also draws it (vt'/vt and spin
   against the angle, one curve per rule switched).
"""

import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.benchmarks.chung_ooi.cases import CASES
from contactlab.benchmarks.chung_ooi.grading import grain
from contactlab.benchmarks.chung_ooi.oblique import ANGLES
from contactlab.cli import _benchmark_engines
from contactlab.solver import wall_impact
from dem_check.engines import kratos, lammps
from dem_check.engines.kratos.laws import hertz_gamma

sys.path.insert(0, str(Path(__file__).parent))
from kratos_rules import KRATOS, Rules, replica

REPEATS = 3
TARGET = 1.0  # [s] per Kratos impact
BENCHMARK_TARGET = 300.0  # [s] the benchmark with both engines
V0 = 2.0  # [m/s]
QUANTITIES = ("restitution", "contact_time", "peak_contact_force", "peak_sensor_force")


def _median_time(fn):
    fn()  # warm-up (imports, first set-up)
    times = []
    for _ in range(REPEATS):
        clock = time.perf_counter()
        fn()
        times.append(time.perf_counter() - clock)
    return statistics.median(times)


def drop_tests():
    body = cl.Grain(diameter=5e-3, density=765.0)
    k_hertz = analytic.hertz_stiffness(21.6e6, body.radius)
    laws = {
        "linear": cl.laws.LinearViscoelastic(1e5, 1.0),
        "hertz": cl.laws.Hertz(k_hertz),
        "hertz_damped": cl.laws.HertzDamped.from_material(21.6e6, 0.2, body.radius, 0.5, body.mass),
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
            case = (body, sensor, law, V0)
            t_kratos = _median_time(lambda case=case: kratos.drop_test(*case))
            t_lammps = _median_time(lambda case=case: lammps.drop_test(*case))
            res = kratos.drop_test(body, sensor, law, V0)
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


def attribution(restitution=1.0, figure=None):
    case = next(c for c in CASES if c.number == 4)
    body = grain(case.materials[0], case.inputs["radius [m]"])
    mu, speed = case.inputs["friction [-]"], case.inputs["speed [m/s]"]
    normal = cl.laws.Hertz.from_material(*body.material())
    if restitution < 1.0:
        damping = analytic.tsuji_damping_coefficient(
            normal.k_hertz, body.mass, restitution, "force"
        )
        normal = cl.laws.HertzDamped(normal.k_hertz, damping)
    gamma = hertz_gamma(normal, body.mass) if restitution < 1.0 else 0.0
    mindlin = {
        history: cl.laws.Mindlin.from_material(*body.material(), mu, history=history)
        for history in ("total", "incremental")
    }
    variants = {
        "Kratos": KRATOS,
        "arm R": Rules(arm="R"),
        "no rescale": Rules(history="incremental"),
        "total history": Rules(history="total"),
        "no tangential damping": Rules(damping="none"),
    }
    curves = {name: [] for name in [*variants, "contactlab total", "contactlab incremental"]}
    curves["LAMMPS mindlin/force"] = []
    print(f"Test 4, e = {restitution:g}: vt'/vt and spin [rad/s]")
    heads = [*variants, "contactlab total", "contactlab incremental", "LAMMPS mindlin/force"]
    print("| angle | " + " | ".join(heads) + " |")
    print("|---" * (len(heads) + 1) + "|")
    for degrees in ANGLES:
        angle = math.radians(degrees)
        vt = speed * math.sin(angle)
        dt = wall_impact(normal, body.mass, speed * math.cos(angle)).contact_time / 2000
        k_m = mindlin["total"].k_mindlin
        args = (body.mass, body.radius, normal.k_hertz, k_m, mu, gamma, speed, angle, 0.0, dt)
        cells = [replica(*args, chosen) for chosen in variants.values()]
        for history in ("total", "incremental"):
            cells.append(
                cl.simulate_oblique(body, cl.Sensor.rigid(), normal, mindlin[history], speed, angle)
            )
        cells.append(lammps.lammps_oblique(body, normal, mindlin["incremental"], speed, angle))
        text = [f"{c.tangential_velocity / vt:.4f} / {c.angular_velocity:.1f}" for c in cells]
        for name, cell in zip(curves, cells, strict=True):
            curves[name].append((cell.tangential_velocity / vt, cell.angular_velocity))
        print(f"| {degrees} | " + " | ".join(text) + " |")
    print()
    if figure is not None:
        _draw(curves, restitution, figure)


def _draw(curves, restitution, path):
    """vt'/vt and spin against the angle, one curve per rule switched (test 4)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.2), layout="constrained")
    kratos = np.array(curves["Kratos"])
    for name, values in curves.items():
        if name == "Kratos":
            continue
        values = np.array(values)
        style = "--" if name.startswith(("contactlab", "LAMMPS")) else "o-"
        axes[0].plot(ANGLES, values[:, 0] - kratos[:, 0], style, ms=3, label=name)
        axes[1].plot(ANGLES, values[:, 1] / kratos[:, 1] - 1.0, style, ms=3, label=name)
    axes[0].set_ylabel("vt'/vt minus Kratos' [-]")
    axes[1].set_ylabel("spin over Kratos' - 1 [-]")
    for ax in axes:
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("incidence angle [deg]")
    axes[0].legend(frameon=False, fontsize=7)
    fig.suptitle(
        f"Chung & Ooi test 4 (e = {restitution:g}): one of Kratos' rules switched, or "
        "another code, against Kratos",
        fontsize=9,
    )
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"figure: {path}")


if __name__ == "__main__":
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    if "--attribution-only" not in sys.argv:
        drop_tests()
        benchmark_times()
    attribution(figure=figure)
    if "--damped" in sys.argv:
        attribution(0.98)
