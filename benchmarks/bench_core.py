"""The compiled core (issue 25): one impact with its metrics, and every solver figure
before and after a change, measured in one run.

1. One linear impact (the paper's grain, k2 = 1e5 N/m, c2 = 1 N*s/m, v0 = 2 m/s, the
   40 kHz disc sensor, 500 us window, 20 001 samples) with every headline number;
   target median <= 0.6 ms. Beside it, in the same run, the same impact with its numbers
   read the way ``ImpactResult`` reads them without the compiled loop's readings
   (refined from the output grid on the dense solution: the path before the core read
   them), and the largest relative difference between the two readings.
2. ``--before DIR``: the figures of ``bench_solver.py`` and ``bench_batch.py`` (single
   linear and damped-Hertz impacts with and without metrics; batch throughput on one
   thread and on every core; ``simulate_impact`` in a loop) for the code in ``DIR`` (a
   checkout of the code before the change, e.g. ``git archive main | tar -x -C DIR``)
   and for this checkout, each measured in a fresh process, alternated ``--rounds``
   times so both see the same machine load; the table prints medians over the rounds
   and the ratio after / before of times (lower is better) and rates (higher is better).

Usage: ``python benchmarks/bench_core.py [--before DIR] [--rounds N]``. The compiled
kernels of both checkouts should be in their numba caches (``contactlab warm-up``), or
the first round pays the compile.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from bench_solver import REPEATS
from timing import median_time

HERE = Path(__file__).resolve().parent
WINDOW, SAMPLES = 500e-6, 20001
HEADLINE = (
    "contact_time",
    "peak_contact_force",
    "sensor_response_time",
    "peak_sensor_force",
    "restitution",
    "impulse",
)


def _setup():
    import contactlab as cl

    paper = cl.study.StudySetup.paper()  # the paper's grain and 40 kHz disc sensor
    return cl, paper.grain, paper.sensor


def _read(res):
    """Every headline number of a result (they are read lazily)."""
    return [getattr(res, name) for name in HEADLINE]


def single_with_metrics():
    """Part 1: one linear impact with its metrics, core readings against grid readings."""
    cl, grain, sensor = _setup()
    law = cl.laws.LinearViscoelastic(1e5, 1.0)

    def solve():
        return cl.simulate_impact(grain, sensor, law, 2.0, WINDOW)

    def core():
        return _read(solve())

    def grid():
        return _read(solve().grid_reading())

    t_core, t_grid = median_time(core, REPEATS), median_time(grid, REPEATS)
    print(f"1. One linear impact, {SAMPLES} samples, with its {len(HEADLINE)} headline numbers")
    print(f"   read by the compiled loop  {t_core * 1e3:7.3f} ms   (target <= 0.6 ms)")
    print(f"   read from the grid         {t_grid * 1e3:7.3f} ms   ratio {t_grid / t_core:5.2f}x")
    worst = max(abs(a / b - 1.0) for a, b in zip(core(), grid(), strict=True))
    print(f"   largest relative difference of the two readings: {worst:.1e}")


def figures():
    """Every figure of bench_solver and bench_batch's throughput, as a dict (this tree).

    ``bench_batch`` (its frames, loop and rate) is the measured tree's own when the tree
    has one (``_measure`` puts its ``benchmarks/`` first): its loop reads the results
    through that tree's API.
    """
    import bench_batch
    import numpy as np

    from contactlab.batch import hertz_impacts, linear_impacts

    cl, grain, sensor = _setup()
    out = {}
    linear = cl.laws.LinearViscoelastic(1e5, 1.0)
    # the measured tree's from_material: the grain's Material, or (before it) its numbers
    material = grain.material()
    grain_data = (material,) if hasattr(cl.analytic, "Material") else tuple(material)
    tsuji = cl.laws.HertzDamped.from_material(*grain_data, 0.5, grain.mass)
    for name, law, options in (("linear", linear, {}), ("hertz", tsuji, {"rtol": 1e-6})):

        def run(law=law, options=options):
            return cl.simulate_impact(grain, sensor, law, 2.0, WINDOW, **options)

        out[f"single {name} [ms]"] = 1e3 * median_time(run, REPEATS)
        out[f"single {name} + metrics [ms]"] = 1e3 * median_time(
            lambda run=run: _read(run()), REPEATS
        )
    frames = {
        "linear": (
            linear_impacts,
            bench_batch.study_frame(bench_batch.ROWS),
            cl.laws.LinearViscoelastic,
        ),
        "hertz": (
            hertz_impacts,
            bench_batch.hertz_frame(bench_batch.HERTZ_ROWS),
            cl.laws.HertzDamped,
        ),
    }
    for name, (impacts, frame, law) in frames.items():
        impacts(frame.iloc[:2])
        out[f"batch {name} 1 thread [1/s]"] = bench_batch._rate(impacts, frame, 1)[0]
        out[f"batch {name} {os.cpu_count()} threads [1/s]"] = bench_batch._rate(
            impacts, frame, None
        )[0]
        subset = frame.iloc[:: len(frame) // bench_batch.LOOP_ROWS]
        t0 = time.perf_counter()
        bench_batch.loop(subset, law)
        out[f"loop {name} [1/s]"] = len(subset) / (time.perf_counter() - t0)
    np.seterr(all="ignore")
    return out


def _measure(tree):
    env = dict(os.environ, PYTHONPATH=str(tree))
    code = (
        f"import sys; sys.path.insert(0, {str(HERE)!r}); import bench_core, json; "
        f"sys.path.insert(0, {str(tree / 'benchmarks')!r}); "
        "print(json.dumps(bench_core.figures()))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True, cwd=tree
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def before_after(before, rounds):
    """Part 2: the figures of ``before`` and of this checkout, alternated."""
    trees = {"before": Path(before).resolve(), "after": HERE.parent}
    runs = {name: [] for name in trees}
    for _ in range(rounds):
        for name, tree in trees.items():
            runs[name].append(_measure(tree))
    print(
        f"\n2. Before ({trees['before']}) and after ({trees['after']}), medians of {rounds} rounds"
    )
    print(f"   {'figure':34s} {'before':>10s} {'after':>10s}   after/before")
    for key in runs["before"][0]:
        b = statistics.median(r[key] for r in runs["before"])
        a = statistics.median(r[key] for r in runs["after"])
        better = "lower is better" if key.endswith("[ms]") else "higher is better"
        print(f"   {key:34s} {b:10.4g} {a:10.4g}   {a / b:6.2f}  ({better})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="a checkout of the code before the change")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    single_with_metrics()
    if args.before:
        before_after(args.before, args.rounds)


if __name__ == "__main__":
    main()
