"""Shared handling of a sampled signal for the inverse methods.

A signal is a pair ``(t, y)`` of 1-D arrays: time [s], strictly increasing and uniformly
sampled, and the sensor's output (force [N] after the sensitivity conversion). Baseline,
noise and onset are read by :mod:`contactlab.signals`, as :mod:`contactlab.traces.prepare`
reads a measured trace, so a trace and an array give the same answer.
"""

import math

import numpy as np

from contactlab import signals
from contactlab.errors import ParameterError
from contactlab.metrics import _as_signal
from contactlab.validation import check_number

__all__ = [
    "BASELINE_MIN_SAMPLES",
    "baseline",
    "check_baseline_samples",
    "check_window",
    "lobe_around_peak",
    "uniform_signal",
]

UNIFORM_RTOL = 1e-4
"""Largest deviation of a time step from the mean interval, relative to it (the rule of
:mod:`contactlab.traces.checks`)."""

BASELINE_MIN_SAMPLES = 16
"""Fewest pre-trigger samples that give a usable noise estimate (standard deviation known
to about 1/sqrt(2*16) = 18 %)."""


def uniform_signal(t, y, name="signal"):
    """Check ``(t, y)`` and return them as float arrays with the sample interval [s].

    Raises
    ------
    ParameterError
        Not 1-D and of equal length, not finite, not strictly increasing, or not
        uniformly sampled (the inverse methods discretise the sensor on one step).
    """
    try:
        t, y = _as_signal(t, y)
    except (TypeError, ValueError) as exc:  # ParameterError, or no numbers at all
        raise ParameterError(f"t and {name}: {exc}") from None
    dt = (t[-1] - t[0]) / (t.size - 1)
    deviation = float(np.max(np.abs(np.diff(t) - dt)))
    if deviation > UNIFORM_RTOL * dt:
        raise ParameterError(
            f"t must be uniformly sampled; its steps deviate from {dt:.6g} s by up to "
            f"{deviation:.3g} s"
        )
    return t, y, dt


def check_window(name, window):
    """Return a time window as ``(start, end)`` floats [s], finite, with ``start < end``.

    Raises
    ------
    ParameterError
        Not a pair, not finite numbers, or ``end <= start``; the message names ``name``.
    """
    if isinstance(window, str) or not hasattr(window, "__len__") or len(window) != 2:
        raise ParameterError(f"{name} must be (start, end) [s]; got {window!r}")
    start = check_number(f"{name} start", window[0], unit="s")
    end = check_number(f"{name} end", window[1], low=start, unit=f"s (> {name} start)")
    return start, end


def check_baseline_samples(t, window, found=False):
    """Refuse a noise window that holds too few samples to estimate the noise.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times [s].
    window : (float, float)
        The window ``[start, end)`` [s].
    found : bool, default False
        Whether the window was found before the pulse (its end is the pulse's start) or
        given (or taken as every pre-trigger sample); the message speaks to either.

    Raises
    ------
    ParameterError
        Fewer than :data:`BASELINE_MIN_SAMPLES` samples of ``t`` lie in ``window``; the
        message says how to give a window.
    """
    count = int(signals.in_window(t, window).sum())
    if count >= BASELINE_MIN_SAMPLES:
        return
    if found:
        where = (
            f"only {count} samples lie before the pulse, which starts about {window[1]:.6g} "
            f"s; a noise estimate needs {BASELINE_MIN_SAMPLES}: record a longer pre-trigger"
        )
    else:
        where = (
            f"baseline window {window} s holds {count} samples; need at least "
            f"{BASELINE_MIN_SAMPLES} pre-trigger samples: record a pre-trigger"
        )
    raise ParameterError(
        f"{where}, or give the noise window (baseline_window=(start, end) [s]; --baseline "
        "T0 T1 on the command line)"
    )


def baseline(t, y, window=None, k=5.0):
    """Baseline mean, noise and onset of a pulse (:mod:`contactlab.signals`).

    Parameters
    ----------
    t, y : numpy.ndarray
        The signal.
    window : (float, float), optional
        Baseline window ``[start, end)`` [s]. Default: the samples before ``t = 0``
        (oscilloscopes write time relative to the trigger; a record without them is
        handled by :func:`contactlab.inverse.pulse.pulse_baseline`).
    k : float, default 5
        Onset threshold in baseline standard deviations [-].

    Returns
    -------
    mean : float
        Baseline mean (signal unit).
    noise : float
        Baseline standard deviation (signal unit).
    onset : float
        First time [s] where ``|y - mean|`` exceeds ``k * noise``.
    window : (float, float)
        The window used [s].

    Raises
    ------
    ParameterError
        Fewer than :data:`BASELINE_MIN_SAMPLES` samples in the window, or no sample
        above the threshold.
    """
    if window is None:
        window = (float(t[0]), 0.0)
    else:
        window = check_window("baseline_window", window)
    check_baseline_samples(t, window)
    mean, noise, _ = signals.baseline(t, y, window, name="baseline_window")
    if noise == 0.0:
        raise ParameterError(f"the baseline window {window} s is exactly constant (no noise)")
    onset = signals.detect_onset(t, y, window, k, name="baseline_window")
    return mean, noise, onset, window


def lobe_around_peak(t, y, reference=0.0):
    """The lobe holding the largest deviation from ``reference``: its start and end [s].

    A lobe is a run of samples on one side of ``reference``; its ends are the crossings,
    interpolated linearly (the first or last sample where the run meets the record's end).
    """
    d = y - reference
    i = int(np.argmax(np.abs(d)))
    side = np.sign(d[i])
    other = np.flatnonzero(np.sign(d) != side)
    before, after = other[other < i], other[other > i]
    start = t[0] if before.size == 0 else _crossing(t, d, before[-1], before[-1] + 1)
    end = t[-1] if after.size == 0 else _crossing(t, d, after[0] - 1, after[0])
    return float(start), float(end)


def _crossing(t, d, i, j):
    """Zero crossing of ``d`` between samples i and j = i + 1 (linear)."""
    if d[j] == d[i]:
        return t[j]
    return t[i] - d[i] * (t[j] - t[i]) / (d[j] - d[i])


RINGING_EXCESS = 1.3
"""The post-contact window is reported as not free ringing when the free ringing and
the line leave more than this times the noise before the pulse [-]. On white noise the
ratio of the two estimates scatters by about ``1/sqrt(n)`` (``n`` the baseline window's
400 samples at 2 MHz: 5 %); on realistic records (``benchmarks/bench_single_trace.py``,
four seeds) white noise, hum, drift and bounces gave 0.95-1.07, 1/f noise as large as
the white noise 0.91-1.01, crosstalk of 2 % of the peak 1.57-2.05."""


def difference_noise(y):
    """The record's noise standard deviation from its sample-to-sample differences
    (robust: a pulse and its ringing occupy a minority of them; drift and hum are too
    slow to reach them; 1/f noise is under-read, by 10-20 % when it is as large as the
    white noise)."""
    return signals.robust_noise(np.diff(y)) / math.sqrt(2.0)
