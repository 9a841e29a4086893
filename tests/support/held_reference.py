"""The lobe model's unit signal and its sampling at the window's times as they were
written before they were compiled (:mod:`contactlab.kernels.held_force`): ``numpy.interp``
and ``scipy.signal.lfilter``. The tests hold the kernels to them bit for bit;
``benchmarks/bench_held_force.py`` times the onset fits with them."""

import numpy as np
from scipy import signal

__all__ = ["numpy_response", "numpy_unit"]


def numpy_unit(step, count, tau, u, h, b, a):
    """:func:`contactlab.kernels.held_force.held_signal` with numpy and scipy: the
    times [s] and the filtered unit force [-] on ``k step``, ``k = -1 ... count - 1``."""
    s = np.arange(-1, count) * step
    force = np.interp((s - 0.5 * step) / tau, u, h, left=0.0, right=0.0)
    return s - 0.5 * step, signal.lfilter(b, a, force)


def numpy_response(t, t0, s, r):
    """:func:`contactlab.kernels.held_force.sampled_signal` with numpy: the unit signal
    ``r`` on its grid ``s`` [s] at the times ``t - t0`` [s], 0 before the grid."""
    return np.interp(t - t0, s, r, left=0.0)
