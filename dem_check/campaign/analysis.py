"""Per-impact analysis: the signal's own numbers, the reconstructed force, an optional fit.

Each impact found by :func:`dem_check.campaign.detection.find_impacts` is read on its
segment (local baseline, impact, decayed ringing):

- ``sensor_response_time [s]``: the first lobe of the Gaussian-smoothed signal read with
  :func:`contactlab.metrics.first_lobe` at the onset level (five sigma of the local
  noise), with the same hysteresis so that only a return to zero ends it;
- ``peak_sensor_force [N]``: the largest value of the low-passed signal (flat pass band) in
  that lobe;
- ``impulse [N*s]``: the integral of the signal from the end of the local baseline to
  the end of the decayed ringing. The sensor returns to rest, so this is the impulse of
  the true contact force (``integral S1 dt = integral S2 dt - m1 v1(end)``);
- ``peak_contact_force [N]`` and ``contact_time [s]``: from the true force reconstructed
  by :func:`contactlab.inverse.reconstruct_force` (Tikhonov, GCV) on the segment;
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
from contactlab.metrics import first_lobe, impulse
from dem_check.campaign.detection import BASELINE_MIN_SAMPLES, ONSET_SIGMAS
from dem_check.campaign.plausibility import physics_status

__all__ = [
    "GALLERY_PERIODS",
    "MIN_SAMPLES_PER_CONTACT",
    "ImpactTraces",
    "analyse_impact",
    "window_row",
]

MIN_SAMPLES_PER_CONTACT = 20
"""Fewest samples per contact time for a reconstruction [-]. Below it the Tikhonov
reconstruction has fewer force values than a pulse's shape needs; the impact keeps its
signal numbers (onset, peak signal, impulse) and its reason says the record is too
coarse, instead of a reconstructed peak and contact time."""

IMPULSE_EXCESS = 0.2
"""Largest excess of the segment's impulse over the reconstructed contact's [-]. One
impact gives the same impulse both ways (to the few per cent that noise allows); a
second impact or contact inside the segment that the ringing check could not see (it
began within a sensor period of the first lobe's end) adds its own, and the impact is
flagged ``"overlap"``."""

RECONSTRUCTION_BASELINE = 5.0
"""Sensor periods of a baseline before the impact given to the reconstruction [-] (at
least 64 samples: its noise to 10 %)."""

RECONSTRUCTION_TAIL = 8.0
"""Sensor periods after the decayed ringing given to the reconstruction [-]: it reads
the signal to three periods past a window that ends a lobe-length after the main
lobe."""

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


def _main_lobe_start(y, level):
    """Index from which the first lobe is read: the last sample under ``level`` before
    the signal first reaches half its largest value. Wiggles before the impact that
    cross the onset level (an acquisition filter's pre-echo, a trigger glitch) then do
    not pass for its first lobe."""
    half = int(np.argmax(y >= 0.5 * np.nanmax(y)))
    under = np.flatnonzero(y[:half] < level)
    return int(under[-1]) if under.size else 0


def _signal_numbers(t, raw, smooth, flat, base, span):
    """Peak, response time and impulse of the signal (module docstring)."""
    in_base = (t >= base[0]) & (t < base[1])
    level = ONSET_SIGMAS * float(np.std(smooth[in_base], ddof=1))
    above = smooth - smooth[in_base].mean()
    first = _main_lobe_start(above, level)
    lobe = first_lobe(t[first:], above[first:], level, hysteresis=level)
    in_lobe = (t >= lobe[0]) & (t <= lobe[1])
    # both filters pass the baseline's level unchanged (unit gain at 0 Hz), and the
    # low-passed record is unread near the record's ends, where a baseline may lie
    peak = np.max(flat[in_lobe]) - smooth[in_base].mean() if in_lobe.any() else np.nan
    return {
        "noise [N]": float(np.std(raw[in_base], ddof=1)),
        "peak_sensor_force [N]": float(peak),
        "sensor_response_time [s]": float(lobe[1] - lobe[0]),
        "impulse [N*s]": impulse(t, raw - _impulse_baseline(t, raw, in_base, span[1]), *span),
    }


def _impulse_baseline(t, raw, in_base, end):
    """The baseline under the impulse integral: the line through the means of the local
    baseline and of the quiet samples after the ringing decayed (at least
    :data:`~dem_check.campaign.detection.BASELINE_MIN_SAMPLES` of them), or the local
    baseline's mean when there are too few after it or the baseline lies after the
    impact. Drift, 1/f noise and hum slower than the segment then do not add to the
    impulse as a constant baseline lets them."""
    after = t > end
    before = float(raw[in_base].mean())
    if after.sum() < BASELINE_MIN_SAMPLES or t[in_base].mean() > end:
        return before
    centres = float(t[in_base].mean()), float(t[after].mean())
    return before + (float(raw[after].mean()) - before) * (t - centres[0]) / (
        centres[1] - centres[0]
    )


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
        fit = fit_contact(t, raw, grain, sensor, law, baseline_window=base)
    notes = [f"fit: {w.message}" for w in caught]
    return _fit_columns(fit), notes


def analyse_impact(detection, window, sensor, grain=None, fit=None):
    """The table row and gallery traces of one ``"ok"`` impact.

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

    Returns
    -------
    row : dict
        Unit-bearing columns (module docstring); ``status`` is ``"ok"``, or
        ``"reconstruction failed"`` / ``"fit failed"`` with the error in ``reason``.
    traces : ImpactTraces or None
        For the gallery (``None`` when the reconstruction failed).
    """
    part = slice(window.first, window.stop)
    t = np.asarray(detection.signal.t[part])
    raw = np.asarray(detection.signal.values[part])
    smooth = np.asarray(detection.smoothed.values[part])
    flat = np.asarray(detection.lowpassed.values[part])
    base = window.baseline_window
    start = base[1] if window.start is None else window.start
    row = {**window_row(window), "significance [-]": window.significance}
    row.update(_signal_numbers(t, raw, smooth, flat, base, (start, window.end)))
    if grain is not None:
        row["velocity_change [m/s]"] = row["impulse [N*s]"] / grain.mass
    dt = float(t[1] - t[0])
    if not row["sensor_response_time [s]"] >= MIN_SAMPLES_PER_CONTACT * dt:
        return _too_coarse(row, row["sensor_response_time [s]"], dt, "signal's first lobe"), None
    part = _reconstruction_part(t, base, window.end, sensor)
    try:
        rec = reconstruct_force(t[part], raw[part], sensor, baseline_window=base)
    except ParameterError as exc:
        row.update(status="reconstruction failed", reason=str(exc))
        return row, None
    if not rec.metrics.duration >= MIN_SAMPLES_PER_CONTACT * dt:
        return _too_coarse(row, rec.metrics.duration, dt, "reconstructed contact"), None
    row["peak_contact_force [N]"] = rec.metrics.peak
    row["contact_time [s]"] = rec.metrics.duration
    excess = row["impulse [N*s]"] / rec.metrics.impulse - 1.0
    if not abs(excess) <= IMPULSE_EXCESS:
        reason = (
            f"the segment's impulse is {excess + 1.0:.3g} times that of the reconstructed "
            "contact: a second impact (or contact) follows within the first one's main "
            "lobe, so neither is analysed alone"
        )
        return {**window_row(window), "status": "overlap", "reason": reason}, None
    start, end = rec.parameters["window [s]"]
    keep = (rec.t >= start - GALLERY_PERIODS * sensor.period) & (
        rec.t <= end + GALLERY_PERIODS * sensor.period
    )
    traces = ImpactTraces(rec.t[keep].copy(), rec.signal[keep].copy(), rec.force[keep].copy())
    if fit is not None:
        try:
            columns, notes = _fit(t, raw, base, grain, sensor, fit)
        except ParameterError as exc:
            row.update(status="fit failed", reason=f"fit: {exc}")
        else:
            row.update(columns)
            row["reason"] = "; ".join([r for r in (row["reason"],) if r] + notes)
    if not math.isfinite(row["contact_time [s]"]):
        row.update(
            status="reconstruction failed",
            reason="the reconstructed force does not return below its threshold in the segment",
        )
    row.update(physics_status(row, grain))
    return row, traces
