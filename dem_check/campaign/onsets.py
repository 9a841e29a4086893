"""The first touch of each impact of a record (:mod:`contactlab.inverse.onset`).

The detector's onset is the smoothed signal's crossing of five noise sigmas
(:mod:`dem_check.campaign.detection`, step 4), which lags the touch by the time the signal
takes to reach it. Here each analysed impact's rise is fitted with the sensor's response
to a force ``(t - t0)**q (1 + bend (t - t0) / T)``; ``q`` and ``bend`` are chosen once
per record on its most significant impacts, since every impact of a record has the same
contact law (:func:`contactlab.inverse.onset.rise_shape`).
"""

import dataclasses

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.onset import RISE_FRACTION, Rise, fit_onset, rise_shape

__all__ = ["SHAPE_IMPACTS", "first_touches", "record_onsets"]

SHAPE_IMPACTS = 8
"""The rise's shape is read on this many of a record's most significant impacts [-]."""


def _rise(detection, window, sensor):
    """The :class:`contactlab.inverse.onset.Rise` of one impact."""
    part = slice(window.first, window.stop)
    t = np.asarray(detection.record.t[part])
    y = np.asarray(detection.record.values[part], dtype=float)
    smooth = np.asarray(detection.smoothed.values[part])
    base = window.baseline_window
    in_base = (t >= base[0]) & (t < base[1])
    raw = np.asarray(detection.signal.values[part])
    noise = float(np.std(raw[in_base], ddof=1))
    reached = (t >= window.onset) & (smooth >= RISE_FRACTION * window.peak)
    if not reached.any():
        raise ParameterError(f"the impact at {window.onset:.6g} s does not rise to its peak")
    return Rise(t, y, window.onset, float(t[int(np.argmax(reached))]), noise)


def record_onsets(detection, windows, sensor):
    """The onsets [s] of ``windows`` (the crossing where the rise cannot be fitted), and
    the rise's exponent and bend, shared by the record's impacts (read on its
    :data:`SHAPE_IMPACTS` most significant ones)."""
    rises = []
    for window in windows:
        try:
            rises.append(_rise(detection, window, sensor))
        except ParameterError:
            rises.append(None)
    strongest = sorted(
        (k for k, r in enumerate(rises) if r is not None),
        key=lambda k: -windows[k].significance,
    )[:SHAPE_IMPACTS]
    try:
        q, bend = rise_shape([rises[k] for k in strongest], sensor)
    except ParameterError:  # no rise long enough: every impact keeps its crossing
        return [w.onset for w in windows], None, None
    return [_fitted(w, r, sensor, q, bend) for w, r in zip(windows, rises, strict=True)], q, bend


def _fitted(window, rise, sensor, exponent, bend):
    """The fitted onset [s] of one impact, or its crossing where it has no rise to fit."""
    if rise is None:
        return window.onset
    try:
        return fit_onset(rise, sensor, exponent, bend).onset
    except ParameterError:  # too few samples in the rise
        return window.onset


def first_touches(detection, sensor, statuses):
    """The detection's impacts, those with a status of ``statuses`` with their onset
    fitted (:func:`record_onsets`)."""
    chosen = [k for k, w in enumerate(detection.impacts) if w.status in statuses]
    if not chosen:
        return list(detection.impacts)
    onsets, _, _ = record_onsets(detection, [detection.impacts[k] for k in chosen], sensor)
    impacts = list(detection.impacts)
    for k, onset in zip(chosen, onsets, strict=True):
        impacts[k] = dataclasses.replace(impacts[k], onset=onset)
    return impacts
