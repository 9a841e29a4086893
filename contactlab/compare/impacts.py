"""Compare two impacts quantity by quantity (:func:`compare`), or a measured trace with
the model of its set-up (:func:`compare_trace`)."""

import numpy as np

from contactlab import metrics, signals
from contactlab.blas import with_one_blas_thread
from contactlab.compare.comparison import Comparison, quantity_row, waveform_row
from contactlab.compare.physics import physics_problems
from contactlab.compare.quantities import checked_tolerances, merged_tolerances, noise_tolerances
from contactlab.compare.waveform import (
    ALIGNMENTS,
    alignment_shift,
    sensor_signal,
    waveform_errors,
)
from contactlab.config import ImpactConfig
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.inverse._signal import BASELINE_MIN_SAMPLES
from contactlab.inverse.pulse import describe_window, pulse_baseline
from contactlab.inverse.sampling import HIT_PEAK_FRACTION
from contactlab.traces.prepare import noise_level, remove_baseline
from contactlab.traces.trace import Trace
from contactlab.validation import check_choice, check_number, check_text

__all__ = ["compare", "compare_trace"]

_SCALARS = (
    "contact_time",
    "peak_contact_force",
    "peak_sensor_force",
    "sensor_response_time",
    "restitution",
)
_SENSOR_SCALARS = {"peak_sensor_force": "peak", "sensor_response_time": "duration"}


def _scalar(obj, name, threshold, hysteresis, least_peak):
    """Value of a scalar quantity, or None when the object does not have it."""
    if name not in _SENSOR_SCALARS:
        return getattr(obj, name, None)  # a trace has no contact force or grain velocity
    if isinstance(obj, Trace):
        pulse = obj.metrics(threshold or 0.0, hysteresis, least_peak)
    elif threshold is not None:
        pulse = metrics.pulse_metrics(
            obj.t, obj.sensor_force, threshold, hysteresis=hysteresis, least_peak=least_peak
        )
    else:
        return getattr(obj, name)
    return getattr(pulse, _SENSOR_SCALARS[name])


def _label(obj):
    if isinstance(obj, Trace):
        return "trace"
    return str(getattr(obj, "method", type(obj).__name__))


def compare(
    a,
    b,
    tolerances=None,
    align="onset",
    threshold=None,
    labels=None,
    hysteresis=0.0,
    least_peak=0.0,
):
    """Compare two impacts quantity by quantity.

    Parameters
    ----------
    a : ImpactResult, EngineResult or Trace
        The impact under test (engine run, measurement).
    b : ImpactResult, EngineResult or Trace
        The reference (usually :func:`contactlab.simulate_impact`); relative errors are
        ``(a - b) / |b|``.
    tolerances : dict, optional
        Tolerances by quantity name, replacing :data:`DEFAULT_TOLERANCES` (same basis);
        unknown names raise ParameterError listing the valid ones.
    align : {"onset", "xcorr", None}, default "onset"
        Time alignment of the sensor signals before the waveform errors (see
        :mod:`contactlab.compare.waveform`). Durations and peaks do not depend on it.
    threshold : float, optional
        Read both sensor signals' first lobes with :func:`contactlab.metrics.pulse_metrics`
        at this level [N] (e.g. a few times a trace's noise). Default: each result's own
        reading (exact for :class:`~contactlab.ImpactResult`), and 0 for a trace.
    labels : (str, str), optional
        Names of a and b in the table and plot; default from their types.
    hysteresis : float, default 0
        With ``threshold``: how far below it a signal must fall to end its lobe [N] (see
        :func:`contactlab.metrics.first_lobe`).
    least_peak : float, default 0
        A trace's (and, with ``threshold``, a result's) lobes whose peak is under this
        fraction of the signal's largest value are passed over [-] (see
        :func:`contactlab.metrics.first_lobe`).

    Returns
    -------
    Comparison

    Examples
    --------
    >>> import contactlab as cl
    >>> law = cl.laws.LinearViscoelastic(1e5, 1.0)
    >>> grain = cl.Grain(diameter=5e-3, density=765.0)
    >>> res = cl.simulate_impact(grain, cl.Sensor.rigid(), law, 2.0)
    >>> compare(res, res).passed
    True
    """
    tolerances = merged_tolerances(tolerances)
    align = check_choice("align", align, ALIGNMENTS)
    if threshold is not None:
        threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    hysteresis = check_number("hysteresis", hysteresis, low=0.0, low_open=False, unit="N")
    least_peak = check_number(
        "least_peak", least_peak, low=0.0, low_open=False, high=1.0, high_open=True
    )
    if labels is None:
        labels = (_label(a), _label(b))
    elif isinstance(labels, str) or not isinstance(labels, tuple | list) or len(labels) != 2:
        raise ParameterError(f"labels must be two names; got {labels!r}")
    labels = tuple(check_text("labels", label) for label in labels)
    sig_a = sensor_signal(a, f"a ({labels[0]})")
    sig_b = sensor_signal(b, f"b ({labels[1]})")
    rows = []
    for name in _SCALARS:
        va = _scalar(a, name, threshold, hysteresis, least_peak)
        vb = _scalar(b, name, threshold, hysteresis, least_peak)
        missing = [lab for lab, v in zip(labels, (va, vb), strict=True) if v is None]
        note = f"not available: {' and '.join(missing)} has no {name}" if missing else ""
        rows.append(quantity_row(name, va, vb, tolerances[name], note))
    shift = alignment_shift(sig_a, sig_b, align)
    rms, largest, window = waveform_errors(sig_a, sig_b, shift)
    scale = float(np.max(np.abs(sig_b[1])))
    note = f"sensor signal, over b's peak {scale:.4g} N"
    rows.append(
        waveform_row("waveform_rms_error", rms, scale, tolerances["waveform_rms_error"], note)
    )
    rows.append(
        waveform_row("waveform_max_error", largest, scale, tolerances["waveform_max_error"], note)
    )
    return Comparison(rows, a, b, labels, align, shift, window, threshold)


def _without_baseline(trace, sensor, k, crosstalk):
    """The trace less its baseline, its noise [N] and the notes saying how.

    On a moving sensor the baseline is the pulse's local one
    (:func:`contactlab.inverse.pulse.pulse_baseline`: a line before the pulse and on the
    free ringing after it, with a status); a rigid sensor has no ringing to fit, and the
    mean of the samples before the trigger (or of the quietest stretch) is removed, as
    it is when the local baseline cannot be fitted (a noise-free trace; the status says
    why).
    """
    trigger = trace.metadata.get("trigger_time")
    trigger = 0.0 if trigger is None else trigger
    t, values = np.asarray(trace.t), np.asarray(trace.values)
    before = int(np.count_nonzero(t < trigger))
    window = (float(t[0]), trigger) if before >= BASELINE_MIN_SAMPLES else None
    status = "ok"
    if not sensor.is_rigid:
        try:
            pulse = pulse_baseline(
                t, values, sensor, window, k, crosstalk=crosstalk, first_touch=False
            )  # the baseline only: the waveforms are aligned by their own crossing
        except ParameterError as exc:  # e.g. a noise-free trace: no noise to fit against
            status = f"no local baseline ({exc})"
        else:
            step = {"step": "remove_baseline", "local baseline": describe_window(pulse)}
            text = f"removed: {describe_window(pulse)}"
            notes = {"baseline": text, "baseline status": pulse.status}
            notes.update({f"baseline note {i + 1}": note for i, note in enumerate(pulse.notes)})
            return trace.derive(step, values=values - pulse.values), pulse.noise, notes
    window = window or signals.quiet_window(t, values)
    noise = noise_level(trace, window)
    text = f"removed: the mean of {window[0]:.6g} to {window[1]:.6g} s"
    return remove_baseline(trace, window), noise, {"baseline": text, "baseline status": status}


def _passed_over(trace, threshold):
    """A note naming the lobes before the hit that the comparison passed over (none when
    the first lobe above the threshold is the hit's)."""
    t, y = np.asarray(trace.t), np.asarray(trace.values)
    first = metrics.first_lobe(t, y, threshold, threshold)[0]
    hit = metrics.first_lobe(t, y, threshold, threshold, HIT_PEAK_FRACTION)[0]
    if np.isnan(first) or first == hit:
        return {}
    before = t < hit
    return {
        "lobe note": (
            f"passed over lobes from {first:.6g} s to the hit at {hit:.6g} s: they peak at "
            f"{float(np.max(y[before])):.3g} N, under {HIT_PEAK_FRACTION:g} of the trace's "
            f"largest value {float(np.max(y)):.4g} N (a filter's pre-echo or noise, not the hit)"
        )
    }


@with_one_blas_thread
def compare_trace(
    trace, config, tolerances=None, align="onset", k=5.0, threshold=None, *, crosstalk=True
):
    """Compare a measured sensor trace with the model of an impact set-up.

    The trace's baseline is removed: a line fitted on its samples before the pulse (the
    pre-trigger, or the samples before the pulse it finds) and, with the sensor's free
    ringing, on the samples after the contact, so a drift or wander is removed as well
    (:func:`contactlab.inverse.pulse.pulse_baseline`; a trace that starts at the impact
    takes a line or quadratic fitted with the ringing after the contact and extrapolated
    back). Both sensor signals are then read at
    ``k`` times the trace's noise, so the measurement and the model are read alike. A
    lobe ends at its last crossing of that level before the signal is back at the
    baseline (hysteresis equal to the threshold), so noise on a slow rise or fall cannot
    cut it short. The lobe read is the first whose peak reaches
    :data:`~contactlab.inverse.sampling.HIT_PEAK_FRACTION` of the trace's largest value:
    smaller lobes before it (an acquisition filter's pre-echo, a noise excursion) are
    passed over, and ``lobe note`` names them.
    :attr:`Comparison.notes` says what was removed (``baseline``) and
    whether it can be trusted (``baseline status``: ``ok``, ``short pre-trigger``,
    ``drifting baseline``, ``not free ringing``; ``baseline note 1``, ... with the
    numbers).

    Parameters
    ----------
    trace : Trace
        The measured sensor signal in newtons (read it with ``sensitivity=``).
    config : contactlab.config.ImpactConfig
        The impact set-up (:func:`contactlab.config.load_config`); simulated with its
        ``[simulation]`` settings.
    tolerances : dict, optional
        See :func:`compare`; by default the engine tolerances widened by the trace's
        noise (:func:`noise_tolerances`), and any given here replace those.
    align : {"onset", "xcorr", None}, default "onset"
    k : float, default 5
        Lobe threshold in units of the baseline noise [-].
    threshold : float, optional
        Lobe threshold [N] instead of ``k`` times the noise.
    crosstalk : bool, default True
        Remove the structure's crosstalk with the baseline (modes found on the ringing
        after the contact, :func:`contactlab.inverse.single_crosstalk.single_impact_crosstalk`;
        ``baseline note N`` names the modes removed); False keeps it in the measured
        signal (a rigid sensor's trace has no local baseline and is not affected).

    Returns
    -------
    Comparison
        ``a`` is the measurement (after baseline removal), ``b`` the model;
        ``physics`` lists what in the measurement the grain cannot produce (its impulse
        from the trigger on over the grain's mass, its peak;
        :func:`contactlab.compare.physics.physics_problems`), which fails the comparison.
    """
    sensor_signal(trace, "trace")
    given = checked_tolerances(tolerances)
    if not isinstance(config, ImpactConfig):
        raise ParameterError(
            "config must be a contactlab.config.ImpactConfig (from load_config or "
            f"load_preset); got {type(config).__name__}"
        )
    k = check_number("k", k, low=0.0, low_open=False)
    crosstalk = check_flag("crosstalk", crosstalk)
    trace, noise, notes = _without_baseline(trace, config.sensor, k, crosstalk)
    if threshold is None:
        threshold = k * noise
    model = config.simulate()
    tolerances = {**noise_tolerances(noise, model.peak_sensor_force), **given}
    result = compare(
        trace,
        model,
        tolerances,
        align,
        threshold,
        ("measured", "model"),
        hysteresis=threshold,
        least_peak=HIT_PEAK_FRACTION,
    )
    notes["lobe threshold [N]"] = threshold
    notes.update(_passed_over(trace, threshold))
    result.notes.update(notes)
    velocity_change = metrics.impulse(trace.t, trace.values, 0.0) / config.grain.mass
    result.physics = physics_problems(config.grain, float(np.max(trace.values)), velocity_change)
    return result
