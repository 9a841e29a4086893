"""Checks every reader applies, whatever the format: channel choice and sample validity;
and the one check writers of uniformly sampled layouts need.

Errors name the file and where in it the fault lies. Text readers pass a ``where``
function mapping a sample index to ``"line N"``; binary readers map it to ``"sample N"``.
"""

import numpy as np

from contactlab.errors import ParameterError, TraceFormatError

__all__ = ["check_samples", "fail", "select_channel", "uniform_interval"]

UNIFORM_RTOL = 1e-4
"""Largest deviation of a time step from the sample interval, relative to it, for a trace
to count as uniformly sampled. Time columns printed with ~12 digits (Tektronix) jitter by
~1e-6 of an interval and must pass; a dropped or repeated sample (a deviation of 1) or
real timing irregularity must not."""


def fail(path, where, message):
    """A :class:`TraceFormatError` reading ``"<path>, <where>: <message>"``."""
    return TraceFormatError(f"{path}, {where}: {message}")


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


def uniform_interval(trace, purpose="this layout stores start + n * interval"):
    """Sample interval [s] of a uniformly sampled trace.

    Uses ``metadata["sample_interval"]`` when present, else the mean spacing.

    Parameters
    ----------
    trace : Trace
    purpose : str
        Why uniform sampling is needed, for the message.

    Raises
    ------
    ParameterError
        If the trace has fewer than 2 samples or its time steps are not uniform.
    """
    t = trace.t
    if t.size < 2:
        raise ParameterError(f"{purpose}: needs at least 2 samples; got {t.size}")
    interval = trace.metadata.get("sample_interval") or (t[-1] - t[0]) / (t.size - 1)
    deviation = np.max(np.abs(np.diff(t) - interval))
    if not deviation <= UNIFORM_RTOL * interval:
        raise ParameterError(
            f"{purpose}, but the trace's time steps deviate from {interval!r} s by up to "
            f"{deviation!r} s (non-uniform sampling)"
        )
    return float(interval)
