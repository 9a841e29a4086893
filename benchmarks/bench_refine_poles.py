"""Benchmark: the joint poles' refinement with the windows stacked, against the loop over
the windows it replaced (session 17), timed in the same run.

``contactlab.inverse.crosstalk.joint_structure_modes`` on the test's closed-form windows
of plate ringing (``tests/support/plate_windows.py``: the 40 kHz sensor, the 730 and
1890 Hz plate modes, white and 1/f noise), five records of eight windows at 1 MHz put
together (40 windows, as after the 20 hits and bounces of ``bench_realistic.py --speed``),
with ``ringdown._Projection`` as it is and replaced by the loop
(``tests/support/projection_reference.py``), alternated, best of three. Prints the CPU
times, their ratio and the largest relative difference of the refined poles
(``docs/campaign.md``, "Speed").

Run: ``.venv/bin/python benchmarks/bench_refine_poles.py``
"""

import os
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

import contactlab.inverse.ringdown as ringdown
from contactlab.inverse.crosstalk import joint_structure_modes

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
from plate_windows import SENSOR, plate_windows  # the test's windows
from projection_reference import LoopProjection

STACKED = ringdown._Projection


def timed(projection, windows):
    """CPU time [s] of the refinement with ``projection`` and the modes it found."""
    ringdown._Projection = projection
    try:
        started = time.process_time()
        found = joint_structure_modes(windows, SENSOR, refine=True)
        return time.process_time() - started, np.asarray(found[0], dtype=complex)
    finally:
        ringdown._Projection = STACKED


def main():
    windows = [w for seed in range(5) for w in plate_windows(seed, 1e6, 0.03, 0.01)]
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min); {len(windows)} windows")
    best = {STACKED: np.inf, LoopProjection: np.inf}
    found = {}
    with threadpool_limits(1):  # as run_campaign works
        for _ in range(3):
            for projection in best:
                seconds, found[projection] = timed(projection, windows)
                best[projection] = min(best[projection], seconds)
    difference = np.max(
        np.abs(found[STACKED] - found[LoopProjection]) / np.abs(found[LoopProjection])
    )
    print(f"stacked windows: {best[STACKED]:.3f} s of CPU; loop: {best[LoopProjection]:.3f} s")
    print(f"ratio (loop over stacked): {best[LoopProjection] / best[STACKED]:.2f}")
    print(f"largest relative difference of the poles: {difference:.1e}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
