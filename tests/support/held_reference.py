"""The lobe model's unit signal as it was written before it was compiled
(:mod:`contactlab.kernels.held_force`): ``numpy.interp`` and ``scipy.signal.lfilter``.
The test holds the kernel to it bit for bit; ``benchmarks/bench_held_force.py`` times
the onset fits with it."""

import numpy as np
from scipy import signal

__all__ = ["numpy_unit"]


def numpy_unit(step, count, tau, u, h, b, a):
    """:func:`contactlab.kernels.held_force.held_signal` with numpy and scipy: the
    times [s] and the filtered unit force [-] on ``k step``, ``k = -1 ... count - 1``."""
    s = np.arange(-1, count) * step
    force = np.interp((s - 0.5 * step) / tau, u, h, left=0.0, right=0.0)
    return s - 0.5 * step, signal.lfilter(b, a, force)
