"""The baseline of the one pulse of a single trace, and how far it can be trusted.

The single-trace paths (``reconstruct``, ``fit``, ``dem-check compare``) read one impact
from one record. On a laboratory record the baseline under it is not the mean of a
pre-trigger: it drifts, wanders and hums, and the structure the sensor is mounted on
rings after the hit. :func:`pulse_baseline` finds the pulse, fits its local baseline
(:func:`contactlab.inverse.local_baseline.local_baseline`: a line through the quiet
samples just before it and, with the sensor's free ringing, the samples after its
contact; for a record that starts at its pulse,
:func:`contactlab.inverse.local_baseline.head_baseline`: the campaign's head level, a
line or a quadratic fitted with the free ringing after the contact and extrapolated
back) and says in words what it did and what it could not vouch for.

Why a status and notes in the result, not a warning: a warning is printed once and
lost in a batch, a JSON summary or a notebook that filters it, and the test suite turns
every warning into an error, so a record with a slight drift would stop a run where it
should only be labelled. The status travels with the numbers (``summary()``,
``to_dict()``, the command line's output), where a user reading the contact time reads
why it may be off.
"""

from dataclasses import dataclass

import numpy as np

from contactlab import signals
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.inverse._signal import (
    BASELINE_MIN_SAMPLES,
    RINGING_EXCESS,
    baseline,
    difference_noise,
    lobe_around_peak,
)
from contactlab.inverse.lobe_onset import single_onset
from contactlab.inverse.local_baseline import PRE_PERIODS, head_baseline, local_baseline
from contactlab.inverse.single_crosstalk import single_impact_crosstalk
from contactlab.signals import SPREAD_MIN_SAMPLES

__all__ = [
    "DRIFT_SIGMAS",
    "RINGING_EXCESS",
    "PulseBaseline",
    "describe_window",
    "difference_noise",
    "pulse_baseline",
]

ONSET_MARGIN = 0.25
"""Sensor periods between the baseline's end and the pulse's detected onset [-]: the
sensor's rise delays the threshold crossing by less than a quarter period, so the
samples before that hold no force (the Tikhonov window starts there as well)."""

BLOCK_PERIODS = 16
"""Block of the running baseline that finds a pulse in a record without a pre-trigger,
in sensor periods [-] (at least 16 samples): long against a contact and its rise, short
against drift."""

LOCAL_PERIODS = 20
"""Sensor periods on either side of a pulse whose median is the level its lobe is read
from, in a record without a pre-trigger [-]."""

DRIFT_SIGMAS = 1.0
"""A baseline that changes by more than this many noise standard deviations across the
pulse is reported as drifting [-]: a constant baseline would then be off by more than
the noise, and the line removed holds only if the drift is smooth over the fit. For a
record that starts at its pulse, the change is that of the drift the head level left:
a line through its residual after the contact, extrapolated back to the record's first
sample (:attr:`~contactlab.inverse.local_baseline.LocalBaseline.drift`)."""

DEGREE_NAMES = {1: "line", 2: "quadratic"}
"""Names of the head level's polynomial degrees, for the notes."""


@dataclass(frozen=True, eq=False)
class PulseBaseline:
    """The local baseline of a single trace's pulse (SI units, signal unit N)."""

    values: np.ndarray
    """The baseline at every sample [N]."""
    noise: float
    """Standard deviation of the record about the baseline [N], before the pulse (after
    it, from the free-ringing fit, for a short pre-trigger)."""
    onset: float
    """The pulse's onset [s]: its crossing of ``k`` noise sigmas (the windows start from
    it)."""
    window: tuple
    """The baseline window fitted before the pulse ``[start, end)`` [s]: the last
    :data:`~contactlab.inverse.local_baseline.PRE_PERIODS` sensor periods before it
    (empty, after the pulse, for a short pre-trigger); ``noise`` is read there."""
    contact: tuple
    """The window the contact lies in ``(start, end)`` [s]: a quarter sensor period
    before the onset to one lobe-length after the end of the signal's largest lobe."""
    post: tuple
    """The post-contact window fitted with the sensor's free ringing ``[start, end]`` [s]."""
    drift: float
    """The baseline's change across the pulse [N]; with a short pre-trigger, the drift
    the head level left, extrapolated back to the record's first sample."""
    post_noise: float
    """Residual of the free ringing and the line after the contact [N] (rms)."""
    status: str
    """``"ok"``, or the flags that apply, comma-separated: ``short pre-trigger``,
    ``drifting baseline``, ``not free ringing`` (judged against the noise before the
    pulse, or with a short pre-trigger against :func:`difference_noise`, after the
    crosstalk's removal), ``no structure mode`` (not free ringing, and no structure
    mode was significant: nothing removed), ``onset not fitted`` (the first touch is
    the crossing)."""
    notes: tuple
    """One sentence per flag, with the numbers, and one naming the structure modes
    removed."""
    crosstalk: object = None
    """The :class:`~contactlab.inverse.crosstalk.Crosstalk` removed (included in
    ``values``), or None when its removal was off or the ringing too short."""
    head: tuple = ()
    """With a short pre-trigger: the head level's fit window and degree ``(start [s],
    end [s], degree)`` (:attr:`~contactlab.inverse.local_baseline.LocalBaseline.head`);
    empty otherwise."""
    first_touch: object = None
    """The :class:`~contactlab.inverse.lobe_onset.FirstTouch`: the pulse's first touch
    [s] fitted on its whole lobe with the contact family read on it (its Cramér-Rao
    bound with it), or the crossing ``onset`` with the reason (status ``onset not
    fitted``); None when not asked for."""


def _onset_back(t, distance, level, peak):
    """The last crossing of ``level`` by ``distance`` before sample ``peak`` [s]."""
    below = np.flatnonzero(distance[: peak + 1] <= level)
    if below.size == 0:
        return float(t[0])
    i = int(below[-1])
    if i == peak:
        return float(t[i])
    d0, d1 = distance[i], distance[i + 1]
    return float(t[i] + (level - d0) * (t[i + 1] - t[i]) / (d1 - d0))


def _pulse_without_pretrigger(t, y, sensor):
    """The largest pulse of a record without a pre-trigger: its peak (sample), the start
    of its lobe [s] and the running baseline's level at every sample.

    The peak is the largest residual of the running baseline
    (:func:`contactlab.signals.running_baseline`, which follows drift); the lobe is the
    run of samples on one side of the median of :data:`LOCAL_PERIODS` sensor periods on
    either side of it (mostly baseline and the ringing, which is symmetric about it).
    The running baseline's level (every sample) is returned as well: a pulse at the
    record's start has its lobe read about it, since a median leaves a drift's change
    over those periods in the lobe (a drift of 100 noise sigmas over 2.5 ms, curving,
    held the signal on the pulse's side of the median to the record's end).
    """
    dt = float(t[1] - t[0])
    width = min(max(16, round(BLOCK_PERIODS * sensor.period / dt)), t.size // 2)
    if width < SPREAD_MIN_SAMPLES:  # the running baseline's noise needs 16 per block
        raise ParameterError(
            f"the record holds {t.size} samples, too few to find its baseline without a "
            "pre-trigger; record a pre-trigger or pass baseline_window=(start, end) [s]"
        )
    running = signals.running_baseline(y, width)
    peak = int(np.argmax(np.abs(running.residual)))
    half = LOCAL_PERIODS * sensor.period
    near = (t >= t[peak] - half) & (t <= t[peak] + half)
    level = float(np.median(y[near]))
    start, _ = lobe_around_peak(t[near], y[near], level)
    return peak, start, running.level


def _windows(t, y, sensor, window, k):
    """Baseline window before the pulse (None if too short), onset [s] and the level the
    pulse's lobe is read from (a pulse at the record's start: the running baseline's, at
    every sample)."""
    margin = ONSET_MARGIN * sensor.period
    if window is None and int(signals.in_window(t, (float(t[0]), 0.0)).sum()) < (
        BASELINE_MIN_SAMPLES
    ):
        peak, start, running = _pulse_without_pretrigger(t, y, sensor)
        pre = (max(float(t[0]), start - margin - PRE_PERIODS * sensor.period), start - margin)
        if int(signals.in_window(t, pre).sum()) < BASELINE_MIN_SAMPLES:
            return None, start, running
        mean, noise, _ = signals.baseline(t, y, pre, name="baseline_window")
        return pre, _onset_back(t, np.abs(y - mean), k * noise, peak), mean
    mean, _, onset, pre = baseline(t, y, window, k)
    if window is None:  # an oscilloscope's pre-trigger holds the pulse's start: cut it
        pre = (pre[0], min(pre[1], onset - margin))
    if int(signals.in_window(t, pre).sum()) < BASELINE_MIN_SAMPLES:
        return None, onset, mean
    return pre, onset, mean


def _describe(base, pre, contact, noise, sensor, reference):
    """Status and notes of a fitted baseline (module constants); ``reference`` is the
    noise the post-contact residual is judged against [N]."""
    flags, notes = [], []
    if pre is None:
        first, last, degree = base.head
        flags.append("short pre-trigger")
        notes.append(
            f"fewer than {BASELINE_MIN_SAMPLES} samples before the pulse: the baseline under "
            f"it is a {DEGREE_NAMES[degree]} fitted with the sensor's free ringing on "
            f"{first:.6g} to {last:.6g} s, after the contact, and extrapolated back"
        )
    if abs(base.drift) > DRIFT_SIGMAS * noise and pre is None:
        flags.append("drifting baseline")
        notes.append(
            f"what the {DEGREE_NAMES[degree]} leaves after the contact still drifts: a line "
            f"through it on {base.post[0]:.6g} to {base.post[1]:.6g} s moves the baseline at "
            f"the record's start by {base.drift:+.3g} N ({abs(base.drift) / noise:.1f} noise "
            f"sigmas); the drift is not a {DEGREE_NAMES[degree]} over {first:.6g} to "
            f"{last:.6g} s (or a slow structure mode is left), and with nothing before the "
            "pulse the figures can be off by that much or more: record a pre-trigger"
        )
    elif abs(base.drift) > DRIFT_SIGMAS * noise:
        flags.append("drifting baseline")
        notes.append(
            f"the baseline changes by {base.drift:+.3g} N ({abs(base.drift) / noise:.1f} noise "
            f"sigmas) across the pulse ({contact[0]:.6g} to {base.post[0]:.6g} s); it is "
            f"removed as a line fitted before the pulse and on the ringing to "
            f"{base.post[1]:.6g} s, which holds for a drift smooth over that span"
        )
    if base.post_noise > RINGING_EXCESS * reference:
        where = "the noise before the pulse" if pre else "the record's sample-to-sample noise"
        flags.append("not free ringing")
        notes.append(
            f"after the contact ({base.post[0]:.6g} to {base.post[1]:.6g} s) the sensor's "
            f"free ringing leaves {base.post_noise:.3g} N rms, "
            f"{base.post_noise / reference:.1f} times {where}: crosstalk from the "
            f"structure, a second hit or a wrong sensor model (resonance "
            f"{sensor.resonance:.6g} Hz, damping ratio {sensor.damping_ratio:.3g}); the "
            "contact time and impulse may be off"
        )
    return ", ".join(flags) or "ok", tuple(notes)


def _crosstalk_notes(removed, status):
    """Status and notes of the crosstalk's removal (``removed`` None: not tried)."""
    if removed is None:
        return status, ()
    if removed.modes:
        return status, (
            f"structural crosstalk removed (modes found on the ringing after the contact, "
            f"response to this pulse): {removed.describe()}",
        )
    if "not free ringing" in status:
        return status + ", no structure mode", (
            "no structure mode below a quarter of the sensor resonance was significant in "
            "the ringing after the contact: nothing removed",
        )
    return status, ()


def pulse_baseline(t, y, sensor, window=None, k=5.0, *, crosstalk=True, first_touch=True):
    """Find the pulse of a single trace and fit its local baseline.

    Parameters
    ----------
    t, y : numpy.ndarray
        The record: time [s] (uniform, checked by the caller) and signal [N].
    sensor : Sensor
        The sensor (its period sets the windows; its resonance and damping ratio the
        free ringing fitted after the contact).
    window : (float, float), optional
        Baseline window ``[start, end)`` [s], used as given (a window that holds the
        pulse's start inflates the noise, which a fit's quality judgement then reports).
        Default: the samples before ``t = 0`` up to a quarter period before the onset;
        a record with fewer than 16 of them (no pre-trigger) takes the
        :data:`~contactlab.inverse.local_baseline.PRE_PERIODS` periods before the pulse
        it finds on its running baseline, and a record that starts at the pulse the
        head level fitted after the contact and extrapolated back
        (:func:`~contactlab.inverse.local_baseline.head_baseline`; status ``short
        pre-trigger``).
    k : float, default 5
        Onset threshold in noise standard deviations [-].
    crosstalk : bool, default True
        Remove the structure's crosstalk first
        (:func:`~contactlab.inverse.single_crosstalk.single_impact_crosstalk`: modes found on
        the ringing after the contact, their response to the pulse fitted before it and
        after the contact); the modes removed are named in ``notes``.
    first_touch : bool, default True
        Fit the first touch on the pulse's whole lobe
        (:func:`~contactlab.inverse.lobe_onset.single_onset`, on the record less the
        crosstalk removed; 0.2-0.5 s of CPU).

    Returns
    -------
    PulseBaseline

    Raises
    ------
    ParameterError
        A window with too few samples or without noise, no sample above the threshold,
        a record too short to find its pulse.
    """
    crosstalk = check_flag("crosstalk", crosstalk)
    first_touch = check_flag("first_touch", first_touch)
    pre, onset, reference = _windows(t, y, sensor, window, k)
    start, end = lobe_around_peak(t, y, reference)
    lobe = end - start  # the first guess of the contact's duration [s]
    contact = (max(onset - ONSET_MARGIN * sensor.period, float(t[0])), end + (end - start))
    if contact[1] >= float(t[-1]):
        raise ParameterError(
            f"the record ends at {t[-1]:.6g} s, inside the pulse's window {contact[0]:.6g} to "
            f"{contact[1]:.6g} s: nothing of the ringing after the contact is left to fit"
        )
    removed = None
    if crosstalk:
        end = pre[1] if pre else None
        removed = single_impact_crosstalk(t, y, sensor, onset, end, contact[1])
    clean = y if removed is None else y - removed.values
    if pre is None:  # nothing before the pulse: the head level, fitted after it
        base = head_baseline(t, clean, contact[1], float(t[-1]), sensor)
    else:
        base = local_baseline(t, clean, pre, contact[0], contact[1], float(t[-1]), sensor)
    noise = base.noise if pre else base.post_noise
    if not noise > 0.0:
        raise ParameterError(
            f"the baseline window {pre} s is exactly constant (no noise); pass "
            "baseline_window=(start, end) [s] over noisy samples"
        )
    # with nothing before the pulse, the post-contact residual is judged against the
    # noise of the sample differences (crosstalk of 2 %: 1.5-1.8 times it; white noise,
    # hum, 1/f noise, drift of 20 sigma and bounces 0.9-1.2, measured)
    reference = noise if pre else difference_noise(clean)
    status, notes = _describe(base, pre, contact, noise, sensor, reference)
    status, more = _crosstalk_notes(removed, status)
    touch = single_onset(t, clean, sensor, onset, lobe, noise) if first_touch else None
    if touch is not None and touch.note:
        status = "onset not fitted" if status == "ok" else status + ", onset not fitted"
        more = (*more, touch.note)
    return PulseBaseline(
        values=base.values if removed is None else base.values + removed.values,
        noise=float(noise),
        onset=float(onset),
        window=base.window,
        contact=contact,
        post=base.post,
        drift=base.drift,
        post_noise=base.post_noise,
        status=status,
        notes=notes + more,
        crosstalk=removed,
        head=base.head,
        first_touch=touch,
    )


def describe_window(pulse):
    """One line saying which samples gave the baseline (for a comparison's notes)."""
    if pulse.head:
        first, last, degree = pulse.head
        return (
            f"a {DEGREE_NAMES[degree]} fitted with the free ringing on {first:.6g} to "
            f"{last:.6g} s and extrapolated back under the pulse (no pre-trigger)"
        )
    return (
        f"a line fitted on {pulse.window[0]:.6g} to {pulse.window[1]:.6g} s before the pulse "
        f"and, with the free ringing, on {pulse.post[0]:.6g} to {pulse.post[1]:.6g} s after it"
    )
