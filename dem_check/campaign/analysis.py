"""Per-impact analysis: the signal's own numbers, the reconstructed force, an optional fit.

Each impact found by :func:`dem_check.campaign.detection.find_impacts` is read on its
segment (local baseline, impact, decayed ringing), less its own baseline: a line fitted
before the impact and on the sensor's free ringing after its contact
(:mod:`dem_check.campaign.local`; the samples of the record's other impacts held out),
so that drift, wander, hum and the slow part of 1/f noise are read on both sides of it.
With the record's white and 1/f noise levels
(:func:`dem_check.campaign.local.record_noise`, estimated once per record) the line and
ringing are fitted by generalised least squares and the noise under the pulse is
predicted from both sides (its conditional mean, :mod:`contactlab.inverse.noise_prediction`)
and taken off with the line before the peak signal and the impulse are read:

- ``onset_uncertainty [s]``: the standard deviation of the fitted onset under the
  record's white and 1/f noise, with the damping ratio read on the record
  (:mod:`dem_check.campaign.onsets`; NaN for a crossing, and the reason says why);
- ``sensor_response_time [s]``: the first lobe of the Gaussian-smoothed signal read with
  :func:`contactlab.metrics.first_lobe` at the onset level (five sigma of the local
  noise), with the same hysteresis so that only a return to zero ends it;
- ``peak_sensor_force [N]``: the largest value of the low-passed signal (flat pass band) in
  that lobe;
- ``impulse [N*s]``: the integral of the signal from the local baseline's end (a tenth
  of a sensor period before the onset) to a sensor period after the reconstructed
  contact's end (or a later contact's, which flags an ``"overlap"``), plus the fitted free ringing's
  integral from there in closed form. The sensor returns to rest, so this is the impulse
  of the true contact force (``integral S1 dt = integral S2 dt - m1 v1(end)``). With
  the crosstalk removed, its share of the impulse is left in where removing it adds
  more error than it takes off (:func:`dem_check.campaign.structure.removed_from_impulse`;
  columns ``crosstalk_impulse [N*s]``, ``crosstalk_impulse_error [N*s]``,
  ``crosstalk_impulse_removed``);
- ``peak_contact_force [N]`` and ``contact_time [s]``: from the true force reconstructed
  by :func:`contactlab.inverse.reconstruct_force` (Tikhonov, GCV on the problem
  whitened with the noise's AR model read on the baseline, a force value per twentieth
  of a sensor period) on the segment, its contact's edges read with the shape of the
  contact family the onset fit read on the record (:attr:`Detection.contact_family`),
  the peak and the contact (start, duration) read from that family's force fitted to
  the signal (:mod:`contactlab.inverse.reconstruct_family`);
- with a grain, ``velocity_change [m/s]`` = impulse / grain mass (``(1 + e) v`` for an
  impact at speed ``v`` and restitution ``e``: the impulse alone cannot separate them);
- with ``fit=`` a law name, :func:`contactlab.inverse.fit_contact` on the segment: each
  fitted parameter with its 95 % interval and identifiability flag (columns
  ``fit_<name> [unit]``, ``fit_<name>_low [unit]``, ``fit_<name>_high [unit]``,
  ``fit_<name>_identifiable``).
"""

import math
import warnings
from dataclasses import dataclass

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse import fit_contact, reconstruct_force
from contactlab.inverse.reconstruct import DEFAULT_MAX_UNKNOWNS
from contactlab.inverse.sampling import MIN_SAMPLES_PER_CONTACT
from contactlab.metrics import impulse
from contactlab.quantities import column
from dem_check.campaign.local import local_baseline, record_noise
from dem_check.campaign.plausibility import physics_status
from dem_check.campaign.segment_lobe import NoLobe, segment_lobe
from dem_check.campaign.structure import impact_crosstalk, record_modes, removed_from_impulse

__all__ = [
    "GALLERY_PERIODS",
    "MIN_SAMPLES_PER_CONTACT",
    "ImpactTraces",
    "analyse_impact",
    "read_impact",
    "window_row",
]


IMPULSE_EXCESS = 0.2
"""Largest excess of the segment's impulse over the reconstructed contact's [-]. One
impact gives the same impulse both ways (to the few per cent that noise allows); a
second impact or contact inside the segment that the ringing check could not see (it
began within a sensor period of the first lobe's end) adds its own, and the impact is
flagged ``"overlap"``."""

GRID_PER_PERIOD = 20.0
"""Force values per sensor period in the reconstruction [-]. A finer grid resolves
nothing more (the sensor passes little above twice its resonance) and lets generalised
cross-validation, which assumes white noise, fit 1/f noise as force: on a 2 MHz record
with 1/f noise as large as the white noise, 390 values (0.5 us) gave a peak 16 % high
(lambda 0.06), 200-50 values within 0.5 % (lambda 0.09-0.3). A trade-off: 40 values per
period read the paper's fig6 grain (white noise 0.9 %, 5 MHz) to 3.2 % instead of 5.3 %,
but realistic records worse (a reconstructed peak 10 % off at 100 sigma with 1/f noise of
0.3 sigma, against 1.1 %; ``benchmarks/bench_realistic.py``)."""

ONSET_MARGIN = 0.1
"""Sensor periods before the onset where the local baseline's window ends and the impulse
integral starts [-] (2.5 us for a 40 kHz sensor: more than the onsets' error, 1.3-1.6
samples at 1-2 MHz and 1.5 us at 5 MHz, 30-100 sigma). The detection's baseline window
ends 4-35 us before the onset; 1/f noise under the pulse is best read on the samples
nearest it, and each sample integrated before the onset adds noise only."""

RECONSTRUCTION_BASELINE = 5.0
"""Sensor periods of a baseline before the impact given to the reconstruction [-] (at
least 64 samples: its noise to 10 %)."""

RECONSTRUCTION_TAIL = 8.0
"""Sensor periods after the decayed ringing given to the reconstruction [-]: it reads
the signal to three periods past a window that ends a lobe-length after the main
lobe."""

NOT_GIVEN = object()
"""Default of ``analyse_impact``'s ``noise``: estimate it (``None`` means none)."""

ONSET_UNCERTAINTY = column("onset_uncertainty")
"""Column of an onset's standard deviation under the record's noise [s]
(:mod:`dem_check.campaign.onsets`)."""

GALLERY_PERIODS = 3.0
"""Sensor periods kept for the report's gallery before the reconstruction window and
after it [-]."""


@dataclass(frozen=True, eq=False)
class ImpactTraces:
    """The signal and reconstructed force of one impact, cropped for the report."""

    t: np.ndarray
    """Time [s] (the record's time base)."""
    signal: np.ndarray
    """Sensor signal without its local baseline [N]."""
    force: np.ndarray
    """Reconstructed contact force [N]."""


def window_row(window):
    """The table row of an impact that is not analysed: where it is and why not."""
    return {"status": window.status, "reason": window.reason, "onset [s]": window.onset}


def _onset_uncertainty(window):
    """The ``onset_uncertainty [s]`` column of an analysed impact, and where its onset
    is a crossing (nothing fitted, so no uncertainty), a note in its reason that says so."""
    columns = {ONSET_UNCERTAINTY: window.onset_uncertainty}
    if math.isfinite(window.onset_uncertainty) or "crossing" in window.reason:
        return columns  # fitted, or the crossing's reason is there already
    note = (
        "onset: the 5-sigma crossing, not fitted (fewer than 4 samples per sensor period, "
        "or fit_onsets=False): no onset uncertainty"
    )
    return {**columns, "reason": "; ".join(r for r in (window.reason, note) if r)}


def _signal_numbers(t, record, raw, smooth, flat, window, sensor, noise, held):
    """Peak, response time and impulse of the signal (module docstring), and the record
    less its local baseline (``held``: the samples of other impacts, :func:`_held`).
    Raises :class:`~dem_check.campaign.segment_lobe.NoLobe` where the smoothed signal
    does not rise above, or does not return to, the onset level inside the segment."""
    base = window.baseline_window
    in_base = (t >= base[0]) & (t < base[1])
    lobe = segment_lobe(t, smooth, window, held)
    in_lobe = (t >= lobe[0]) & (t <= lobe[1])
    # a contact cannot outlast one lobe-length after the signal's first lobe
    # (contactlab.inverse.reconstruct_force's window)
    contact_end = 2.0 * lobe[1] - lobe[0]
    local = _local(t, record, window, contact_end, sensor, noise, held=held)
    # the reconstruction reads its noise model on the detection's baseline window: it
    # gets the record less the line fitted there
    detrended = record - _local(t, record, window, contact_end, sensor, None, False, held).values
    # the low-passed record less the local baseline: ``flat`` is the low-passed record
    # less the running baseline (record - raw), which the low-pass leaves unchanged
    lowpassed = flat + (record - raw) - local.values
    peak = np.max(lowpassed[in_lobe]) if in_lobe.any() else np.nan
    numbers = {
        "noise [N]": float(np.std(detrended[in_base], ddof=1)),
        "peak_sensor_force [N]": float(peak),
        "sensor_response_time [s]": float(lobe[1] - lobe[0]),
        "impulse [N*s]": local.impulse,
    }
    return numbers, detrended, contact_end


def _local(
    t, record, window, contact_end, sensor, noise=None, near_onset=True, held=None, also=None
):
    """The impact's local baseline (:func:`dem_check.campaign.local.local_baseline`),
    its ringing fitted from ``contact_end`` [s]; a baseline before the impact is read up
    to :data:`ONSET_MARGIN` periods before the onset, where the impulse integral starts
    (``near_onset=False``: to the detection's baseline window's end). With the record's
    ``noise`` (:func:`dem_check.campaign.local.record_noise`) the noise under the pulse
    is predicted from both sides and taken off with the line. ``held``: samples of other
    impacts (:func:`_held`), left out of the fit and of the prediction. ``also``: further
    records whose impulses are read with the same fit (``LocalBaseline.impulses``)."""
    base = window.baseline_window
    if near_onset and base[1] <= window.onset:
        end = max(base[1], window.onset - ONSET_MARGIN * sensor.period)
        return local_baseline(
            t, record, (base[0], end), end, contact_end, window.end, sensor, noise, held, also
        )
    start = base[1] if window.start is None else window.start
    return local_baseline(
        t, record, base, start, contact_end, window.end, sensor, exclude=held, also=also
    )


def _crosstalk_impulse(found, local):
    """The crosstalk's share of the impulse ``local`` read with it removed (``also``:
    its columns read with the same fit), that share's standard error and, where
    removing it adds more error than it takes off
    (:func:`dem_check.campaign.structure.removed_from_impulse`), the impulse with the
    share left in (the reconstruction keeps the removal)."""
    share, error = found.share(local.impulses)
    removed = removed_from_impulse(share, error)
    return {
        "impulse [N*s]": local.impulse if removed else local.impulse + share,
        "crosstalk_impulse [N*s]": share,
        "crosstalk_impulse_error [N*s]": error,
        "crosstalk_impulse_removed": removed,
    }


def _held(detection, window, t, sensor):
    """Samples of the segment ``t`` that hold another impact of the record: from a
    sensor period before its onset (an impact not analysed keeps its crossing, which
    lags the touch) to its decayed ringing, as :func:`dem_check.campaign.local.record_noise`
    leaves them out of the quiet samples. Another impact's ringing is signal: a
    baseline fitted on it, or noise predicted from it, reads it into this impact."""
    held = np.zeros(t.size, dtype=bool)
    for other in detection.impacts:
        if other is not window:
            held |= (t >= other.onset - sensor.period) & (t <= other.end)
    return held


def _last_force(rec):
    """End of the last contact the reconstruction holds [s]: of its run of force above
    the significance threshold that lies after the contact and carries at least
    :data:`IMPULSE_EXCESS` of its impulse (a second contact the impulse check is for;
    a shorter excursion of noise read as force is not one), else the contact's end."""
    above = np.flatnonzero(rec.force > rec.parameters["threshold [N]"])
    # the regularised force's own contact where the family's fit read the metrics' (with
    # the fit's end, the impulse at 1 and 2 MHz, 10-30 sigma: 5.1 -> 6.0 %, 8.9 -> 9.7 %)
    end = rec.parameters.get("regularised_contact [s]", (None, rec.metrics.end))[1]
    last = end
    for run in np.split(above, np.flatnonzero(np.diff(above) > 1) + 1):
        if run.size > 1 and rec.t[run[0]] > end:
            carried = impulse(rec.t[run], rec.force[run])
            if carried >= IMPULSE_EXCESS * rec.metrics.impulse:
                last = float(rec.t[run[-1]])
    return last


def _reconstruction_part(t, base, end, sensor):
    """The samples the reconstruction needs: the last :data:`RECONSTRUCTION_BASELINE`
    periods of a baseline before the impact (all of one after it), the impact and
    :data:`RECONSTRUCTION_TAIL` periods past the decayed ringing. The Tikhonov solve costs
    the number of samples times the square of the unknowns; a long baseline adds cost,
    not accuracy."""
    dt = float(t[1] - t[0])
    keep = max(64, round(RECONSTRUCTION_BASELINE * sensor.period / dt)) * dt
    after = base[0] > end  # a short pre-trigger's baseline lies after the ringing
    start = t[0] if after else max(t[0], base[1] - keep)
    stop = t[-1] if after else end + RECONSTRUCTION_TAIL * sensor.period
    return (t >= start) & (t <= stop)


def _unknowns(onset, contact_end, sensor):
    """Force values of the reconstruction: one per :data:`GRID_PER_PERIOD`-th of a sensor
    period over the contact window (a quarter period before the onset to
    ``contact_end``), at most :data:`~contactlab.inverse.reconstruct.DEFAULT_MAX_UNKNOWNS`."""
    span = contact_end - onset + 0.25 * sensor.period
    return int(min(DEFAULT_MAX_UNKNOWNS, max(2, math.ceil(span * GRID_PER_PERIOD / sensor.period))))


def _too_coarse(row, span, dt, what):
    """The row with the reason that the record is too coarse to reconstruct."""
    note = (
        f"too coarse to reconstruct: the {what} lasts {span / dt:.3g} samples (need "
        f"{MIN_SAMPLES_PER_CONTACT}); peak_sensor_force, impulse and onset are read, no "
        "contact force or contact time is given"
    )
    reason = "; ".join(r for r in (row["reason"], note) if r)
    return {**row, "reason": reason}


def _fit_columns(fit):
    """``fit_<name> [unit]`` and its interval, identifiability and the fit's chi2."""
    columns = {}
    for name, p in fit.parameters.items():
        if name == "onset":
            continue  # the onset is in its own column
        columns[f"fit_{name} [{p.unit}]"] = p.value
        columns[f"fit_{name}_low [{p.unit}]"] = p.ci95[0]
        columns[f"fit_{name}_high [{p.unit}]"] = p.ci95[1]
        columns[f"fit_{name}_identifiable"] = p.identifiable
    columns["fit_reduced_chi_squared [-]"] = fit.goodness["reduced_chi_squared [-]"]
    return columns


def _fit(t, raw, base, grain, sensor, law):
    """Fit columns and notes (warnings turned into text: nothing hidden)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fit = fit_contact(t, raw, grain, sensor, law, baseline_window=base, crosstalk=False)
    notes = [f"fit: {w.message}" for w in caught]
    return _fit_columns(fit), notes


def analyse_impact(
    detection, window, sensor, grain=None, fit=None, crosstalk=True, modes=None, noise=NOT_GIVEN
):
    """The table row and gallery traces of one ``"ok"`` impact (:func:`read_impact`
    without its local baseline)."""
    row, traces, _ = read_impact(detection, window, sensor, grain, fit, crosstalk, modes, noise)
    return row, traces


def read_impact(
    detection, window, sensor, grain=None, fit=None, crosstalk=True, modes=None, noise=NOT_GIVEN
):
    """The table row, gallery traces and local baseline of one ``"ok"`` impact.

    Parameters
    ----------
    detection : Detection
        The record's detection (its baseline-free and smoothed signals).
    window : ImpactWindow
        The impact (status ``"ok"``).
    sensor : Sensor
    grain : Grain, optional
        Gives ``velocity_change [m/s]``; needed by ``fit``.
    fit : str, optional
        A law name of :data:`contactlab.inverse.FIT_MODELS`.
    crosstalk : bool, default True
        Find the structure's modes ringing after the contact and remove their response
        before the numbers are read (:mod:`dem_check.campaign.structure`); the columns
        ``crosstalk [N]`` and ``crosstalk_modes`` say what was removed.
    modes : list of (float, float), optional
        The record's structure modes (:func:`dem_check.campaign.structure.record_modes`,
        found once per record); found here when not given.
    noise : ColouredNoise or None, optional
        The record's white and 1/f noise (:func:`dem_check.campaign.local.record_noise`,
        estimated once per record); estimated here when not given; ``None``: the
        baseline is the ordinary least-squares line and ringing, with no noise predicted
        under the pulse.

    Returns
    -------
    row : dict
        Unit-bearing columns (module docstring); ``status`` is ``"ok"``, or
        ``"reconstruction failed"`` / ``"fit failed"`` with the error in ``reason``
        (``"reconstruction failed"`` also where the segment holds no whole first lobe of
        the signal: its numbers are not read).
    traces : ImpactTraces or None
        For the gallery (``None`` when the reconstruction failed).
    baseline : LocalBaseline or None
        The local baseline the impulse was read with (its post-contact window and the
        sensor's free ringing fitted there: :mod:`dem_check.campaign.overlaps` takes
        that ringing off a later impact); ``None`` where no impulse was read after the
        reconstruction.
    """
    part = slice(window.first, window.stop)
    t = np.asarray(detection.signal.t[part])
    raw = np.asarray(detection.signal.values[part])
    smooth = np.asarray(detection.smoothed.values[part])
    flat = np.asarray(detection.lowpassed.values[part])
    record = np.asarray(detection.record.values[part], dtype=float)
    base = window.baseline_window
    row = {**window_row(window), "significance [-]": window.significance}
    row.update(_onset_uncertainty(window))
    if noise is NOT_GIVEN:
        noise = record_noise(detection, sensor)
    held = _held(detection, window, t, sensor)
    try:
        numbers, detrended, contact_end = _signal_numbers(
            t, record, raw, smooth, flat, window, sensor, noise, held
        )
        if crosstalk:
            if modes is None:
                modes = record_modes(detection, sensor)
            found = impact_crosstalk(detection, window, sensor, contact_end, part, modes, noise)
            row["crosstalk [N]"] = sum(m.amplitude for m in found.modes)
            row["crosstalk_modes"] = found.describe()
            if found.modes:
                record, raw, smooth, flat = (v - found.values for v in (record, raw, smooth, flat))
                numbers, detrended, contact_end = _signal_numbers(
                    t, record, raw, smooth, flat, window, sensor, noise, held
                )
    except NoLobe as exc:
        row.update(status="reconstruction failed", reason=str(exc))
        return row, None, None
    row.update(numbers)
    if grain is not None:
        row["velocity_change [m/s]"] = row["impulse [N*s]"] / grain.mass
    dt = float(t[1] - t[0])
    if not row["sensor_response_time [s]"] >= MIN_SAMPLES_PER_CONTACT * dt:
        return (
            _too_coarse(row, row["sensor_response_time [s]"], dt, "signal's first lobe"),
            None,
            None,
        )
    part = _reconstruction_part(t, base, window.end, sensor)
    try:
        rec = reconstruct_force(
            t[part],
            # reconstruct_force subtracts the baseline window's mean: it is added back,
            # so that the local baseline (fitted on both sides) is what is removed
            detrended[part] + float(np.mean(detrended[(t >= base[0]) & (t < base[1])])),
            sensor,
            baseline_window=base,
            max_unknowns=_unknowns(window.onset, contact_end, sensor),
            crosstalk=False,  # removed above, with the record's modes (or kept on request)
            first_touch=False,  # the onset was fitted per record (dem_check.campaign.onsets)
            # the edges with the shape of the record's contact family (its onset fit's)
            contact_family=detection.contact_family,
        )
    except ParameterError as exc:
        row.update(status="reconstruction failed", reason=str(exc))
        return row, None, None
    if not rec.metrics.duration >= MIN_SAMPLES_PER_CONTACT * dt:
        lobe = row["sensor_response_time [s]"]
        if lobe > rec.metrics.duration + sensor.period:  # not a short contact: a merged pair
            reason = (
                f"the signal's first lobe lasts {lobe:.3g} s, more than the reconstructed "
                f"contact ({rec.metrics.duration / dt:.3g} samples) and a sensor period: one "
                "contact does not explain it (a second one within the first lobe), so "
                "neither is analysed alone"
            )
            return {**window_row(window), "status": "overlap", "reason": reason}, None, None
        return _too_coarse(row, rec.metrics.duration, dt, "reconstructed contact"), None, None
    row["peak_contact_force [N]"] = rec.metrics.peak
    row["contact_time [s]"] = rec.metrics.duration
    # the impulse to a period past the last force the reconstruction holds: its contact's
    # end, or that of a second contact which began within the first lobe (the ringing
    # check cannot see it, the impulse check below does); the post-contact window then
    # holds free ringing only. A post-contact window that starts inside a second contact
    # fits its force as ringing and misses the rest of its impulse (120 us after a 100 us
    # contact, with the window from the first lobe's bound: 1.83 times the contact's
    # impulse instead of 2). A period past the contact's end also spans less 1/f noise
    # than the first lobe's bound (about 130 us against 200 us for a 100 us contact)
    last = _last_force(rec)
    columns = found.columns if crosstalk and found.modes else None
    local = _local(t, record, window, last + sensor.period, sensor, noise, held=held, also=columns)
    row["impulse [N*s]"] = local.impulse
    if columns is not None:
        row.update(_crosstalk_impulse(found, local))
    if grain is not None:
        row["velocity_change [m/s]"] = row["impulse [N*s]"] / grain.mass
    excess = row["impulse [N*s]"] / rec.metrics.impulse - 1.0
    if not abs(excess) <= IMPULSE_EXCESS:
        reason = (
            f"the segment's impulse is {excess + 1.0:.3g} times that of the reconstructed "
            f"contact (its force is significant until {last:.6g} s): a second impact (or "
            "contact) follows within the first one's main lobe, so neither is analysed alone"
        )
        return {**window_row(window), "status": "overlap", "reason": reason}, None, local
    start, end = rec.parameters["window [s]"]
    keep = (rec.t >= start - GALLERY_PERIODS * sensor.period) & (
        rec.t <= end + GALLERY_PERIODS * sensor.period
    )
    traces = ImpactTraces(rec.t[keep].copy(), rec.signal[keep].copy(), rec.force[keep].copy())
    if fit is not None:
        try:
            columns, notes = _fit(t, detrended, base, grain, sensor, fit)
        except ParameterError as exc:
            row.update(status="fit failed", reason=f"fit: {exc}")
        else:
            row.update(columns)
            row["reason"] = "; ".join([r for r in (row["reason"],) if r] + notes)
    # a contact that reaches the end of the window the force is reconstructed on has no
    # end read (2 MHz, 2 % crosstalk, no structure mode found on the record: a 16.5 sigma
    # Hertz impact's force, the ringing left in, stayed above its threshold to 59 us past
    # that window's end, contact time +124 %, docs/campaign.md "No whole first lobe, traced")
    if not rec.metrics.end < rec.parameters["window [s]"][1]:
        row.update(
            status="reconstruction failed",
            reason="the reconstructed force does not return below its threshold in the "
            f"window it is reconstructed on (to {rec.parameters['window [s]'][1]:.6g} s): no "
            "contact end to read",
        )
    row.update(physics_status(row, grain))
    return row, traces, local
