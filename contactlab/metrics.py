"""Pulse metrics shared by simulations and measured traces.

One module serves both: a simulated :class:`~contactlab.result.ImpactResult` and a
measured trace from :func:`dem_check.read_trace` are read with the same functions, so an
error between them is never an artefact of two different readings.

All functions take a time axis ``t`` [s] (strictly increasing) and a signal ``y`` (force [N]
or any unit) sampled on it. Crossing times are interpolated linearly between samples.
"""

from dataclasses import asdict, dataclass

import numpy as np

from contactlab.errors import ParameterError
from contactlab.validation import check_number, check_samples

__all__ = [
    "PulseMetrics",
    "first_lobe",
    "impulse",
    "peak",
    "pulse_metrics",
    "relative_error",
    "rise_time",
]


def _as_signal(t, y):
    t, y = check_samples("t", t, unit="s"), check_samples("y", y)
    if y.shape != t.shape:
        raise ParameterError(
            f"t and y must be 1-D arrays of equal length; got shapes {t.shape} and {y.shape}"
        )
    if t.size < 2:
        raise ParameterError(f"a pulse needs at least 2 samples; got {t.size}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise ParameterError("t and y must be finite (no NaN or inf samples)")
    if np.any(np.diff(t) <= 0):
        raise ParameterError("t must be strictly increasing")
    return t, y


def _bound(name, value):
    """A window bound [s]: a finite number, or None for no bound."""
    return None if value is None else check_number(name, value, unit="s")


def _crossing_time(t, y, i, level):
    """Time where the segment between samples i-1 and i crosses ``level`` (linear)."""
    y0, y1 = y[i - 1], y[i]
    if y1 == y0:
        return t[i]
    return t[i - 1] + (level - y0) * (t[i] - t[i - 1]) / (y1 - y0)


def first_lobe(t, y, threshold=0.0, hysteresis=0.0, least_peak=0.0):
    """Start and end of the first main lobe of a pulse: first rise above a threshold to the
    first return to it.

    This is how an experimenter reads a contact time off a sensor signal.

    Parameters
    ----------
    t : array_like
        Time [s], strictly increasing.
    y : array_like
        Signal (e.g. sensor force [N]).
    threshold : float, default 0.0
        Level in the signal's unit. With 0 the lobe starts at the first sample above zero
        (or at the first sample when the signal starts at zero and rises).
    hysteresis : float, default 0.0
        For noisy signals, in the signal's unit (>= 0): the lobe is over only once the
        signal falls to ``threshold - hysteresis``, and it ends at its last downward
        crossing of ``threshold`` before that (a Schmitt trigger read at one level).
        Noise that dips under the threshold on a slow rise then does not end the lobe.
    least_peak : float, default 0.0
        Fraction of the signal's largest value [-] in [0, 1): a lobe whose peak is under
        it is passed over and the next lobe is read. A measured record's filter pre-echo
        or a lone noise excursion before the hit (a few tenths of a newton before a hit of
        tens) is then not read as the pulse. With 0 every lobe counts.

    Returns
    -------
    start, end : float
        Crossing times [s], linearly interpolated. ``end`` is ``nan`` when the signal never
        returns to the threshold inside the window; ``start`` and ``end`` are both ``nan``
        when the signal never exceeds it.
    """
    t, y = _as_signal(t, y)
    threshold = check_number("threshold", threshold)  # NaN would read as "never exceeded"
    hysteresis = check_number("hysteresis", hysteresis, low=0.0, low_open=False)
    least_peak = check_number(
        "least_peak", least_peak, low=0.0, low_open=False, high=1.0, high_open=True
    )
    above = y > threshold
    floor = least_peak * float(np.max(y)) if least_peak else None  # None: every lobe
    i = 0
    while above[i:].any():
        i_up = i + int(np.argmax(above[i:]))
        start = t[0] if i_up == 0 else _crossing_time(t, y, i_up, threshold)
        dropped = y[i_up:] <= threshold - hysteresis
        if not dropped.any():
            return start, np.nan
        i_drop = i_up + int(np.argmax(dropped))
        if floor is None or np.max(y[i_up:i_drop]) >= floor:
            falls = np.flatnonzero(above[i_up:i_drop] & ~above[i_up + 1 : i_drop + 1])
            i_down = i_up + 1 + int(falls[-1])
            return start, _crossing_time(t, y, i_down, threshold)
        i = i_drop  # a lobe under least_peak of the largest value: read the next one
    return np.nan, np.nan


def peak(t, y, start=None, end=None):
    """Largest value of a signal and its time, optionally inside ``[start, end]`` [s].

    Returns
    -------
    time, value : float
        Time of the peak [s] and the peak value (signal unit). Sample-resolved.
    """
    t, y = _as_signal(t, y)
    start, end = _bound("start", start), _bound("end", end)
    mask = np.ones(t.shape, dtype=bool)
    if start is not None:
        mask &= t >= start
    if end is not None:
        mask &= t <= end
    if not mask.any():
        raise ParameterError(f"no samples inside the window [{start}, {end}] s")
    idx = np.flatnonzero(mask)
    i = idx[np.argmax(y[idx])]
    return float(t[i]), float(y[i])


def impulse(t, y, start=None, end=None):
    """Time integral of a signal (trapezoidal rule), optionally over ``[start, end]`` [s].

    Returns
    -------
    float
        Impulse [N*s] for a force signal.
    """
    t, y = _as_signal(t, y)
    start, end = _bound("start", start), _bound("end", end)
    lo = t[0] if start is None else max(start, t[0])
    hi = t[-1] if end is None else min(end, t[-1])
    if hi <= lo:
        return 0.0
    inner = (t > lo) & (t < hi)
    tt = np.concatenate(([lo], t[inner], [hi]))
    yy = np.interp(tt, t, y)
    return float(np.trapezoid(yy, tt))


def rise_time(t, y, low=0.1, high=0.9):
    """10-90 % rise time (fractions configurable) of the first rise to the peak [s]."""
    t, y = _as_signal(t, y)
    low, high = check_number("low", low, low=0.0, low_open=False), check_number("high", high)
    if not 0.0 <= low < high <= 1.0:
        raise ParameterError(f"need 0 <= low < high <= 1; got low={low}, high={high}")
    i_peak = int(np.argmax(y))
    y_peak = y[i_peak]
    if y_peak <= 0.0 or i_peak == 0:
        return np.nan
    times = []
    for frac in (low, high):
        level = frac * y_peak
        i = int(np.argmax(y[: i_peak + 1] >= level))
        times.append(t[0] if i == 0 else _crossing_time(t, y, i, level))
    return float(times[1] - times[0])


@dataclass(frozen=True)
class PulseMetrics:
    """Metrics of a force pulse as a laboratory reports them (SI units)."""

    start: float
    """Start of the first lobe [s]."""
    end: float
    """End of the first lobe [s] (``nan`` if it does not end in the window)."""
    duration: float
    """Length of the first lobe [s]."""
    peak_time: float
    """Time of the largest value in the first lobe [s]."""
    peak: float
    """Largest value in the first lobe (signal unit, N for a force)."""
    rise_time: float
    """10-90 % rise time of the first lobe [s]."""
    impulse: float
    """Integral of the first lobe [signal unit * s, N*s for a force]."""
    unit: str = "N"
    """Unit of the signal (``"N"``, or ``"V"`` for a trace not yet converted)."""

    def to_dict(self):
        """Metrics as a dict with unit-bearing keys (``peak [V]`` for a volt signal)."""
        units = {
            "start": "s",
            "end": "s",
            "duration": "s",
            "peak_time": "s",
            "peak": self.unit,
            "rise_time": "s",
            "impulse": f"{self.unit}*s",
        }
        values = asdict(self)
        del values["unit"]
        return {f"{k} [{units[k]}]": v for k, v in values.items()}


def pulse_metrics(t, y, threshold=0.0, unit="N", hysteresis=0.0, least_peak=0.0):
    """All pulse metrics of the first lobe of a signal.

    Parameters
    ----------
    t : array_like
        Time [s], strictly increasing.
    y : array_like
        Signal, a force [N] (baseline removed for a measured trace).
    threshold : float, default 0.0
        Level that defines the lobe (see :func:`first_lobe`).
    unit : str, default "N"
        Unit of ``y``, carried into :meth:`PulseMetrics.to_dict` keys.
    hysteresis : float, default 0.0
        See :func:`first_lobe`.
    least_peak : float, default 0.0
        See :func:`first_lobe`.

    Returns
    -------
    PulseMetrics
    """
    t, y = _as_signal(t, y)
    start, end = first_lobe(t, y, threshold, hysteresis, least_peak)
    if np.isnan(start):
        return PulseMetrics(*(np.nan,) * 7, unit=unit)
    stop = t[-1] if np.isnan(end) else end
    t_peak, y_peak = peak(t, y, start, stop)
    in_lobe = (t >= start) & (t <= stop)
    return PulseMetrics(
        start=float(start),
        end=float(end),
        duration=float(end - start),
        peak_time=t_peak,
        peak=y_peak,
        rise_time=rise_time(t[in_lobe], y[in_lobe]) if in_lobe.sum() >= 2 else np.nan,
        impulse=impulse(t, y, start, stop),
        unit=unit,
    )


def relative_error(measured, true):
    """Signed relative error ``(measured - true) / true`` [-]."""
    measured, true = check_number("measured", measured), check_number("true", true)
    if true == 0:
        raise ParameterError("relative error is undefined for a true value of 0")
    return (measured - true) / true
