"""Preparing a sampled trace on plain arrays: baseline, noise, onset, low-pass.

A trace here is a time axis ``t`` [s] (strictly increasing; not checked here, readers and
the inverse methods check it) and samples ``y`` in any unit (V, or N after the
sensitivity conversion) on it. These are the numerical cores that
:mod:`dem_check.traces.prepare` applies to a measured ``Trace`` and that
:mod:`contactlab.inverse` applies to arrays, so a ``Trace`` read from a file and the
same samples as arrays give the same answer to the last bit.

The baseline is read over a time window ``[start, end)`` [s], usually the pre-trigger
part of the trace. Samples that are not finite are *overrange* (readers write a sample
at the instrument's limit as +-inf): a baseline or a filter that would depend on them
refuses them, naming the fault.
"""

import numbers
from typing import NamedTuple

import numpy as np
from scipy import signal

from contactlab.errors import ParameterError
from contactlab.validation import check_count, check_number

__all__ = ["Baseline", "baseline", "detect_onset", "in_window", "lowpass", "noise_level"]


class Baseline(NamedTuple):
    """Statistics of the samples in a baseline window (see :func:`baseline`)."""

    mean: float
    """Mean of the samples (their unit)."""
    noise: float
    """Standard deviation of the samples, ``ddof=1`` (their unit)."""
    samples: int
    """Number of samples in the window."""


def _trace(t, y):
    t = np.asarray(t, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if t.ndim != 1 or y.shape != t.shape:
        raise ParameterError(
            f"t and y must be 1-D arrays of equal length; got shapes {t.shape} and {y.shape}"
        )
    return t, y


def _window(window, name):
    """``(start, end)`` as floats [s]; an empty or reversed window is left to the count."""
    try:
        start, end = window
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be (start, end) [s]; got {window!r}") from None
    if not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in (start, end)):
        raise ParameterError(f"{name} must be (start, end) [s]; got {window!r}")
    return float(start), float(end)


def in_window(t, window):
    """Which samples lie in the time window ``[start, end)``.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times [s].
    window : (float, float)
        ``(start, end)`` [s]; ``start`` is included, ``end`` excluded.

    Returns
    -------
    numpy.ndarray of bool
    """
    start, end = window
    return (t >= start) & (t < end)


def baseline(t, y, window, *, name="window"):
    """Mean and noise (standard deviation, ``ddof=1``) of the samples in a time window.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    y : array_like
        Samples on ``t`` (any unit), of the same length.
    window : (float, float)
        Baseline window ``[start, end)`` [s] (see :func:`in_window`).
    name : str, default "window"
        The caller's name for ``window``, used in the messages.

    Returns
    -------
    Baseline
        ``(mean, noise, samples)``, mean and noise in the unit of ``y``.

    Raises
    ------
    ParameterError
        If the window is not a pair of numbers, holds fewer than 2 samples (an empty or
        reversed window holds none) or holds overrange (non-finite) samples.
    """
    t, y = _trace(t, y)
    window = _window(window, name)
    samples = y[in_window(t, window)]
    if samples.size < 2:
        raise ParameterError(
            f"the baseline window {window} s holds {samples.size} samples; need at least 2 "
            f"(pass {name}=(start, end) [s])"
        )
    if not np.isfinite(samples).all():
        raise ParameterError(f"the baseline window {window} s holds overrange samples")
    return Baseline(float(samples.mean()), float(samples.std(ddof=1)), int(samples.size))


def noise_level(t, y, window, *, name="window"):
    """Noise of a trace: the standard deviation (``ddof=1``) of its baseline.

    Parameters
    ----------
    t, y, window, name
        As for :func:`baseline`.

    Returns
    -------
    float
        In the unit of ``y``.
    """
    return baseline(t, y, window, name=name).noise


def detect_onset(t, y, window, k=5.0, *, name="window"):
    """Time of the first crossing of ``k`` times the baseline noise [s].

    The onset is where ``|y - mean|`` first exceeds ``k * noise`` (mean and noise of the
    baseline window), interpolated linearly between samples; it is ``t[0]`` if the first
    sample already exceeds it, and the sample's time if the sample is overrange. The
    search covers the whole trace, since a pulse may start before the trigger; with
    Gaussian noise a baseline sample exceeds 5 sigma with probability 6e-7, so raise
    ``k`` for very long baselines.

    Parameters
    ----------
    t, y, window, name
        As for :func:`baseline`.
    k : float, default 5.0
        Threshold in baseline standard deviations [-], > 0.

    Returns
    -------
    float
        Onset time [s].

    Raises
    ------
    ParameterError
        As :func:`baseline`, for ``k <= 0``, or if no sample exceeds the threshold.
    """
    k = check_number("k", k, low=0.0)
    t, y = _trace(t, y)
    mean, noise, _ = baseline(t, y, window, name=name)
    level = k * noise
    deviation = np.abs(y - mean)
    above = deviation > level
    if not above.any():
        raise ParameterError(f"no sample deviates from the baseline by more than {k} sigma")
    i = int(np.argmax(above))
    if i == 0:
        return float(t[0])
    t0, t1, d0, d1 = t[i - 1], t[i], deviation[i - 1], deviation[i]
    if np.isinf(d1):
        return float(t1)
    return float(t0 + (level - d0) * (t1 - t0) / (d1 - d0))


def lowpass(y, interval, cutoff, order=4):
    """Zero-phase Butterworth low-pass filter of a uniformly sampled trace.

    A digital Butterworth filter of ``order`` with -3 dB frequency ``cutoff`` (bilinear
    transform, prewarped at the cutoff: ``scipy.signal.butter``) is applied forward and
    backward (``scipy.signal.sosfiltfilt``, odd extension at the ends), so there is no
    phase shift (a pulse's timing is kept) and the magnitude response is squared::

        |H(f)|^2 = 1 / (1 + (tan(pi f dt) / tan(pi cutoff dt))^(2 order))

    with ``dt = interval``: exactly 1/2 (-6 dB) at the cutoff, and
    ``1 - (f / cutoff)^(2 order)`` to first order in the passband when ``f << 1 / dt``.

    Parameters
    ----------
    y : array_like
        Samples, 1-D, finite.
    interval : float
        Sample interval [s], > 0.
    cutoff : float
        -3 dB frequency of the single pass [Hz], > 0 and below the Nyquist frequency
        ``0.5 / interval``.
    order : int, default 4
        Butterworth order of the single pass, >= 1.

    Returns
    -------
    numpy.ndarray
        The filtered samples, in the unit of ``y``.

    Raises
    ------
    ParameterError
        Bad ``interval``, ``cutoff`` or ``order``; overrange (non-finite) samples; or a
        trace no longer than the filter's edge padding, ``3 (2 ceil(order / 2) + 1)``
        samples.
    """
    y = np.asarray(y, dtype=np.float64)
    if y.ndim != 1:
        raise ParameterError(f"y must be a 1-D array; got shape {y.shape}")
    interval = check_number("interval", interval, low=0.0, unit="s")
    nyquist = 0.5 / interval
    cutoff = check_number("cutoff", cutoff, low=0.0, high=nyquist, high_open=True, unit="Hz")
    order = check_count("order", order)
    if not np.isfinite(y).all():
        raise ParameterError("lowpass needs finite samples; the trace holds overrange samples")
    sos = signal.butter(order, cutoff, btype="low", output="sos", fs=1.0 / interval)
    pad = 3 * (2 * len(sos) + 1)
    if y.size <= pad:
        raise ParameterError(f"lowpass of order {order} needs more than {pad} samples")
    return signal.sosfiltfilt(sos, y)
