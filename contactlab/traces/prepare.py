"""Preparing a measured trace: baseline, noise, onset, alignment, low-pass, force units.

Every function that changes a trace returns a new :class:`~contactlab.traces.trace.Trace`
and appends a record of itself (name and parameters) to ``metadata["history"]``. The
arithmetic is :mod:`contactlab.signals` on the trace's arrays (the inverse methods use the
same functions); this module chooses the window, checks what a ``Trace`` adds (uniform
sampling, units) and keeps the history.

The baseline is the pre-trigger part of the trace: by default the samples before
``metadata["trigger_time"]``, or before t = 0 when the file does not give a trigger time
(oscilloscopes write time relative to the trigger, so both usually mean the same). Pass
``pre_trigger=(start, end)`` [s] to choose the window explicitly, e.g. to exclude the
first rise of a pulse that starts before the trigger.
"""

import numpy as np

from contactlab import signals
from contactlab.errors import ParameterError
from contactlab.plausibility import check_plausible
from contactlab.traces.checks import uniform_interval
from contactlab.traces.trace import Trace
from contactlab.validation import check_number

__all__ = ["align", "detect_onset", "lowpass", "noise_level", "remove_baseline", "to_force"]


def check_trace(name, value):
    """Return ``value`` after checking it is a :class:`~dem_check.traces.Trace`."""
    if not isinstance(value, Trace):
        raise ParameterError(f"{name} must be a dem_check Trace; got {type(value).__name__}")
    return value


def _window(trace, pre_trigger):
    """The baseline window ``(start, end)`` [s]: from ``pre_trigger`` or the trigger."""
    check_trace("trace", trace)
    if pre_trigger is None:
        trigger = trace.metadata.get("trigger_time")
        end = 0.0 if trigger is None else float(trigger)
        return float(trace.t[0]), end
    try:
        start, end = pre_trigger
    except (TypeError, ValueError):
        raise ParameterError(f"pre_trigger must be (start, end) [s]; got {pre_trigger!r}") from None
    start = check_number("pre_trigger start", start, unit="s")
    end = check_number("pre_trigger end", end, low=start, unit="s")
    return start, end


def _baseline(trace, pre_trigger):
    """The baseline window [s] and its statistics (:class:`contactlab.signals.Baseline`)."""
    window = _window(trace, pre_trigger)
    return window, signals.baseline(trace.t, trace.values, window, name="pre_trigger")


def noise_level(trace, pre_trigger=None):
    """Noise of a trace: standard deviation (ddof=1) of its baseline, in its unit.

    Parameters
    ----------
    trace : Trace
    pre_trigger : (float, float), optional
        Baseline window ``[start, end)`` [s]; default: before the trigger (see module).

    Returns
    -------
    float
    """
    return _baseline(trace, pre_trigger)[1].noise


def remove_baseline(trace, pre_trigger=None):
    """Subtract the mean of the baseline (the pre-trigger samples).

    Parameters
    ----------
    trace : Trace
    pre_trigger : (float, float), optional
        As for :func:`noise_level`.

    Returns
    -------
    Trace
    """
    window, (mean, _, samples) = _baseline(trace, pre_trigger)
    step = {"step": "remove_baseline", "window [s]": window, "baseline": mean, "samples": samples}
    return trace.derive(step, values=trace.values - mean)


def detect_onset(trace, k=5.0, pre_trigger=None):
    """Time of the first crossing of ``k`` times the baseline noise [s].

    The onset is where ``|value - baseline mean|`` first exceeds ``k * noise_level``,
    interpolated linearly between samples. The search covers the whole trace, since a
    pulse may start before the trigger; with Gaussian noise a baseline sample exceeds 5
    sigma with probability 6e-7, so raise ``k`` for very long baselines.

    Parameters
    ----------
    trace : Trace
    k : float, default 5.0
        Threshold in units of the baseline standard deviation [-].
    pre_trigger : (float, float), optional
        Baseline window ``[start, end)`` [s]; default: before the trigger (see module).

    Returns
    -------
    float
        The onset: the interpolated time of the first crossing [s].

    Raises
    ------
    ParameterError
        If no sample exceeds the threshold.
    """
    k = check_number("k", k, low=0.0)  # named before a bad window, as in signals.detect_onset
    window = _window(trace, pre_trigger)
    return signals.detect_onset(trace.t, trace.values, window, k, name="pre_trigger")


def align(trace, onset):
    """Shift time so that ``onset`` [s] becomes t = 0.

    Parameters
    ----------
    trace : Trace
    onset : float
        Time that becomes zero [s], e.g. from :func:`detect_onset`.

    Returns
    -------
    Trace
    """
    check_trace("trace", trace)
    onset = check_number("onset", onset, unit="s")
    trigger = trace.metadata.get("trigger_time")
    return trace.derive(
        {"step": "align", "onset [s]": onset},
        t=trace.t - onset,
        metadata={"trigger_time": None if trigger is None else trigger - onset},
    )


def lowpass(trace, cutoff, order=4):
    """Zero-phase Butterworth low-pass filter.

    A Butterworth filter of ``order`` with -3 dB frequency ``cutoff`` is applied forward
    and backward (``scipy.signal.sosfiltfilt``, through :func:`contactlab.signals.lowpass`,
    which gives the exact response), so there is no phase shift (a pulse's timing is kept)
    and the magnitude response is squared: ``|H(f)|^2`` is 1/2 (-6 dB) at the cutoff and
    ``1 - (f / cutoff)^(2 order)`` to first order in the passband.

    Parameters
    ----------
    trace : Trace
        Uniformly sampled, without overrange samples.
    cutoff : float
        -3 dB frequency of the single pass [Hz], below the Nyquist frequency.
    order : int, default 4
        Butterworth order of the single pass.

    Returns
    -------
    Trace
    """
    check_trace("trace", trace)
    interval = uniform_interval(trace, "lowpass needs uniform sampling")
    values = signals.lowpass(trace.values, interval, cutoff, order)
    step = {
        "step": "lowpass",
        "cutoff [Hz]": float(cutoff),
        "order": int(order),
        "filter": "Butterworth, zero-phase (sosfiltfilt)",
    }
    return trace.derive(step, values=values)


def to_force(trace, sensitivity):
    """Convert a volt trace to newtons with the sensor's sensitivity.

    Parameters
    ----------
    trace : Trace
        In volts.
    sensitivity : float
        Sensor sensitivity [V/N] (e.g. 0.0225 for 22.5 mV/N), > 0; outside 1e-5 to 10 V/N
        (real sensors with their amplifiers) a PlausibilityWarning names the likely slip.

    Returns
    -------
    Trace
        In newtons, with ``metadata["sensitivity [V/N]"]`` and a history entry.
    """
    check_trace("trace", trace)
    sensitivity = check_number("sensitivity", sensitivity, low=0.0, unit="V/N")
    check_plausible("sensitivity", sensitivity, "sensitivity")
    if trace.unit != "V":
        raise ParameterError(
            f"sensitivity converts volts to newtons; the trace is in {trace.unit!r}, not 'V'"
        )
    with np.errstate(over="ignore"):
        values = trace.values / sensitivity
    overflow = np.isinf(values) & np.isfinite(trace.values)
    if overflow.any():
        raise ParameterError(
            f"sensitivity = {sensitivity!r} V/N turns {trace.values[overflow][0]!r} V into an "
            "infinite force: give the sensitivity in V/N (e.g. 0.0225 for 22.5 mV/N)"
        )
    return trace.derive(
        {"step": "to_force", "sensitivity [V/N]": sensitivity},
        values=values,
        unit="N",
        metadata={"sensitivity [V/N]": sensitivity},
    )
