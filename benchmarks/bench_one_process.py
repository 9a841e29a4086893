"""Batch kernels of several checkouts timed in one process, interleaved (issue 25).

``bench_core.py --before`` times each checkout in its own process, one after the other:
on a shared machine the load moves between the processes and their ratios scatter by
10-15 %. Here each checkout's ``contactlab`` is copied under another package name (every
``contactlab`` in its sources renamed), all are imported into this process, and their
compiled batch loops (``solve_rows``) solve the same rows in turn, ``--rounds`` times;
CPU time of this process (``time.process_time``). Every round runs every checkout, so
the machine's load falls out of the ratios. It also checks that the checkouts' numbers
agree (largest relative difference against the first).

Usage::

    python benchmarks/bench_one_process.py --tree before=/tmp/before25 --tree now=. \
        [--law hertz|linear] [--rounds 7] [--workdir DIR]

The first ``--tree`` is the reference. A checkout from before the compiled core
(``d6916cc``: ``contactlab.batch.hertz_kernel`` / ``linear_kernel``) is run through its
own kernels. The copies compile into ``--workdir`` (a new temporary folder by default:
about a minute per checkout; a kept ``--workdir`` loads them from numba's cache the next
time: unchanged files are not rewritten). Every kernel is called once before the timed
rounds.
"""

import argparse
import importlib
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from bench_batch import hertz_frame, study_frame

ROWS = {"hertz": 3000, "linear": 30000}
"""Rows per round: about 0.4 s of one thread for either law."""


def _copy(tree, name, workdir):
    """``tree/contactlab`` copied to ``workdir/name`` with the package renamed.

    A file whose renamed text is already there is left alone: numba's cache is keyed on
    the source file's time stamp, so an unchanged checkout loads instead of compiling.
    Files no longer in ``tree`` are removed. Any change empties the copy's caches: a
    cached caller does not notice a changed callee.
    """
    source, target = Path(tree) / "contactlab", workdir / name
    wanted, changed = set(), False
    for path in source.rglob("*"):
        if "__pycache__" in path.parts or not path.is_file():
            continue
        copy = target / path.relative_to(source)
        wanted.add(copy)
        copy.parent.mkdir(parents=True, exist_ok=True)
        if path.suffix != ".py":
            shutil.copyfile(path, copy)
            continue
        text = re.sub(r"\bcontactlab\b", name, path.read_text())
        if not copy.exists() or copy.read_text() != text:
            copy.write_text(text)
            changed = True
    for copy in list(target.rglob("*.py")):
        if copy not in wanted and "__pycache__" not in copy.parts:
            copy.unlink()
            changed = True
    if changed:  # numba's cache of a caller does not notice a changed callee
        for cache in list(target.rglob("__pycache__")):
            shutil.rmtree(cache)


def _runner(name, law, columns, out, status):
    """A call solving every row with checkout ``name``'s batch loop."""
    p, q = (1.5, 0.25) if law == "hertz" else (1.0, 0.0)
    rtol = importlib.import_module(f"{name}.batch.hertz").DEFAULT_RTOL
    try:
        kernel = importlib.import_module(f"{name}.kernels.impact_loop").solve_rows
        return lambda: kernel(*columns, p, q, rtol, out, status)
    except ModuleNotFoundError:  # before the compiled core: one kernel per law
        old = importlib.import_module(f"{name}.batch.{law}_kernel").solve_rows
        if law == "hertz":
            return lambda: old(*columns, rtol, out, status)
        return lambda: old(*columns, out, status)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", action="append", required=True, help="NAME=DIR, repeated")
    parser.add_argument("--law", choices=sorted(ROWS), default="hertz")
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--workdir", type=Path, default=None)
    args = parser.parse_args()
    workdir = args.workdir or Path(tempfile.mkdtemp(prefix="one_process_"))
    workdir.mkdir(parents=True, exist_ok=True)
    sys.path.insert(0, str(workdir))
    trees = [item.split("=", 1) for item in args.tree]
    rows = ROWS[args.law]
    frame = (hertz_frame if args.law == "hertz" else study_frame)(rows).to_numpy()
    columns = [np.ascontiguousarray(frame[:, i]) for i in range(7)]
    out, status = np.empty((rows, 6)), np.empty(rows, np.int64)
    runners, results = {}, {}
    for label, tree in trees:
        name = f"cl_{label}"
        _copy(tree, name, workdir)
        runners[label] = _runner(name, args.law, columns, out, status)
        runners[label]()  # compile or load
        results[label] = out.copy()
    reference = trees[0][0]
    for label in runners:
        rel = np.abs(results[label] - results[reference]) / np.abs(results[reference])
        print(f"{label}: largest relative difference from {reference}: {np.nanmax(rel):.1e}")
    times = {label: [] for label in runners}
    for _ in range(args.rounds):
        for label, run in runners.items():
            start = time.process_time()
            run()
            times[label].append(time.process_time() - start)
    base = np.array(times[reference])
    print(f"\n{args.law}, {rows} rows, {args.rounds} rounds, CPU time per row:")
    for label, spent in times.items():
        spent = np.array(spent)
        print(
            f"   {label:10s} min {spent.min() / rows * 1e6:7.2f} us, median "
            f"{np.median(spent) / rows * 1e6:7.2f} us, time / {reference}: min "
            f"{spent.min() / base.min():.3f}, median {np.median(spent) / np.median(base):.3f}"
        )


if __name__ == "__main__":
    main()
