"""Impacts the ringing check flagged ``"overlap"``, read apart (issue 22).

Where the envelope of an impact's ringing grows (:mod:`dem_check.campaign.detection`,
step 5), a second impact began in it: both are flagged ``"overlap"``. Their contacts do
not overlap (the second began after the first one's main lobe), so each is read alone,
in time order, with the ordinary analysis (:func:`dem_check.campaign.analysis.read_impact`):

- the next impact is **held out**: from :data:`HOLD_PERIODS` sensor periods before its
  onset (which, not analysed, is where the ringing grew: it lags the touch) the record
  is replaced by this impact's line and free ringing. Both are fitted from
  :data:`POST_MARGIN` periods after its first lobe to the next contact's decayed
  ringing, together with the next impact's lobe (its contact family's force through
  the sensor: :func:`dem_check.campaign.overlap_fit.joint_ringing`), so the ringing is
  read through the next impact instead of extrapolated from the few periods before it.
  Where that leaves the reconstruction mostly modelled samples (its window spans two
  lobe-lengths), it can fail: the impact then keeps its signal's numbers and its reason
  says so;
- from the second impact on, the free ringing of the impact before (that fit's) is
  **subtracted** from the record and from its smoothed and low-passed traces (the same
  filters, :func:`dem_check.campaign.noise.record_filters`), from a period before the
  ringing's origin (the next segment starts at that origin: its filtered traces see no
  step there; the held-out fill, from ``hold`` on, is the same ringing); the impact's
  baseline window is the stretch between that origin and its own onset. Its onset is
  fitted as an analysed impact's (:func:`dem_check.campaign.onsets.record_onsets`, with
  the record's contact family), and its peak signal, impulse, contact force and contact
  time are the joint fit's (the ordinary reading's local baseline has only that short
  window before the impact: at half the velocity 0.2 ms after the first it read the
  impulse up to 8 % high, with the true ringing subtracted too). That fit assumes the
  record's contact family: its chi-squared under the record's noise is checked
  (:func:`dem_check.campaign.overlap_fit.checked_joint_ringing`); where it is rejected
  every family is fitted and one that agrees is kept (both impacts' reasons say so);
  where none agrees the later impact keeps its ordinary reading's numbers with status
  :data:`UNRELIABLE` (not analysed) and a reason that says why.

The first impact of a group gets status ``"overlap, neighbour held out"``, each later one
``"overlap, ringing subtracted"``, with a reason that says what was held out or taken
off; both are analysed (:data:`dem_check.campaign.detection.ANALYSED`). An impact that
cannot be read apart keeps ``"overlap"`` and its reason says why: too few quiet samples
between the previous contact and its onset, or an impact before it that could not be
read (the analysis flagged it, no contact family was read, the joint fit failed, or the
record is too coarse for the ringing to be fitted). A second contact that starts within
a period of the first lobe's end is not seen by the ringing check (the analysis flags it
by its impulse) and is not read apart.
"""

import dataclasses

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_onset import SCAN_DURATIONS
from contactlab.inverse.local_baseline import free_ringing
from dem_check.campaign.analysis import ONSET_MARGIN, read_impact, window_row
from dem_check.campaign.detection import BASELINE_MIN_SAMPLES
from dem_check.campaign.noise import record_filters
from dem_check.campaign.onsets import record_onsets
from dem_check.campaign.overlap_fit import AFTER_PERIODS, checked_joint_ringing
from dem_check.campaign.plausibility import physics_status

__all__ = ["HELD_OUT", "HOLD_PERIODS", "SUBTRACTED", "UNRELIABLE", "separate_overlaps"]

HELD_OUT = "overlap, neighbour held out"
"""Status of the first impact of an overlapping group, read apart (analysed)."""

SUBTRACTED = "overlap, ringing subtracted"
"""Status of a later impact of an overlapping group, read on the record less the
previous impact's fitted free ringing (analysed)."""

UNRELIABLE = "overlap, unreliable"
"""Status of a later impact of an overlapping group whose joint fit with the impact
before it agrees with the record's noise for no contact family
(:func:`dem_check.campaign.overlap_fit.checked_joint_ringing`): its row keeps the numbers
of its reading on the record less the fitted ringing, which the status and reason mark
as not to be trusted (not analysed)."""

HOLD_PERIODS = 2.0
"""Sensor periods before a later impact's detected onset from which its signal is held
out [-]. Its onset is where the ringing envelope grew, the first sample above the
growth level in a sensor period's window of a grid: the touch can lie up to that window
and the one before it earlier."""


POST_MARGIN = 1.0
"""Sensor periods after an impact's first lobe (the smoothed signal back at its
baseline) from which its free ringing is fitted before a later impact [-]: the lobe
can end a little before the contact does (a period, as the analysis reads the impulse
past its contact's end), and the joint fit models free ringing there. Measured with the
ringing fitted alone between the two (before the joint fit), on a pair 0.2 ms apart
(1:0.5, one seed): from the lobe's end the second impact's impulse was 10 % high, from a
period after it 8 %."""


def _groups(detection):
    """Indices of the impacts of each overlapping group (the windows of one run share
    its segment), in time order."""
    groups = {}
    for k, window in enumerate(detection.impacts):
        if window.status == "overlap":
            groups.setdefault((window.first, window.stop), []).append(k)
    return [ks for ks in groups.values() if len(ks) > 1]


def _less(detection, ringing):
    """The detection with the modelled ``ringing`` [N] (every sample of the record)
    taken off its record and its levelled, smoothed and low-passed traces."""
    step = {"step": "overlap_ringing_subtracted"}
    trace = detection.record.derive(step, values=ringing)
    smoothed, lowpassed = record_filters(trace, detection.floor)
    return dataclasses.replace(
        detection,
        record=detection.record.derive(step, values=detection.record.values - ringing),
        signal=detection.signal.derive(step, values=detection.signal.values - ringing),
        smoothed=detection.smoothed.derive(
            step, values=detection.smoothed.values - smoothed.values
        ),
        lowpassed=detection.lowpassed.derive(
            step, values=detection.lowpassed.values - lowpassed.values
        ),
    )


def _held_out(detection, window, hold, later, limit, sensor, family, noise):
    """The detection with the samples of ``window``'s segment from index ``hold`` on (the
    next impact's) replaced by this impact's line and free ringing, fitted with the next
    impact's lobe (:func:`dem_check.campaign.overlap_fit.joint_ringing`) from
    :data:`POST_MARGIN` periods after this impact's first lobe to the next contact's
    decayed ringing (at most to ``limit`` [s]: the segment's end, or where a third impact
    is held out): the analysis then reads a record that holds this impact alone; and
    that fit, checked against the record's ``noise``
    (:class:`dem_check.campaign.overlap_fit.CheckedJoint`: its free ringing is what is
    taken off the next impact)."""
    part = slice(window.first, window.stop)
    t = np.asarray(detection.record.t[part])
    y = np.asarray(detection.record.values[part], dtype=float)
    smooth = np.asarray(detection.smoothed.values[part])
    cut = hold - window.first
    base = window.baseline_window
    level = float(np.mean(smooth[(t >= base[0]) & (t < base[1])]))
    top = int(np.argmax(smooth[:cut]))
    lobe_end = float(t[top + int(np.argmax(smooth[top:cut] <= level))])  # back to the baseline
    post = lobe_end + POST_MARGIN * sensor.period
    length = lobe_end - window.onset  # the second contact's first guess
    stop = later.onset + (SCAN_DURATIONS[-1] * length) + AFTER_PERIODS * sensor.period
    fitted = (t >= post) & (t <= min(stop, limit))
    if family is None:
        raise ParameterError("no contact family was read for the next impact's lobe")
    checked = checked_joint_ringing(
        t[fitted], y[fitted], (later.onset, length), sensor, family, noise
    )
    other = np.zeros(np.asarray(detection.record.t).size)
    other[window.first + cut : window.stop] = (y - checked.joint.values(t, sensor))[cut:]
    return _less(detection, other), checked


def _window(detection, window, first, stop, base, sensor, noise):
    """The impact as one alone on ``[first, stop)``: its peak and significance read
    there, its onset fitted, its baseline ending before that onset; or the reason it
    cannot be read."""
    t = np.asarray(detection.record.t)
    smooth = np.asarray(detection.smoothed.values)
    at = first + int(np.searchsorted(t[first:stop], window.onset))
    top = at + int(np.argmax(smooth[at:stop]))
    alone = dataclasses.replace(
        window,
        first=first,
        stop=stop,
        end=min(window.end, float(t[stop - 1])),
        baseline_window=base,
        start=base[1],
        status="ok",
        reason="",
        peak=float(smooth[top]),
        significance=float(smooth[top] / detection.local_noise[top]),
    )
    family = detection.contact_family
    onsets, notes, name, damping, spreads, _ = record_onsets(
        detection, [alone], sensor, noise, family
    )
    family = family or (None if name is None else (name, damping))
    end = min(base[1], onsets[0] - ONSET_MARGIN * sensor.period)
    quiet = int(np.count_nonzero((t >= base[0]) & (t < end)))
    if quiet < BASELINE_MIN_SAMPLES:
        why = (
            f"only {quiet} quiet samples between {base[0]:.6g} s and its onset "
            f"{onsets[0]:.6g} s (need {BASELINE_MIN_SAMPLES})"
        )
        return None, why, family
    alone = dataclasses.replace(
        alone,
        onset=onsets[0],
        onset_uncertainty=spreads[0],
        reason=notes[0],
        baseline_window=(base[0], end),
        start=end,
    )
    return alone, "", family


def _joint_numbers(checked, grain, row):
    """The columns of a later impact read from the joint fit of the impact before it
    (``checked``, :class:`dem_check.campaign.overlap_fit.CheckedJoint`): peak signal,
    impulse, contact force and contact time of its contact family's force fitted with
    that impact's ringing and a line, its velocity change, the physics check on them,
    and the reason saying so; or, where no family's fit agreed with the record's noise,
    the row as read (on the record less the fitted ringing, its baseline the short
    window before it) with status :data:`UNRELIABLE` and the reason saying why."""
    joint = checked.joint
    check = checked.note()
    if not checked.accepted:
        note = (
            f"{check}: its numbers are not the joint fit's but its reading on the record "
            "less the fitted ringing, whose baseline is the short window before it (up to "
            "8 % off at 0.2 ms from the impact before it, docs/campaign.md): unreliable"
        )
        return {"status": UNRELIABLE, "reason": "; ".join(r for r in (row["reason"], note) if r)}
    out = {
        "peak_sensor_force [N]": joint.peak_signal,
        "impulse [N*s]": joint.impulse,
        "peak_contact_force [N]": joint.amplitude,
        "contact_time [s]": joint.duration,
    }
    if grain is not None:
        out["velocity_change [m/s]"] = joint.impulse / grain.mass
    note = (
        "peak signal, impulse, contact force and contact time from its contact family's "
        f"force fitted with the previous impact's line and free ringing (rms residual "
        f"{joint.rms:.3g} N; the record's noise {row['noise [N]']:.3g} N; {check})"
    )
    out["reason"] = "; ".join(r for r in (row["reason"], note) if r)
    return {**out, **physics_status({**row, **out}, grain)}


def _read_group(detection, group, sensor, options):
    """Rows (and gallery traces) of one overlapping group, read in time order."""
    t = np.asarray(detection.record.t)
    dt = float(t[1] - t[0])
    windows = [detection.impacts[k] for k in group]
    out, current, base, before = {}, detection, windows[0].baseline_window, None
    first = windows[0].first
    for j, (k, window) in enumerate(zip(group, windows, strict=True)):
        later = windows[j + 1] if j + 1 < len(windows) else None
        hold = window.stop
        if later is not None:
            hold = int(np.searchsorted(t, later.onset - HOLD_PERIODS * sensor.period))
        alone, why, family = _window(current, window, first, hold, base, sensor, options["noise"])
        if alone is None:
            break
        alone = dataclasses.replace(alone, stop=window.stop, end=window.end)
        try:
            reading, local = current, None
            if later is not None:
                limit = later.end
                if j + 2 < len(windows):  # a third impact: the fit ends where it is held out
                    limit = windows[j + 2].onset - HOLD_PERIODS * sensor.period
                reading, local = _held_out(
                    current, alone, hold, later, limit, sensor, family, options["noise"]
                )
            row, traces, _ = read_impact(
                dataclasses.replace(reading, impacts=[alone]), alone, sensor, **options
            )
        except (ParameterError, ValueError, np.linalg.LinAlgError) as error:
            # a reading the ordinary analysis was not built for (a window with no
            # samples between the contact and the held-out ones): flagged, with the error
            why = f"reading it alone failed ({type(error).__name__}: {error})"
            break
        parts, status = [], HELD_OUT
        if before is not None:
            status = SUBTRACTED
            parts.append(
                f"the free ringing of the impact at {before[0]:.6g} s (fitted from "
                f"{before[1]:.6g} s with this impact's lobe) subtracted, the baseline read from "
                f"{alone.baseline_window[0]:.6g} to {alone.baseline_window[1]:.6g} s"
            )
        if later is not None:
            parts.append(
                f"the impact at {later.onset:.6g} s held out: from {t[hold]:.6g} s the record "
                "is this impact's line and free ringing, fitted with the next impact's lobe"
            )
            if local.rejected is not None:
                parts.append(local.note())
        how = "; ".join(parts)
        note = f"overlap read apart: {how}"
        if row["status"] == "ok" and before is not None:
            row.update(_joint_numbers(before[2], options["grain"], row))
            status = row["status"] if row["status"] == UNRELIABLE else status
        elif row["status"] == "reconstruction failed" and later is not None:
            # the held-out samples (the model, without noise) fill most of the record
            # the reconstruction reads: its signal numbers stand, its contact is not given
            row["reason"] = f"no contact force or contact time: {row['reason']}"
            row["status"] = "ok"
        if row["status"] == "ok":
            row["status"] = status
        row["reason"] = "; ".join(r for r in (note, row["reason"]) if r)
        out[k] = (row, traces)
        if later is None or row["status"] != status:
            why = "the impact before it was not read apart"
            break
        ringing = np.zeros(t.size)
        # from a period before the ringing's origin: the filters of the next segment,
        # which starts at that origin, see no step there (the held-out fill, from ``hold``
        # on, is this ringing too)
        joint = local.joint
        free = t >= joint.start - sensor.period
        ringing[free] = free_ringing(t[free], joint.start, joint.ringing, sensor)
        current = _less(current, ringing)
        first = int(np.searchsorted(t, joint.start))
        base = (float(t[first]), later.onset - HOLD_PERIODS * sensor.period + dt)
        before = (alone.onset, joint.start, local)
    for k, window in zip(group, windows, strict=True):
        if k not in out:
            row = window_row(window)
            reason = f"{row['reason']}; not read apart: {why}"
            out[k] = ({**row, "significance [-]": window.significance, "reason": reason}, None)
    return out


def separate_overlaps(
    detection, sensor, grain=None, fit=None, crosstalk=True, modes=None, noise=None
):
    """Read the record's overlapping impacts apart (module docstring).

    Parameters
    ----------
    detection : Detection
    sensor : Sensor
    grain, fit, crosstalk, modes, noise
        As for :func:`dem_check.campaign.analysis.analyse_impact` (``noise``: the
        record's, :func:`dem_check.campaign.local.record_noise`, or None).

    Returns
    -------
    dict
        ``{index in detection.impacts: (row, traces)}`` for every impact of an
        overlapping group (status :data:`HELD_OUT`, :data:`SUBTRACTED`, another the
        analysis gave, or ``"overlap"`` with why it was not read apart); ``traces`` for
        the gallery, or None.
    """
    options = {"grain": grain, "fit": fit, "crosstalk": crosstalk, "modes": modes, "noise": noise}
    out = {}
    for group in _groups(detection):
        out.update(_read_group(detection, group, sensor, options))
    return out
