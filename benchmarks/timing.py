"""Wall times the benchmark scripts share.

The machine is shared: a figure is the median of several calls after one warm-up call
(imports, compilation, caches), not a single run; the fastest call is the best estimate
of the cost on a quiet machine.
"""

import statistics
import time


def wall_times(fn, repeats):
    """Wall times [s] of ``repeats`` calls of ``fn()``, after one warm-up call."""
    fn()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return times


def median_time(fn, repeats):
    """Median wall time [s] of ``repeats`` calls of ``fn()``, after one warm-up call."""
    return statistics.median(wall_times(fn, repeats))
