"""Sensor signals set side by side: time alignment and waveform errors.

The sensor signals S1 are compared after a time alignment (``align``): ``"onset"`` makes
the first crossings of :data:`ONSET_LEVEL` times each signal's peak coincide (the same
reading for a noise-free simulation and a noisy trace), ``"xcorr"`` maximises their
cross-correlation (parabolic refinement of the best lag), ``None`` keeps the time axes.
Both signals are then interpolated linearly onto a common uniform grid spanning the
window both cover, with the finer of their two sample intervals, and the RMS and largest
differences are taken there.
"""

import math

import numpy as np

from contactlab import metrics
from contactlab.errors import ParameterError
from contactlab.traces.trace import Trace

__all__ = ["ALIGNMENTS", "ONSET_LEVEL", "alignment_shift", "sensor_signal", "waveform_errors"]

ALIGNMENTS = ("onset", "xcorr", None)
"""Accepted values of ``align``."""

ONSET_LEVEL = 0.1
"""Fraction of a signal's peak whose first crossing is its onset for ``align="onset"``:
high enough to clear measurement noise, low enough to sit on the steep first rise."""


def sensor_signal(obj, label):
    """``(t, S1)`` of a result or a trace (which must be in newtons)."""
    if isinstance(obj, Trace):
        if obj.unit != "N":
            raise ParameterError(
                f"{label}: the trace is in {obj.unit!r}; compare needs newtons: read it with "
                "sensitivity=<V/N> (or contactlab.traces.to_force)"
            )
        return obj.t, obj.values
    if not all(hasattr(obj, name) for name in ("t", "sensor_force")):
        raise ParameterError(
            f"{label}: expected a simulated result or a Trace; got {type(obj).__name__}"
        )
    return obj.t, obj.sensor_force


def _onset(t, y):
    peak = float(np.max(y))
    if not peak > 0.0:
        raise ParameterError("align='onset' needs a signal with a positive peak")
    return metrics.first_lobe(t, y, ONSET_LEVEL * peak)[0]


def _uniform(t, y, step):
    grid = np.arange(t[0], t[-1] + 0.5 * step, step)
    grid = grid[grid <= t[-1]]
    return grid, np.interp(grid, t, y)


def _xcorr_shift(sig_a, sig_b, step):
    """Shift [s] added to a's times that maximises the cross-correlation with b."""
    from scipy import signal

    ta, ya = _uniform(*sig_a, step)
    tb, yb = _uniform(*sig_b, step)
    corr = signal.correlate(yb, ya, mode="full", method="fft")
    lags = signal.correlation_lags(yb.size, ya.size, mode="full")
    k = int(np.argmax(corr))
    offset = 0.0
    if 0 < k < corr.size - 1:  # vertex of the parabola through the best lag and neighbours
        left, mid, right = corr[k - 1], corr[k], corr[k + 1]
        curvature = left - 2.0 * mid + right
        if curvature < 0.0:
            offset = 0.5 * (left - right) / curvature
    return tb[0] - ta[0] + (lags[k] + offset) * step


def _step(t):
    return float(np.median(np.diff(t)))


def alignment_shift(sig_a, sig_b, align):
    """Shift [s] added to a's times to line the signals up (``align``: :data:`ALIGNMENTS`)."""
    if align is None:
        return 0.0
    if align == "onset":
        return _onset(*sig_b) - _onset(*sig_a)
    return _xcorr_shift(sig_a, sig_b, min(_step(sig_a[0]), _step(sig_b[0])))


def waveform_errors(sig_a, sig_b, shift):
    """RMS and largest difference of the two signals on their common window [N], and the
    window (start, end) [s] in b's time."""
    ta, ya = sig_a[0] + shift, sig_a[1]
    tb, yb = sig_b
    lo, hi = max(ta[0], tb[0]), min(ta[-1], tb[-1])
    if hi <= lo:
        raise ParameterError(
            f"after alignment the signals do not overlap in time (a: {ta[0]:.4g}..{ta[-1]:.4g}"
            f" s, b: {tb[0]:.4g}..{tb[-1]:.4g} s)"
        )
    step = min(_step(ta), _step(tb))
    grid = np.linspace(lo, hi, max(2, math.floor((hi - lo) / step) + 1))
    diff = np.interp(grid, ta, ya) - np.interp(grid, tb, yb)
    return float(np.sqrt(np.mean(diff**2))), float(np.max(np.abs(diff))), (lo, hi)
