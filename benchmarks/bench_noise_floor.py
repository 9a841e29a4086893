"""Benchmark: the running baseline's levels computed once per record in the campaign's
noise floor (issue 22).

On ``bench_realistic.py --speed``'s record (1.5 million samples at 5 MHz, every effect),
:func:`dem_check.campaign.noise.noise_floor` as it is (the levels of the record and of
its smoothed record computed once each, :mod:`contactlab._block_levels`) against the
reference of the same run: each of its five running baselines computed from the samples
(:func:`contactlab.signals.running_baseline`, :func:`contactlab.signals.quiet_window`),
as before; and the levels once with the residual's numpy code
(``tests/support/levels_reference.py``) in place of its compiled loop
(``contactlab/kernels/levels.py``, session 17). Prints that their results are the same to
the last bit, their CPU times (best of ``--repeats``, alternated) and the ratios.

Run: ``.venv/bin/python benchmarks/bench_noise_floor.py [--repeats 3]``
"""

import argparse
import os
import sys
import time
from pathlib import Path

import bench_realistic  # beside this script: its speed record
import numpy as np

import contactlab._block_levels as block_levels_module
from contactlab import signals
from contactlab._block_levels import BlockLevels, block_levels
from dem_check.campaign import noise

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
from levels_reference import numpy_residual  # the residual's numpy code, the test's

_SHARED = noise.block_levels, signals.levels_baseline, signals.levels_quiet_window
"""What ``noise_floor`` calls; the reference patches them and puts them back."""


def _unshared(y, width):
    """Levels not computed: the reference's baselines compute them from ``y`` each time."""
    return BlockLevels(y, width, None, None, None, None)


def _each_time(levels, exclude=None, head=0):
    """``running_baseline(y, width, exclude, head)``: the levels computed from ``y``."""
    return _SHARED[1](block_levels(levels.y, levels.width), exclude, head)


def _quiet_each_time(t, levels):
    """``quiet_window(t, y, width)``: the levels computed from ``y``."""
    return _SHARED[2](t, block_levels(levels.y, levels.width))


def _reference(trace, sensor):
    """``noise_floor`` with every running baseline computed from its samples."""
    noise.block_levels, signals.levels_baseline = _unshared, _each_time
    signals.levels_quiet_window = _quiet_each_time
    try:
        return noise.noise_floor(trace, sensor)
    finally:
        noise.block_levels, signals.levels_baseline, signals.levels_quiet_window = _SHARED


def _numpy_residual(trace, sensor):
    """``noise_floor`` with the residual's numpy code instead of its compiled loop."""
    compiled = block_levels_module.nearest_residual
    block_levels_module.nearest_residual = numpy_residual
    try:
        return noise.noise_floor(trace, sensor)
    finally:
        block_levels_module.nearest_residual = compiled


def _same(a, b):
    """Whether two ``noise_floor`` results are equal to the last bit."""
    floor_a, *traces_a, noise_a = a
    floor_b, *traces_b, noise_b = b
    pairs = zip(traces_a, traces_b, strict=True)
    values = all(np.array_equal(x.values, y.values, equal_nan=True) for x, y in pairs)
    return floor_a == floor_b and values and np.array_equal(noise_a, noise_b)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    repeats = parser.parse_args().repeats
    _, sensor, _ = bench_realistic.hard()
    trace = bench_realistic.speed_record().trace
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    ways = {
        "levels once": noise.noise_floor,
        "each baseline from its samples": _reference,
        "levels once, the residual in numpy": _numpy_residual,
    }
    times, results = {name: [] for name in ways}, {}
    for _ in range(repeats):
        for name, way in ways.items():
            cpu = time.process_time()
            results[name] = way(trace, sensor)
            times[name].append(time.process_time() - cpu)
    first, *others = results.values()
    print(f"same results to the last bit: {all(_same(first, other) for other in others)}")
    for name, spent in times.items():
        print(
            f"{name}: {min(spent):.3f} s of CPU (best of {repeats}; all: "
            f"{', '.join(f'{s:.3f}' for s in spent)})"
        )
    best = {name: min(spent) for name, spent in times.items()}
    for name in list(ways)[1:]:
        print(f"ratio ({name} over levels once): {best[name] / best['levels once']:.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
