"""Finding every impact in a long record: noise floor, detection, segmentation, overlaps.

A record holds impacts separated by stretches without one. The steps, all on the record
in newtons:

0. **Offset steps** (:func:`dem_check.campaign.step_runs.search_steps`): after a first
   pass (steps 1-3), level changes that persist are found on runs that are one or two
   steps, on the period means outside the impacts, and on runs from the record's start
   or to its end; each is taken off the record and listed in :attr:`Detection.steps`
   with status ``"offset step"``; searched again on what is left (up to ``PASSES``),
   then steps 1-6 run on it. Not with fewer than :data:`RESOLVED_PERIOD_SAMPLES` samples
   per sensor period.
1. **Baseline and local noise** (:mod:`dem_check.campaign.noise`): a running baseline of
   block medians follows drift, wander, offset steps and slow hum; the local noise is
   the MAD of the residual per block (the largest of a block and its neighbours), so hum,
   wander and a structure's ringing raise their own threshold. No pre-trigger and no
   quiet stretch need to be known.
2. **Smoothing.** A Gaussian kernel whose -3 dB frequency is
   :data:`~dem_check.campaign.noise.CUTOFF_FACTOR` times the sensor's resonance, for
   detection and timing (a positive kernel: no overshoot, so no false lobe before a
   sharp rise), and a zero-phase Butterworth low-pass at the same frequency, flat in its
   pass band, for the peak.
3. **Detection.** An impact is a run of the smoothed residual above the noise floor
   (:data:`FLOOR_SIGMAS` local sigmas) that reaches the detection threshold: ``k`` local
   sigmas, ``k`` set so that Gaussian noise crosses it by chance in fewer than
   :data:`FALSE_ALARMS` records (6.2 sigma for 1.5 million samples, never below 5). Its
   **significance** is its peak over the local noise. The run ends once the signal has
   stayed under the floor for :data:`QUIET_PERIODS` sensor periods. A user's
   ``min_force`` [N] and ``min_separation`` [s] turn weaker or closer candidates into
   rows with status ``"below min_force"`` / ``"too close"`` (listed, not analysed).
4. **Onset.** On the smoothed segment, the last crossing before the detection (searched back
   from where the impact reached the threshold) of :data:`ONSET_SIGMAS` times the noise of
   the segment's own baseline (the quiet samples just before the impact, at most
   :data:`BASELINE_PERIODS` periods). An impact with fewer than :data:`BASELINE_MIN_SAMPLES`
   quiet samples before it (a record that starts at the hit, or an impact right after
   another's ringing) takes its baseline from the quiet samples after its ringing decayed:
   status ``"short pre-trigger"``, analysed. The analysed impacts' onsets are then fitted
   (:mod:`dem_check.campaign.onsets`: a contact family's force through the sensor, on the
   whole first lobe), which the crossing lags.
5. **Overlaps.** Free ringing only decays. Where the envelope after the first lobe
   (largest value per sensor period) grows by more than :data:`GROWTH_FACTOR` (plus the
   noise floor) to the detection threshold, and the growth is a force's (the ringing
   about its running mean grows so too, or that mean stands at the threshold), a second
   impact started in the first one's ringing (:mod:`dem_check.campaign.growths`); where it
   does not, a lobe that stands over the threshold once the sensor's free ringing is
   fitted and taken off, and that the plate's ringing does not explain, is one too
   (:mod:`dem_check.campaign.ringing_lobes`). Both are flagged ``"overlap"``, never
   merged. Not with fewer than :data:`RESOLVED_PERIOD_SAMPLES` samples per sensor period
   (ringing not resolved).
6. **Clipping.** Samples held at the record's rail (:mod:`dem_check.campaign.clipping`)
   inside an impact flag it ``"clipped"``: its peak is a lower bound; impacts its
   ringing holds (step 5) are listed ``"overlap"``, not analysed.
"""

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np

from contactlab import signals
from contactlab.bodies import Sensor
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.traces import Trace
from contactlab.traces.prepare import check_trace
from dem_check.campaign.clipping import clipped_samples
from dem_check.campaign.growths import GROWTH_FACTOR, later_impacts
from dem_check.campaign.limits import apply_limits, check_limits
from dem_check.campaign.noise import (
    CUTOFF_FACTOR,
    FALSE_ALARMS,
    FLOOR_SIGMAS,
    ONSET_SIGMAS,
    QUIET_MIN_SAMPLES,
    QUIET_PERIODS,
    NoiseFloor,
    candidate_runs,
    noise_floor,
)
from dem_check.campaign.onsets import NO_CONTACT, first_touches
from dem_check.campaign.plate_swings import STATUS as SWING
from dem_check.campaign.plate_swings import negative_swing
from dem_check.campaign.ringing_lobes import lobe_under_ringing
from dem_check.campaign.step_ringing import difference_sigma
from dem_check.campaign.step_runs import search_steps
from dem_check.campaign.steps import LEAST_HEIGHT, PASSES, remove_steps, settle_steps

__all__ = [
    "ANALYSED",
    "BASELINE_MIN_SAMPLES",
    "CUTOFF_FACTOR",
    "FALSE_ALARMS",
    "FLOOR_SIGMAS",
    "GROWTH_FACTOR",
    "NOT_IMPACTS",
    "ONSET_SIGMAS",
    "Detection",
    "ImpactWindow",
    "NoiseFloor",
    "check_limits",
    "find_impacts",
    "noise_floor",
]

ANALYSED = ("ok", "short pre-trigger", "overlap, neighbour held out", "overlap, ringing subtracted")
"""Impact statuses that are analysed (signal numbers, reconstruction, fit); the last two
are impacts flagged ``"overlap"`` here and read apart by :mod:`dem_check.campaign.overlaps`."""

NOT_IMPACTS = ("offset step", SWING, NO_CONTACT)
"""Statuses of the rows that are listed with why but are no impact: :attr:`Detection.steps`,
:attr:`Detection.swings` and :attr:`Detection.unconfirmed`."""

TAIL_PERIODS = 16.0
"""Quiet sensor periods kept after an impact's ringing has decayed (up to the next
impact's run) [-], at least :data:`BASELINE_MIN_SAMPLES` * 2 samples: the
reconstruction reads the signal to three periods past a window that may end a
lobe-length after the main lobe, and a short pre-trigger's baseline lies there."""

BASELINE_PERIODS = 20.0
"""Longest baseline taken before an impact [sensor periods] (at least 4 *
:data:`BASELINE_MIN_SAMPLES` samples): enough samples for the noise (to a few per cent) without
reaching back into an older impact."""

BASELINE_MIN_SAMPLES = 16
"""Fewest baseline samples (as :func:`contactlab.inverse.reconstruct_force` requires)."""

RESOLVED_PERIOD_SAMPLES = 4
"""Fewest samples per sensor period for the ringing envelope to be followed (overlap
check, step 5) and for offset steps to be looked for (step 0) [-]; a coarser record
cannot show the ringing grow, nor average it out over a period."""


@dataclass(frozen=True)
class ImpactWindow:
    """One impact found in a record: where it is, and whether it can be analysed."""

    onset: float
    """Start of the impact [s] (first crossing of the onset level; for the later impact
    of an overlap, the sensor period where the ringing grew)."""
    baseline_window: tuple
    """Local baseline ``[start, end)`` [s]: before the impact, or after its ringing for a
    ``"short pre-trigger"``."""
    first: int
    """Index of the first sample of the impact's segment."""
    stop: int
    """Index one past the segment's last sample (:data:`TAIL_PERIODS` after the ringing
    decayed, the next impact's run, or the record's end)."""
    end: float
    """Time the ringing had decayed [s]: :data:`QUIET_PERIODS` after the last sample above
    the noise floor (or the record's end)."""
    status: str
    """``"ok"``, ``"short pre-trigger"``, ``"overlap"``, ``"truncated"``, ``"no baseline"``,
    ``"negative"``, ``"overrange"``, ``"clipped"``, ``"below min_force"``, ``"too close"`` or
    ``"offset step"`` (a row of :attr:`Detection.steps`), ``"structure ringing"`` (a row
    of :attr:`Detection.swings`) or ``"no contact"`` (of :attr:`Detection.unconfirmed`):
    those of :data:`ANALYSED` are analysed."""
    reason: str = ""
    """Why the status is not ``"ok"`` (empty when it is), and for an analysed impact
    whose onset could not be fitted, that it is the crossing and why."""
    significance: float = float("nan")
    """Peak of the smoothed signal over its local noise [-]."""
    peak: float = float("nan")
    """Peak of the smoothed signal [N] (a lower bound when ``"clipped"``)."""
    start: float | None = None
    """Where the impulse integral starts [s]: the baseline's end, or the segment's first
    sample for a ``"short pre-trigger"``."""
    onset_uncertainty: float = float("nan")
    """Standard deviation of a fitted ``onset`` [s] (:mod:`dem_check.campaign.onsets`)."""


@dataclass(frozen=True, eq=False)
class Detection:
    """The impacts of one record, with the record as they were found on."""

    floor: NoiseFloor
    impacts: list
    """:class:`ImpactWindow` list, in time order."""
    signal: Trace
    """The record without its running baseline [N]."""
    smoothed: Trace
    """The smoothed residual [N], for detection and timing."""
    lowpassed: Trace
    """The record low-passed [N], for peaks (equal to ``signal`` when not filtered)."""
    local_noise: np.ndarray = None
    """Local noise of the smoothed record at every sample [N]."""
    record: Trace = None
    """The record as given [N], its offset steps taken off (each analysed impact fits
    its own baseline on it)."""
    steps: list = ()
    """:class:`ImpactWindow` rows of the record's DC offset steps (status ``"offset
    step"``, ``peak`` the height [N]), in time order."""
    contact_family: tuple = None
    """``(name, damping ratio [-])`` the onset fit read (:mod:`dem_check.campaign.onsets`)."""
    swings: list = ()
    """:class:`ImpactWindow` rows of ``negative`` candidates the plate's ringing after an
    impact explains (status ``"structure ringing"``, :mod:`dem_check.campaign.plate_swings`),
    in time order: listed, not impacts."""
    unconfirmed: list = ()
    """:class:`ImpactWindow` rows of weak candidates whose lobe fit found no contact
    (status ``"no contact"``, :data:`dem_check.campaign.onsets.CONFIRM_SIGMAS`): listed,
    not impacts."""


def _samples(periods, sensor, dt, minimum):
    """``periods`` sensor periods in samples, at least ``minimum``."""
    return max(minimum, round(periods * sensor.period / dt))


def find_impacts(trace, sensor, *, min_force=None, min_separation=None, fit_onsets=True):
    """Every impact in a record, with its onset, local baseline, significance and status.

    Parameters
    ----------
    trace : Trace
        The record in newtons, uniformly sampled.
    sensor : Sensor
        A moving sensor: its period sets the time scales (blocks, quiet time, envelope)
        and its resonance the smoothing.
    min_force : float, optional
        Smallest peak of the smoothed signal [N] an impact must reach; weaker candidates
        get status ``"below min_force"``.
    min_separation : float, optional
        Shortest time between two impacts' onsets [s]; a candidate closer to the one
        before gets status ``"too close"``.
    fit_onsets : bool, default True
        Give each analysed impact the onset of a fit of its first lobe
        (:mod:`dem_check.campaign.onsets`; where it fails, the crossing with a note in
        ``reason``); ``False`` keeps the smoothed signal's crossing of
        :data:`ONSET_SIGMAS` (step 4), which lags the first touch.

    Returns
    -------
    Detection

    Raises
    ------
    ParameterError
        Not uniformly sampled, too short, without noise, or bad limits.
    """
    check_trace("trace", trace)
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a Sensor; got {type(sensor).__name__}")
    min_force, min_separation = check_limits(min_force, min_separation)
    fit_onsets = check_flag("fit_onsets", fit_onsets)
    stage = _candidates(trace, sensor)
    period = stage["scales"]["period"]
    steps, given = [], trace
    ring = (sensor, float(trace.t[1] - trace.t[0]))  # a step across an impact: its ringing
    least = LEAST_HEIGHT * difference_sigma(stage["finite"])  # smallest step [N]
    for _ in range(PASSES if period >= RESOLVED_PERIOD_SAMPLES else 0):
        # a period's mean averages its ringing out; a step taken off can leave the
        # next pass a run that shows another (one near the record's start)
        more = search_steps(stage["finite"], stage["runs"], period, stage["scales"]["hold"], ring)
        if not more:
            break
        steps, taken_back = settle_steps(steps + more, period, least)
        removed = {
            "step": "offset_steps_removed",
            "steps": [(float(given.t[s.index]), s.height) for s in steps],
        }
        trace = given.derive(removed, values=remove_steps(given.values, steps))
        stage = _candidates(trace, sensor)
        if taken_back:  # a pass took back a step an earlier one read: a next would redo it
            break
    floor, smoothed, ratio, runs = (stage[k] for k in ("floor", "smoothed", "ratio", "runs"))
    t = smoothed.t
    windows, swings, previous_end = [], [], 0
    for k, (first, last) in enumerate(runs):
        following = runs[k + 1][0] if k + 1 < len(runs) else t.size
        stop = min(last + stage["scales"]["hold"] + stage["scales"]["tail"], following, t.size)
        candidate = (previous_end, first, last, stop)
        look = functools.partial(lobe_under_ringing, trace, stage, sensor, run=(first, last))
        found = _classify(
            smoothed, ratio, candidate, stage["scales"], floor, stage["flagged"], look
        )
        previous_end = last + 1
        if found[0].status == "negative" and period >= RESOLVED_PERIOD_SAMPLES:
            why = negative_swing(trace, stage, (first, last), windows, following, sensor)
            if why:  # the plate's ringing after an impact: listed, not an impact
                swings.append(dataclasses.replace(found[0], status=SWING, reason=why))
                continue
        windows += found
    windows = apply_limits(windows, min_force, min_separation)
    found = Detection(
        floor,
        windows,
        stage["signal"],
        smoothed,
        stage["lowpassed"],
        stage["local"],
        trace,
        [_step_row(step, t) for step in steps],
        swings=swings,
    )
    if not fit_onsets or period < RESOLVED_PERIOD_SAMPLES:
        return found  # a sensor period of a few samples holds no rise to fit
    return dataclasses.replace(found, **first_touches(found, sensor, ANALYSED))


def _candidates(trace, sensor):
    """Noise floor, smoothed residual, its ratio to the local noise, time scales,
    flagged samples and candidate runs of a record (module steps 1-3)."""
    floor, signal, smoothed, lowpassed, local = noise_floor(trace, sensor)
    z = np.asarray(smoothed.values)
    dt = float(smoothed.t[1] - smoothed.t[0])
    scales = {
        "period": max(1, round(sensor.period / dt)),
        "hold": _samples(QUIET_PERIODS, sensor, dt, QUIET_MIN_SAMPLES),
        "tail": _samples(TAIL_PERIODS, sensor, dt, 2 * BASELINE_MIN_SAMPLES),
        "baseline": _samples(BASELINE_PERIODS, sensor, dt, 4 * BASELINE_MIN_SAMPLES),
        "spread": round(3.0 * floor.kernel / dt),  # the kernel's reach before a rise
    }
    ratio = np.abs(z) / np.maximum(local, np.finfo(float).tiny)
    finite = np.where(np.isfinite(trace.values), trace.values, 0.0)
    flagged = {
        "overrange": np.asarray(trace.metadata["overrange"], dtype=int),
        "clipped": clipped_samples(finite, floor.noise),
    }
    return {
        "floor": floor,
        "signal": signal,
        "smoothed": smoothed,
        "lowpassed": lowpassed,
        "local": local,
        "ratio": ratio,
        "scales": scales,
        "finite": finite,
        "flagged": flagged,
        "runs": candidate_runs(ratio, scales["hold"], floor.sigmas),
    }


def _step_row(step, t):
    """The candidates-table row of an offset step (status ``"offset step"``)."""
    at = float(t[step.index])
    return ImpactWindow(
        at,
        (np.nan, np.nan),
        step.window[0],
        step.window[1],
        at,
        "offset step",
        step.reason(t),
        significance=step.significance,
        peak=step.height,
    )


def _local_baseline(ratio, candidate, scales):
    """``(start, end)`` indices of the quiet samples just before the impact, or after its
    ringing (short pre-trigger), and whether it is after."""
    previous_end, first, last, stop = candidate
    quiet = np.flatnonzero(ratio[previous_end:first] <= FLOOR_SIGMAS)
    base_end = previous_end + (int(quiet[-1]) if quiet.size else 0) - scales["spread"]
    base_start = max(previous_end, base_end - scales["baseline"])
    if base_end - base_start >= BASELINE_MIN_SAMPLES:
        return base_start, base_end, False
    after = min(last + scales["hold"], stop)
    return after, min(stop, after + scales["baseline"]), True


def _onset(t, z, base, first, detected):
    """The onset [s]: the last crossing of :data:`ONSET_SIGMAS` baseline sigmas before
    the sample where the impact reached the detection threshold (interpolated), searched
    back from it (slow noise or wander crossing earlier is not the impact's start); the
    segment's first sample when the impact is already above the level there."""
    lo, hi = np.sort(np.searchsorted(t, base))  # the window's samples and one either side:
    near = slice(max(int(lo) - 1, 0), int(hi) + 1)  # the baseline checks those, not all
    mean, noise, _ = signals.baseline(t[near], z[near], base, name="baseline_window")
    if noise == 0.0:
        raise ParameterError("the local baseline is exactly constant")
    level = ONSET_SIGMAS * noise
    deviation = np.abs(z[first : detected + 1] - mean)
    below = np.flatnonzero(deviation <= level)
    if below.size == 0:
        return float(t[first])
    j = first + int(below[-1])
    d0, d1 = abs(z[j] - mean), abs(z[j + 1] - mean)
    return float(t[j] + (level - d0) * (t[j + 1] - t[j]) / (d1 - d0))


def _classify(smoothed, ratio, candidate, scales, floor, flagged, look):
    """The :class:`ImpactWindow` (one, or several for an overlap) of one run."""
    previous_end, first, last, stop = candidate
    t, z = smoothed.t, np.asarray(smoothed.values)
    run = z[first : last + 1]
    polarity = 1.0 if run.max() >= -run.min() else -1.0  # the main lobe's side
    detected = first + int(
        np.argmax(polarity * ratio[first : last + 1] * np.sign(run) > floor.sigmas)
    )
    hold = scales["hold"]
    truncated = last + hold > t.size
    rough = float(t[detected])
    end = float(t[min(last + hold, t.size - 1)])
    numbers = {
        "significance": float(ratio[first : last + 1].max()),
        "peak": float(polarity * np.max(polarity * run)),
    }
    base_start, base_end, after = _local_baseline(ratio, candidate, scales)
    segment_first = previous_end if after else base_start
    if base_end - base_start < BASELINE_MIN_SAMPLES:
        reason = (
            f"only {max(base_end - base_start, 0)} quiet samples before the impact at "
            f"{rough:.6g} s and after its ringing (need {BASELINE_MIN_SAMPLES}): it is "
            "squeezed between the record's ends or other impacts"
        )
        return [
            ImpactWindow(
                rough, (np.nan, np.nan), detected, stop, end, "no baseline", reason, **numbers
            )
        ]
    base = (float(t[base_start]), float(t[base_end - 1]) + float(t[1] - t[0]))
    try:
        onset = _onset(t, z, base, segment_first, detected)
    except ParameterError as exc:  # the local noise is far above the record's
        reason = f"the local baseline of the impact at {rough:.6g} s is too noisy to time it: {exc}"
        return [
            ImpactWindow(rough, base, segment_first, stop, end, "no baseline", reason, **numbers)
        ]
    start = float(t[segment_first]) if after else base[1]

    def window(at, status="ok", reason=""):
        return ImpactWindow(
            at, base, segment_first, stop, end, status, reason, start=start, **numbers
        )

    if polarity < 0.0:
        reason = (
            f"the main lobe is negative ({run.min():.4g} N after {rough:.6g} s); a "
            "compressive contact gives a positive signal: check the sensor's polarity"
        )
        return [window(onset, "negative", reason)]
    if truncated:
        reason = (
            f"the record ends {t[-1] - onset:.4g} s after the onset, before the ringing "
            "decayed below the noise floor"
        )
        return [window(onset, "truncated", reason)]
    lobe_end = detected + int(np.argmax(z[detected : last + 1] <= 0.0))
    resolved = scales["period"] >= RESOLVED_PERIOD_SAMPLES  # the ringing can be followed
    growths = resolved and lobe_end > detected
    levels = (FLOOR_SIGMAS * floor.smoothed_noise, floor.sigmas)  # [N], [local sigmas]
    later = later_impacts(z, ratio, lobe_end, last, scales["period"], levels) if growths else []
    if growths and not later:  # a lobe under the ringing: the ringing fitted and taken off
        later = look((onset, lobe_end), following=stop)
    for kind, what in (
        ("overrange", "the instrument's range was exceeded, the true signal is unknown"),
        ("clipped", "held at the record's rail: the peak is a lower bound"),
    ):
        indices = flagged[kind]
        inside = indices[(indices >= segment_first) & (indices < stop)]
        if inside.size:
            reason = f"{inside.size} {kind} samples (first at {t[inside[0]]:.6g} s): {what}"
            ringing = f"in the ringing of the {kind} impact at {onset:.6g} s: not analysed alone"
            return [window(onset, kind, reason)] + [
                window(float(t[i]), "overlap", f"the ringing grew: an impact {ringing}")
                for i in later
            ]
    if not later:
        if after:
            reason = (
                f"fewer than {BASELINE_MIN_SAMPLES} quiet samples before the impact: the "
                f"baseline is read after its ringing, {base[0]:.6g} to {base[1]:.6g} s"
            )
            return [window(onset, "short pre-trigger", reason)]
        return [window(onset)]
    times = [onset, *(float(t[i]) for i in later)]
    out = []
    for k, at in enumerate(times):
        others = ", ".join(f"{other:.6g} s" for j, other in enumerate(times) if j != k)
        out.append(
            window(
                at,
                "overlap",
                f"impacts at {at:.6g} s and {others} overlap: one started before the "
                "other's ringing decayed, so neither is analysed alone",
            )
        )
    return out
