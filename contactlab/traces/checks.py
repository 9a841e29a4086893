"""Checks every reader applies, whatever the format: channel choice, sample validity and
the numeric header fields of binary files; and the check that writers of uniformly
sampled layouts (``start + n * interval``) need.

Errors name the file and where in it the fault lies. Text readers pass a ``where``
function mapping a sample index to ``"line N"``; binary readers map it to ``"sample N"``.
"""

import math

import numpy as np

from contactlab.errors import ParameterError, TraceFormatError

__all__ = [
    "MAX_SAMPLES",
    "check_samples",
    "fail",
    "grid_deviation",
    "header_number",
    "select_channel",
    "uniform_interval",
]

UNIFORM_RTOL = 1e-4
"""Largest disagreement between sample times and a uniform grid, relative to the sample
interval: of a sample time from ``start + n * interval`` for a trace to count as
uniformly sampled, and of a declared interval from the time column's mean spacing. Time
columns printed with ~12 digits (Tektronix) jitter by ~1e-6 of an interval and must
pass; a dropped or repeated sample (a deviation of 1) or real timing irregularity must
not."""


MAX_SAMPLES = 200_000_000
"""Most samples a binary trace may declare (1.6 GB as float64, two days of a 1 kHz DAQ or
50 s at 4 MS/s): a larger declaration is refused before anything is allocated."""


def fail(path, where, message):
    """A :class:`TraceFormatError` reading ``"<path>, <where>: <message>"``."""
    return TraceFormatError(f"{path}, {where}: {message}")


def header_number(path, where, name, value, *, positive=False):
    """A numeric field of a binary file's header (an attribute, a property) as a float.

    Raises
    ------
    TraceFormatError
        Naming the file, ``where`` and the field, if the value is not a finite number
        (or not > 0 when ``positive``).
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or (positive and number <= 0.0):
        shown = value.item() if isinstance(value, np.generic) else value
        raise fail(path, where, f"{name} {shown!r} is not a finite number{' > 0' * positive}")
    return number


def _key(name):
    return str(name).replace(" ", "").casefold()


def select_channel(names, channel, path, where):
    """Index of the requested channel among ``names``.

    Parameters
    ----------
    names : sequence of str
        Channel names in file order.
    channel : str, int or None
        A name (compared ignoring case and spaces, so ``"CH1"`` matches ``"CH 1"``) or a
        0-based index. ``None`` is accepted only for a single-channel file. An index that
        is also another channel's name (Keysight names channels ``"1"``, ``"2"``) is
        refused as ambiguous.
    path : str
        The file, for the message.
    where : str
        Where the channels are listed (``"line 2"``), for the message.

    Raises
    ------
    TraceFormatError
        If the channel does not exist, or the file holds several channels and none was
        chosen. Reading the first of several would be a guess: a comparison against the
        wrong channel looks plausible and is silently wrong.
    """
    listed = ", ".join(repr(n) for n in names)
    if channel is None:
        if len(names) == 1:
            return 0
        raise fail(path, where, f"the file holds {len(names)} channels ({listed}); pass channel=")
    if isinstance(channel, (int, np.integer)) and not isinstance(channel, bool):
        named = [i for i, name in enumerate(names) if _key(name) == _key(channel)]
        if named and named != [channel]:
            raise fail(
                path,
                where,
                f"channel={channel} is ambiguous: a channel is named {str(channel)!r} but "
                f"index {channel} is another; pass channel={str(channel)!r} for the name",
            )
        if 0 <= channel < len(names):
            return int(channel)
    else:
        matches = [i for i, name in enumerate(names) if _key(name) == _key(channel)]
        if len(matches) == 1:
            return matches[0]
    indices = f"0..{len(names) - 1}" if len(names) > 1 else "0"
    raise fail(path, where, f"no channel {channel!r}; available: {listed} (or index {indices})")


def check_samples(t, values, path, where):
    """Check times and values; return the indices of overrange samples.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times [s].
    values : numpy.ndarray
        Samples.
    path : str
        The file, for messages.
    where : callable
        Maps a sample index to a location string such as ``"line 12"``.

    Returns
    -------
    numpy.ndarray
        Indices of infinite values (overrange), empty if none.

    Raises
    ------
    TraceFormatError
        On an empty trace, a missing (NaN) sample, an infinite time, or times that are not
        strictly increasing (duplicated or going back).
    """
    if t.size == 0:
        raise fail(path, where(0), "no samples")
    for name, array in (("time", t), ("value", values)):
        bad = np.isnan(array)
        if bad.any():
            raise fail(path, where(int(np.argmax(bad))), f"missing {name} (NaN)")
    if not np.isfinite(t).all():
        raise fail(path, where(int(np.argmax(~np.isfinite(t)))), "infinite time")
    steps = np.diff(t)
    if t.size > 1 and not (steps > 0).all():
        i = int(np.argmax(steps <= 0)) + 1
        kind = "duplicated" if steps[i - 1] == 0 else "going back"
        now, before = float(t[i]), float(t[i - 1])
        raise fail(path, where(i), f"time {now!r} s is {kind} (previous sample at {before!r} s)")
    return np.flatnonzero(np.isinf(values))


def grid_deviation(t, start, interval, first=0):
    """Largest distance [s] of the times ``t`` from the grid ``start + n * interval``.

    ``n`` counts from ``first`` (the sample number of ``t[0]``).
    """
    n = np.arange(first, first + t.size)
    return float(np.max(np.abs(start + n * interval - t)))


def uniform_interval(trace, purpose="this layout stores start + n * interval"):
    """Sample interval [s] of a uniformly sampled trace.

    The interval must give back every sample time as ``t[0] + n * interval`` to within
    :data:`UNIFORM_RTOL` of an interval (so a writer that stores only the start and the
    interval keeps the samples where they were). ``metadata["sample_interval"]`` (the
    file's declared interval) is tried first, then the mean spacing: a declared interval
    printed with few digits drifts from the time column over a long record.

    Parameters
    ----------
    trace : Trace
    purpose : str
        Why uniform sampling is needed, for the message.

    Raises
    ------
    ParameterError
        If the trace has fewer than 2 samples or its times are not on a uniform grid.
    """
    t = trace.t
    if t.size < 2:
        raise ParameterError(f"{purpose}: needs at least 2 samples; got {t.size}")
    spacing = float((t[-1] - t[0]) / (t.size - 1))
    declared = trace.metadata.get("sample_interval")
    for interval in (declared, spacing) if declared else (spacing,):
        deviation = grid_deviation(t, t[0], interval)
        if deviation <= UNIFORM_RTOL * interval:
            return float(interval)
    raise ParameterError(
        f"{purpose}, but the trace's times deviate from a uniform grid of {spacing!r} s by "
        f"up to {deviation!r} s (non-uniform sampling)"
    )
