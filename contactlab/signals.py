"""Preparing a sampled trace on plain arrays: baseline, noise, onset, low-pass.

A trace here is a time axis ``t`` [s] (strictly increasing; not checked here, readers and
the inverse methods check it) and samples ``y`` in any unit (V, or N after the
sensitivity conversion) on it. These are the numerical cores that
:mod:`contactlab.traces.prepare` applies to a measured ``Trace`` and that
:mod:`contactlab.inverse` applies to arrays, so a ``Trace`` read from a file and the
same samples as arrays give the same answer to the last bit.

The baseline is read over a time window ``[start, end)`` [s], usually the pre-trigger
part of the trace. Samples that are not finite are *overrange* (readers write a sample
at the instrument's limit as +-inf): a baseline or a filter that would depend on them
refuses them, naming the fault.
"""

import itertools
import numbers
from typing import NamedTuple

import numpy as np
from scipy import signal

from contactlab._block_levels import MAD_TO_SIGMA, block_levels
from contactlab._head_level import head_level
from contactlab.errors import ParameterError
from contactlab.validation import check_count, check_interval, check_number, check_samples

__all__ = [
    "MAD_TO_SIGMA",
    "Baseline",
    "RunningBaseline",
    "baseline",
    "detect_onset",
    "in_window",
    "lowpass",
    "noise_level",
    "quiet_window",
    "robust_noise",
    "running_baseline",
]


class RunningBaseline(NamedTuple):
    """A baseline that follows drift, and the local noise around it (see
    :func:`running_baseline`)."""

    level: np.ndarray
    """Baseline at every sample (unit of the samples)."""
    residual: np.ndarray
    """Samples minus the nearest of the block levels around them (unit of the samples):
    what the impacts are found on."""
    noise: np.ndarray
    """Local noise at every sample, :data:`MAD_TO_SIGMA` times the median absolute
    distance from ``level`` over its block, the largest of the block and its two
    neighbours (unit of the samples)."""


class Baseline(NamedTuple):
    """Statistics of the samples in a baseline window (see :func:`baseline`)."""

    mean: float
    """Mean of the samples (their unit)."""
    noise: float
    """Standard deviation of the samples, ``ddof=1`` (their unit)."""
    samples: int
    """Number of samples in the window."""


def _trace(t, y):
    t, y = check_samples("t", t, unit="s"), check_samples("y", y, finite=False)
    if y.shape != t.shape:
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
    if np.isnan([start, end]).any():
        raise ParameterError(f"{name} must be (start, end) [s], not NaN; got {window!r}")
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

    Raises
    ------
    ParameterError
        ``t`` not a 1-D array of finite times, or ``window`` not a pair of numbers.
    """
    t = check_samples("t", t, min_size=1, unit="s")
    start, end = _window(window, "window")
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
        raise ParameterError(
            f"y holds overrange samples (inf or NaN) in the baseline window {window} s"
        )
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
    y = check_samples("y", y, finite=False)
    interval = check_interval("interval", interval)
    nyquist = 0.5 / interval
    cutoff = check_number("cutoff", cutoff, low=0.0, high=nyquist, high_open=True, unit="Hz")
    order = check_count("order", order)
    if not np.isfinite(y).all():
        raise ParameterError("lowpass needs finite y; the trace holds overrange samples")
    sos = signal.butter(order, cutoff, btype="low", output="sos", fs=1.0 / interval)
    pad = 3 * (2 * len(sos) + 1)
    if y.size <= pad:
        raise ParameterError(f"lowpass of order {order} needs more than {pad} samples in y")
    return signal.sosfiltfilt(sos, y)


def robust_noise(y):
    """Noise of samples that may hold pulses: :data:`MAD_TO_SIGMA` times their median
    absolute deviation from their median (unit of ``y``).

    For Gaussian noise this is its standard deviation (to ``0.78 / sqrt(n)`` relative
    scatter); pulses covering less than half of the samples move it little, where they
    would inflate the standard deviation.

    Parameters
    ----------
    y : array_like
        Finite samples, at least 2.

    Returns
    -------
    float
    """
    y = check_samples("y", y)
    if y.size < 2:
        raise ParameterError(f"robust_noise needs at least 2 samples in y; got {y.size}")
    return MAD_TO_SIGMA * float(np.median(np.abs(y - np.median(y))))


def _mask(name, value, size):
    """``value`` as a 1-D bool array of ``size`` samples, or a ParameterError naming it."""
    try:
        mask = np.asarray(value)
    except (TypeError, ValueError):  # ragged nesting
        mask = None
    if mask is None or mask.dtype != bool or mask.shape != (size,):
        raise ParameterError(f"{name} must be {size} booleans, one per sample; got {value!r}")
    return mask


def _block_spread(distance, edges, exclude):
    """Median of ``distance`` per block over the samples not excluded; a block with
    fewer than :data:`SPREAD_MIN_SAMPLES` of them takes its neighbours' (interpolated
    over the block index, held at the ends)."""
    keep = np.ones(distance.size, dtype=bool) if exclude is None else ~exclude
    spread = np.full(edges.size - 1, np.nan)
    for k, (a, b) in enumerate(itertools.pairwise(edges)):
        kept = distance[a:b][keep[a:b]]
        if kept.size >= SPREAD_MIN_SAMPLES:
            spread[k] = np.median(kept)
    valid = np.flatnonzero(np.isfinite(spread))
    if valid.size == 0:
        raise ParameterError("running_baseline: every block is excluded; no noise to read")
    return np.interp(np.arange(spread.size), valid, spread[valid])


SPREAD_MIN_SAMPLES = 16
"""Fewest samples left in a block after the exclusions to read its noise [-]."""


def running_baseline(y, width, exclude=None, head=0):
    """A baseline that follows slow drift, wander, offset steps and hum, and the local
    noise around it.

    The samples are cut into blocks of about ``width`` samples; each block's median is its
    level. The baseline is these levels interpolated linearly between the block centres, and
    extrapolated with the outer slopes before the first centre and after the last (what a
    drift or a hum slower than a block looks like). The residual of a sample is its distance
    to one of four candidate levels, the interpolated one and the medians of its own block
    and of the two blocks around it: the one nearest to the mean of the samples on one side
    of it (over :data:`LOCAL_MEAN_FRACTION` of a block, so the choice does not follow the
    noise; the side whose mean is nearer the sample, so a step's two sides each keep their
    level). A pulse much shorter than a block stands above all four, so it is kept whole; at
    a DC offset step the samples before and after it each find a block on their own side, so
    the step leaves no residual that could pass for an impact. The local noise of a block is
    :data:`MAD_TO_SIGMA` times the median absolute residual of its samples, and the noise at
    a sample the largest of its block's and its two neighbours' (a decaying ringing or a hum
    that fills a block raises its own threshold).

    Parameters
    ----------
    y : array_like
        Finite samples (any unit), at least 2 blocks.
    width : int
        Block length [samples], >= 8; choose it long against a pulse (a pulse must cover
        much less than half of a block) and short against the drift.
    exclude : array_like of bool, optional
        Samples left out of the local noise (pulses found on a first pass, with their
        ringing): a block mostly filled by a pulse's ringing then reads the noise of its
        other samples, or of its neighbours when fewer than 16 are left.
    head : int, default 0
        Samples at the record's start that hold a pulse: the level there and a block on is
        :func:`~contactlab._head_level.head_level`'s robust fit after them, extrapolated
        back, the residual the distance to it, the noise with the fit's error added.

    Returns
    -------
    RunningBaseline

    Raises
    ------
    ParameterError
        Bad ``width`` or ``head``, non-finite samples, too few blocks or quiet samples.
    """
    check_count("width", width, low=8)  # in the order the parameters are checked before
    check_count("head", head, low=0)
    return levels_baseline(block_levels(y, width), exclude, head)


def levels_baseline(levels, exclude=None, head=0):
    """:func:`running_baseline` from the record's levels computed once
    (:func:`contactlab._block_levels.block_levels`): the same arrays, to the last bit.

    Parameters
    ----------
    levels : BlockLevels
        The record's levels; not changed (a ``head`` fit changes copies).
    exclude, head
        As for :func:`running_baseline`.

    Returns
    -------
    RunningBaseline
        The arrays :func:`running_baseline` gives on the same samples, to the last bit.

    Raises
    ------
    ParameterError
        Bad ``head`` or ``exclude``, every block excluded, or too few quiet samples.
    """
    pulse = check_count("head", head, low=0)
    y, level, residual = levels.y, levels.level, levels.residual
    if exclude is not None:
        exclude = _mask("exclude", exclude, y.size)
    error = 0.0
    if pulse:  # head_level changes the level and residual in place
        level, residual = level.copy(), residual.copy()
        error = head_level(y, pulse, levels.width, exclude, level, residual)
    spread = _block_spread(np.abs(residual), levels.edges, exclude)
    widened = np.maximum(
        spread, np.maximum(np.r_[spread[:1], spread[:-1]], np.r_[spread[1:], spread[-1:]])
    )
    noise = np.hypot(MAD_TO_SIGMA * widened[levels.block], error)
    return RunningBaseline(level, residual, noise)


def quiet_window(t, y, width=None):
    """The quietest stretch of a record: the block of ``width`` samples with the smallest
    robust noise around the running baseline, as a time window ``[start, end)`` [s].

    The single-trace methods read their baseline there when a record has no pre-trigger
    (it starts at, or just before, the impact).

    Parameters
    ----------
    t, y : array_like
        Sample times [s] and samples, as for :func:`baseline`.
    width : int, optional
        Block length [samples], >= 8; default a sixteenth of the record, at least 16
        samples (a record shorter than 32 samples is refused).

    Returns
    -------
    (float, float)
    """
    t, y = _trace(t, y)
    if width is None:
        width = max(16, y.size // 16)
    return levels_quiet_window(t, block_levels(y, width))


def levels_quiet_window(t, levels):
    """:func:`quiet_window` from the record's levels computed once
    (:func:`contactlab._block_levels.block_levels`, its block length the window's).

    Parameters
    ----------
    t : array_like
        Sample times [s], one per sample of ``levels.y``.
    levels : BlockLevels

    Returns
    -------
    (float, float)
    """
    t = np.asarray(t, dtype=float)
    if t.shape != levels.y.shape:
        raise ParameterError(f"t must hold one time per sample ({levels.y.size}); got {t.shape}")
    edges = levels.edges
    noise = [robust_noise(levels.residual[a:b]) for a, b in itertools.pairwise(edges)]
    k = int(np.argmin(noise))
    end = float(t[edges[k + 1]]) if edges[k + 1] < t.size else float(np.nextafter(t[-1], np.inf))
    return float(t[edges[k]]), end
