"""Time the pybullet drop bench: ms per impact, engine steps per second, Python overhead.

The base case (preset fig6 grain and law on the paper's 40 kHz disc sensor) and the
presets fig5 and fig6 at dt = 1e-7 s. Medians of several runs (this machine is shared).
The bare engine step cost is measured in the same run on the same scene: a loop of
``stepSimulation`` only, over as many steps as an impact takes (without the sensor
spring the plate is pushed away freely, so the contact share of the steps is similar,
not identical). Target: <= 30 ms per impact of the base case.
"""

import statistics
import time

import pybullet as pb

import contactlab as cl
from contactlab.config import ImpactConfig, load_preset
from dem_check.engines.bullet import drop_scene, drop_test

REPEATS = 7
TIME_STEP = 1e-7  # [s]
TARGET = 30e-3  # [s] per impact


def _median(fn):
    fn()  # warm-up
    return statistics.median(fn() for _ in range(REPEATS))


def _impact(grain, sensor, law):
    """Wall time of one whole drop_test [s] and its engine-step wall time and step count."""
    clock = time.perf_counter()
    res = drop_test(ImpactConfig(grain, sensor, law, {"velocity": 2.0}), time_step=TIME_STEP)
    total = time.perf_counter() - clock
    return total, res.metadata["wall_time [s]"], res.metadata["steps"]


def _bare_steps(grain, sensor, law, steps):
    """Wall time [s] of ``steps`` bare engine steps on the same scene."""
    scene = drop_scene(grain, sensor, law, 2.0, TIME_STEP)
    client = pb.connect(pb.DIRECT)
    try:
        scene.build(client)
        step = pb.stepSimulation
        clock = time.perf_counter()
        for _ in range(steps):
            step(physicsClientId=client)
        return time.perf_counter() - clock
    finally:
        pb.disconnect(client)


def main():
    base = load_preset("fig6")
    cases = {
        "base case (fig6 law, 40 kHz disc)": (
            base.grain,
            cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02),
            base.law,
        ),
        "preset fig5 (k2 = 1e4, 40 kHz)": (
            load_preset("fig5").grain,
            load_preset("fig5").sensor,
            load_preset("fig5").law,
        ),
        "preset fig6 (k2 = 1e5, 20 kHz)": (base.grain, base.sensor, base.law),
    }
    print(f"pybullet drop bench at dt = {TIME_STEP:g} s, median of {REPEATS} runs")
    header = "case", "steps", "ms/impact", "steps/s", "us/step", "bare us/step", "overhead"
    print(f"  {header[0]:36s}" + "".join(f"{h:>14s}" for h in header[1:]))
    verdicts = []
    for name, (grain, sensor, law) in cases.items():
        runs = [_impact(grain, sensor, law) for _ in range(REPEATS + 1)][1:]
        total = statistics.median(r[0] for r in runs)
        stepping = statistics.median(r[1] for r in runs)
        steps = runs[0][2]
        bare = _median(lambda g=grain, s=sensor, law=law, n=steps: _bare_steps(g, s, law, n))
        per_step, bare_step = stepping / steps, bare / steps
        overhead = 1.0 - bare_step / per_step
        print(
            f"  {name:36s}{steps:14d}{total * 1e3:14.2f}{steps / stepping:14.0f}"
            f"{per_step * 1e6:14.2f}{bare_step * 1e6:14.2f}{overhead:14.0%}"
        )
        verdicts.append((name, total))
    base_total = verdicts[0][1]
    verdict = "met" if base_total <= TARGET else "NOT met"
    print(
        f"target {TARGET * 1e3:g} ms per impact of the base case: {verdict} "
        f"({base_total * 1e3:.1f} ms); 'overhead' is the Python share of a step "
        "(state reads, joint force, bookkeeping)"
    )


if __name__ == "__main__":
    main()
