"""What the contact-end search costs the damped-Hertz solvers (issue 25, docs/verification.md
finding 12), in several checkouts alternated in one run.

Figures, each in a fresh process per checkout (the numba caches warm):

* ``hertz_impacts`` on 1 500 damped-Hertz rows (the paper's grain, kH +-50 %, e = 0.5,
  2 m/s) on the 40 kHz disc sensor, and on 1 500 rows of ``bench_batch``'s 10-300 kHz
  sweep: impacts per second on one thread, best of three;
* one damped-Hertz ``simulate_impact`` at rtol 1e-6 (bench_solver's case): median [ms].

Usage: ``python benchmarks/bench_contact_end.py DIR [DIR ...] [--rounds N]``: each
``DIR`` a checkout (e.g. ``git archive <commit> | tar -x -C DIR``); the rounds alternate
the checkouts so they see the same machine load. Prints the load average beside them.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROWS = 1500


def _best_rate(impacts, frame):
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        impacts(frame, threads=1)
        times.append(time.perf_counter() - t0)
    return len(frame) / min(times)


def figures():
    """This checkout's figures, as a dict."""
    sys.path.insert(0, str(HERE))
    import bench_batch
    from timing import median_time

    import contactlab as cl
    from contactlab.batch import hertz_impacts

    sweep = bench_batch.hertz_frame(ROWS)
    disc = cl.study.StudySetup.paper().sensor  # the paper's 40 kHz disc
    at_40k = sweep.assign(**{"k1 [N/m]": disc.stiffness, "c1 [N*s/m]": disc.damping})
    at_40k["m1 [kg]"] = disc.mass
    hertz_impacts(sweep.iloc[:2], threads=1)  # load the compiled kernel
    out = {
        "batch 40 kHz [1/s]": _best_rate(hertz_impacts, at_40k),
        "batch 10-300 kHz [1/s]": _best_rate(hertz_impacts, sweep),
    }
    paper = cl.study.StudySetup.paper()
    # the measured tree's from_material: the grain's Material, or (before it) its numbers
    material = paper.grain.material()
    grain_data = (material,) if hasattr(cl.analytic, "Material") else tuple(material)
    tsuji = cl.laws.HertzDamped.from_material(*grain_data, 0.5, paper.grain.mass)

    def single():
        return cl.simulate_impact(paper.grain, paper.sensor, tsuji, 2.0, 500e-6, rtol=1e-6)

    out["single hertz [ms]"] = 1e3 * median_time(single, 30)
    return out


def _measure(tree):
    code = (
        f"import sys; sys.path.insert(0, {str(HERE)!r}); import bench_contact_end, json; "
        "print(json.dumps(bench_contact_end.figures()))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        env=dict(os.environ, PYTHONPATH=str(tree)),
        capture_output=True,
        text=True,
        check=True,
        cwd=tree,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trees", nargs="+", help="checkouts to compare")
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    runs = {tree: [] for tree in args.trees}
    print(f"load average at start: {os.getloadavg()}")
    for _ in range(args.rounds):
        for tree in args.trees:
            runs[tree].append(_measure(Path(tree).resolve()))
    print(f"load average at end:   {os.getloadavg()}; medians of {args.rounds} rounds")
    keys = list(runs[args.trees[0]][0])
    print(f"   {'checkout':40s} " + " ".join(f"{k:>24s}" for k in keys))
    for tree, got in runs.items():
        row = " ".join(f"{statistics.median(r[k] for r in got):24.4g}" for k in keys)
        print(f"   {tree[-40:]:40s} {row}")


if __name__ == "__main__":
    main()
