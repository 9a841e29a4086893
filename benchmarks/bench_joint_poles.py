"""Benchmark: the joint pencil's structure poles, before and after their refinement.

Windows built in closed form (``tests/support/plate_windows.py``, the test's), not by
the record model: eight windows of ringing after a hit, of the lengths found between the
hits and bounces of ``bench_realistic.py --accuracy`` (1.3-3.8 ms), each holding the 40 kHz sensor's
ringing, an offset, the 730 Hz (damping ratio 0.01) and 1890 Hz (0.02) plate modes at
0.015-0.03 with their own amplitudes and phases, and noise: none, white (0.03), 1/f
(0.01; a sum of first-order processes with corners 10 Hz-100 kHz) or both, at 1 and
2 MHz. ``contactlab.inverse.crosstalk.joint_structure_modes`` with ``refine=False`` (the
pencil) and ``refine=True`` (variable projection); a mode counts as found when a
candidate within 30 % of it is significant after half of the windows. Prints, per
case, the largest and median relative frequency error of each mode and how often it was
missed (``docs/campaign.md``, "Crosstalk").

Run: ``.venv/bin/python benchmarks/bench_joint_poles.py [--seeds N]``
"""

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

from contactlab.inverse.crosstalk import joint_structure_modes

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
# the test's windows, so that the benchmark measures its case on more seeds and rates
from plate_windows import PLATE, SENSOR, mode_error, plate_windows

NOISES = {"none": (0.0, 0.0), "white": (0.03, 0.0), "1/f": (0.0, 0.01), "both": (0.03, 0.01)}
"""White and 1/f noise standard deviations [N] of each case."""


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=12)
    seeds = parser.parse_args().seeds
    print(f"load average {os.getloadavg()[0]:.1f}; {seeds} seeds; errors in %: largest / median")
    for rate in (1e6, 2e6):
        for name, (white, flicker) in NOISES.items():
            errors = {False: [], True: []}
            seconds = {False: 0.0, True: 0.0}
            for seed in range(seeds):
                data = plate_windows(seed, rate, white, flicker)
                for refine in errors:
                    started = time.perf_counter()
                    found = joint_structure_modes(data, SENSOR, refine=refine)
                    seconds[refine] += time.perf_counter() - started
                    errors[refine].append([mode_error(*found, f) for f, _ in PLATE])
            line = f"{rate / 1e6:.0f} MHz {name:6s}"
            for refine, label in ((False, "pencil"), (True, "refined")):
                e = 100 * np.array(errors[refine])
                parts = []
                for k, (frequency, _) in enumerate(PLATE):
                    column = e[:, k]
                    ok = column[np.isfinite(column)]
                    top = f"{ok.max():.1f} / {np.median(ok):.1f}" if ok.size else "-"
                    parts.append(f"{frequency:.0f} Hz {top} (missed {column.size - ok.size})")
                line += f" | {label}: " + ", ".join(parts) + f" [{seconds[refine]:.1f} s]"
            print(line, flush=True)


if __name__ == "__main__":
    main()
