"""The paper's error study end to end: impacts per second serial and on 2 processes, and the
wall-clock time of the whole reproduction (2 800 impacts, Figures 5-12, tables, summary).
Rendering the figures takes about 2-3 s of it, in the main process.

Target: the whole study in at most 10 s on a 2-core machine (``--workers 2``). The machine
may be shared: each timing is the best of ``REPEATS`` runs.
"""

import tempfile
import time

from contactlab.study import StudySetup, run_grid
from contactlab.study.paper import PAPER_GRID, paper_study

REPEATS = 2
TARGET = 10.0
"""Seconds allowed for the whole study on 2 workers."""


def best_of(fn, repeats=REPEATS):
    best, out = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out


def main():
    setup = StudySetup.paper()
    grid = {
        "law.damping": PAPER_GRID.dampings,
        "grain.diameter": PAPER_GRID.sweep_diameters,
        "sensor.resonance": PAPER_GRID.resonances,
    }
    print("Paper study (Keska et al. 2021), linear contact on a disc sensor")
    for workers in (1, 2):
        seconds, result = best_of(lambda w=workers: run_grid(setup, grid, workers=w))
        n = len(result.impacts)
        print(
            f"  frequency sweep, {workers} worker(s): {n} impacts in {seconds:.2f} s = "
            f"{n / seconds:.0f} impacts/s ({1e3 * seconds / n * workers:.2f} ms per impact "
            "and worker)"
        )
    with tempfile.TemporaryDirectory() as out:
        seconds, study = best_of(lambda: paper_study(out, workers=2))
    n = study.summary()["impacts"]
    figures = sum(p.suffix == ".png" for p in study.files)
    verdict = "ok" if seconds <= TARGET else f"over the {TARGET:g} s target"
    print(
        f"  whole study, 2 workers: {n} impacts, {figures} figures (PNG + SVG), tables and "
        f"summary in {seconds:.2f} s ({verdict})"
    )


if __name__ == "__main__":
    main()
