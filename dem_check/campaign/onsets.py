"""The first touch of each impact of a record (:mod:`contactlab.inverse.lobe_onset`).

The detector's onset is the smoothed signal's crossing of five noise sigmas
(:mod:`dem_check.campaign.detection`, step 4), which lags the touch by the time the signal
takes to reach it. Here each analysed impact's whole first lobe is fitted with a contact
family's force pushed through the sensor; the family and its damping are chosen once per
record on its most significant impacts, since every impact of a record has the same
contact law (:func:`contactlab.inverse.lobe_onset.lobe_family`). Where an impact's fit
fails it keeps the crossing, and its ``reason`` says why.
"""

import dataclasses

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_onset import fit_lobe, lobe_family

__all__ = ["FAMILY_IMPACTS", "LOBE_LEVEL", "LOBE_SPAN", "first_touches", "record_onsets"]

FAMILY_IMPACTS = 4
"""The contact family is read on this many of a record's most significant impacts [-]
(18 fits each: 1.0-1.4 s of CPU per record)."""

LOBE_LEVEL = 0.3
"""The first guess of the contact's duration is the time the smoothed signal spends
above this fraction of its peak [-], over :data:`LOBE_SPAN`."""

LOBE_SPAN = 0.8
"""The fraction of a contact's duration its force spends above :data:`LOBE_LEVEL` of its
peak [-] (a half-sine: ``1 - 2 asin(0.3) / pi = 0.81``; the fit refines it)."""


def _lobe(detection, window, sensor):
    """One impact as :func:`contactlab.inverse.lobe_onset.fit_lobe` takes it:
    ``(t, y, (crossing, duration guess), noise)``."""
    part = slice(window.first, window.stop)
    t = np.asarray(detection.record.t[part])
    y = np.asarray(detection.record.values[part], dtype=float)
    smooth = np.asarray(detection.smoothed.values[part])
    base = window.baseline_window
    in_base = (t >= base[0]) & (t < base[1])
    raw = np.asarray(detection.signal.values[part])
    noise = float(np.std(raw[in_base], ddof=1))
    above = np.flatnonzero((t >= window.onset) & (smooth >= LOBE_LEVEL * window.peak))
    if above.size < 2:
        raise ParameterError(f"the impact at {window.onset:.6g} s does not rise to its peak")
    # the first run above the level, gaps shorter than a sensor period bridged (a damped
    # contact's force step rings the sensor down through the level): the first lobe
    period = round(sensor.period / float(t[1] - t[0]))
    gaps = np.flatnonzero(np.diff(above) > period)
    run = above[: gaps[0] + 1] if gaps.size else above
    length = float(t[run[-1]] - t[run[0]]) / LOBE_SPAN
    return t, y, (window.onset, length), noise


def record_onsets(detection, windows, sensor):
    """The fitted onsets of ``windows``, and the contact family they share.

    Returns
    -------
    onsets : list of float
        First touch [s] per window (its crossing where the fit failed).
    notes : list of str
        Empty where fitted; why not where the crossing was kept.
    family : str or None
        The family read on the :data:`FAMILY_IMPACTS` most significant impacts (None
        when none could be fitted: every impact keeps its crossing).
    damping : float or None
        Its damping ratio [-].
    """
    lobes, failed = [], {}
    for k, window in enumerate(windows):
        try:
            lobes.append(_lobe(detection, window, sensor))
        except ParameterError as error:
            lobes.append(None)
            failed[k] = str(error)
    strongest = sorted(
        (k for k, lobe in enumerate(lobes) if lobe is not None),
        key=lambda k: -windows[k].significance,
    )[:FAMILY_IMPACTS]
    try:
        family, damping = lobe_family([lobes[k] for k in strongest], sensor)
    except ParameterError as error:  # no lobe could be fitted: every impact keeps its crossing
        note = f"onset: the 5-sigma crossing (no lobe of the record could be fitted: {error})"
        return [w.onset for w in windows], [note] * len(windows), None, None
    onsets, notes = [], []
    for k, (window, lobe) in enumerate(zip(windows, lobes, strict=True)):
        try:
            if lobe is None:
                raise ParameterError(failed[k])
            t, y, guess, noise = lobe
            onsets.append(fit_lobe(t, y, sensor, guess, noise, family, damping).onset)
            notes.append("")
        except ParameterError as error:
            onsets.append(window.onset)
            notes.append(f"onset: the 5-sigma crossing (its lobe fit failed: {error})")
    return onsets, notes, family, damping


def first_touches(detection, sensor, statuses):
    """The detection's impacts, those with a status of ``statuses`` with their onset
    fitted (:func:`record_onsets`); where the fit failed, the crossing is kept and the
    impact's ``reason`` says so. Returned as the :class:`Detection` fields ``impacts`` and
    ``contact_family``: the record's family and damping ratio ``(name, zeta [-])`` (None
    where none was read), with which the reconstruction reads its contact's edges
    (:mod:`dem_check.campaign.analysis`)."""
    chosen = [k for k, w in enumerate(detection.impacts) if w.status in statuses]
    if not chosen:
        return {"impacts": list(detection.impacts), "contact_family": None}
    onsets, notes, family, damping = record_onsets(
        detection, [detection.impacts[k] for k in chosen], sensor
    )
    impacts = list(detection.impacts)
    for k, onset, note in zip(chosen, onsets, notes, strict=True):
        reason = "; ".join(r for r in (impacts[k].reason, note) if r)
        impacts[k] = dataclasses.replace(impacts[k], onset=onset, reason=reason)
    return {"impacts": impacts, "contact_family": None if family is None else (family, damping)}
