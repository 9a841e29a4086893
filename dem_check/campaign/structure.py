"""The structure's crosstalk of one impact, read on the record around it and removed.

:mod:`contactlab.inverse.crosstalk` finds the structure's modes in the ringing after a
contact and fits their response to the pulse; this module picks the record's windows
for one impact found by :func:`dem_check.campaign.detection.find_impacts`:

- before it, from the previous impact's decayed ringing (or the record's start) to the
  end of its baseline window, at most :data:`SPAN`;
- after its contact (a sensor period after the contact's bound), to
  :data:`NEXT_MARGIN_PERIODS` sensor periods before the next impact's onset (or the
  record's end), at most :data:`SPAN`.
"""

import math

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.crosstalk import (
    Crosstalk,
    fit_crosstalk,
    joint_structure_modes,
    structure_modes,
)
from contactlab.inverse.crosstalk_driven import driven_significance
from dem_check.campaign.local import record_noise

__all__ = [
    "NEXT_MARGIN_PERIODS",
    "SPAN",
    "impact_crosstalk",
    "record_modes",
    "removed_from_impulse",
]

SPAN = 2e-3
"""Longest window the crosstalk is fitted on, on each side of an impact [s]: long
against the modes' periods, short against drift and 1/f noise (a quadratic follows
them)."""

IDENTIFICATION_SPAN = 5e-3
"""Longest window after the contact the modes are identified on [s] (up to the next
impact): a mode is sought from one period in it (200 Hz and up over 5 ms)."""

NEXT_MARGIN_PERIODS = 2.0
"""Sensor periods left before the next impact's onset [-] (its first touch precedes its
5-sigma onset by a few microseconds)."""

FREQUENCY_TOLERANCE = 0.04
"""Poles found after different impacts within this relative frequency of the next lower
one, and within twice it of the lowest, are one mode [-] (a plate mode is found within
+-2 % after each hit of a 2 MHz record)."""

HALF = 0.5
"""Fraction of the impacts after which a mode must be found [-] (at least two): on
records without crosstalk and with 1/f noise as large as the white noise, the pencil's
noise poles fall within :data:`FREQUENCY_TOLERANCE` of each other after two of four
impacts, a plate mode's after three or four."""

RESOLVED_PERIOD_SAMPLES = 4
"""Fewest samples per sensor period for the sensor's ringing to be fitted [-]."""

NOT_GIVEN = object()
"""Default of :func:`record_modes`' ``noise``: estimate it (``None`` means none)."""


def _following(detection, index, sensor):
    """Where the window after impact ``index`` must end [s]: before the next onset."""
    if index + 1 < len(detection.impacts):
        return detection.impacts[index + 1].onset - NEXT_MARGIN_PERIODS * sensor.period
    return float(detection.record.t[-1])


def record_modes(detection, sensor, *, refine=True, noise=NOT_GIVEN):
    """The structure's modes of a record: those found after half of its impacts (two at
    least; all of them when only one impact could be read), on each impact's ringing
    alone and on all of them jointly.

    Each impact's ringing (from its decay to the next impact, at most
    :data:`IDENTIFICATION_SPAN`) is a window. A structure's modes are the same after
    every hit; a pole that the pencil fits to noise, drift or hum after one impact is
    rarely found again within :data:`FREQUENCY_TOLERANCE`. Two ways, pooled:

    1. **window by window** (:func:`~contactlab.inverse.crosstalk.structure_modes`):
       poles found after :data:`HALF` of the impacts whose window was long enough (1.6
       ms for a 40 kHz sensor);
    2. **jointly** (:func:`~contactlab.inverse.crosstalk.joint_structure_modes`, a
       multi-channel matrix pencil on every window from 1.1 ms on): poles shared by the
       windows, kept when significant after :data:`HALF` of them. Windows of 1-2 ms
       between a hit and its bounce, under two periods of a 730 Hz plate mode, add to
       its estimate; window by window the mode was found in none of eight records at 1
       and 5 MHz (``docs/campaign.md``). A joint pole significant after fewer windows
       is kept when the impacts drive it: its ringing, fitted with one coupling to
       every impact's peak shared by all the windows
       (:func:`~contactlab.inverse.crosstalk_driven.driven_significance`), is
       significant (a plate's 4100 Hz mode rung under the noise by the weaker impacts
       of a 2 MHz record). A joint pole within twice
       :data:`FREQUENCY_TOLERANCE` of a mode found window by window is that mode (the
       window-by-window one stays: letting the refined joint pole replace it cost 2 MHz
       records with 1/f noise of 0.3 sigma their impulse, 1.9 % -> 18 % at 30-100 sigma,
       ``docs/campaign.md``).

    Parameters
    ----------
    detection : Detection
    sensor : Sensor
    refine : bool, default True
        Refine the joint poles by variable projection on the windows
        (``joint_structure_modes(..., refine=True)``); False: the pencil's poles, as
        before (``benchmarks/bench_realistic.py --no-refine``).
    noise : ColouredNoise or None, optional
        The record's white and 1/f noise (:func:`dem_check.campaign.local.record_noise`,
        estimated here when not given): the driven test's standard errors then hold the
        1/f noise's correlation between the windows' samples; ``None``: the white
        residual's only.

    Returns
    -------
    list of (float, float)
        ``(frequency [Hz], damping ratio [-])`` by frequency: the medians of each group
        found window by window, then the joint poles.
    """
    t = np.asarray(detection.record.t)
    dt = float(t[1] - t[0])
    if sensor.period < RESOLVED_PERIOD_SAMPLES * dt:
        return []
    windows = []
    for index, window in enumerate(detection.impacts):
        stop = min(_following(detection, index, sensor), window.end + IDENTIFICATION_SPAN)
        first, last = np.searchsorted(t, [window.end, stop])
        values = np.asarray(detection.record.values[first:last], dtype=float)
        if last - first >= 16 and np.isfinite(values).all():
            windows.append((t[first:last], values))
    found = []
    for window in windows:
        try:
            found.append(structure_modes(*window, sensor))
        except ParameterError:  # too short a window: this impact does not count alone
            continue
    modes = _pooled(found)
    if not windows:
        return modes
    candidates, significant = joint_structure_modes(windows, sensor, refine=refine)
    needed = max(2, math.ceil(HALF * len(windows))) if len(windows) > 1 else 1
    onsets = [w.onset for w in detection.impacts]
    drives = [w.peak if w.peak > 0.0 else 0.0 for w in detection.impacts]  # nan: none
    if noise is NOT_GIVEN:
        noise = record_noise(detection, sensor)
    # lags over the record and a block of it (the windows' span and a block mean)
    lags = None if noise is None else noise.autocovariance(2 * t.size)
    *_, driven = driven_significance(windows, onsets, drives, candidates, sensor, lags)
    for (frequency, zeta), hits, shared in zip(
        candidates, significant.sum(axis=0), driven, strict=True
    ):
        near = any(abs(frequency / f - 1.0) <= 2 * FREQUENCY_TOLERANCE for f, _ in modes)
        if (hits >= needed or shared) and not near:
            modes.append((frequency, zeta))
    return sorted(modes)


def _pooled(found):
    """Groups of poles within :data:`FREQUENCY_TOLERANCE` of each other, kept when
    found after :data:`HALF` of the impacts, at least two (any, when one was read)."""
    poles = sorted((f, z, k) for k, modes in enumerate(found) for f, z in modes)
    groups, current = [], []
    for pole in poles:
        near = current and pole[0] <= current[-1][0] * (1.0 + FREQUENCY_TOLERANCE)
        if current and not (near and pole[0] <= current[0][0] * (1.0 + 2 * FREQUENCY_TOLERANCE)):
            groups.append(current)
            current = []
        current.append(pole)
    if current:
        groups.append(current)
    needed = max(2, math.ceil(HALF * len(found))) if len(found) > 1 else 1
    return [
        (float(np.median([p[0] for p in g])), float(np.median([p[1] for p in g])))
        for g in groups
        if len({p[2] for p in g}) >= needed
    ]


def impact_crosstalk(detection, window, sensor, contact_end, segment, modes, noise=None):
    """The crosstalk of one impact on its segment, every record mode fitted and removed.

    Each of the record's modes is fitted and removed, significant on this impact or not
    (``fit_crosstalk(..., drop=False)``): the modes were found after half of the
    record's impacts, and one left out biases the others, whose columns overlap on
    windows of a few periods (1 MHz, 1/f noise of 0.3 sigma, 2 % crosstalk: a 35 sigma
    impact's 4100 Hz response, under 5 standard errors there, dropped: its impulse read 6.0 % high;
    0.3 % with it; ``docs/campaign.md``, "Crosstalk").

    Parameters
    ----------
    detection : Detection
        The record's detection (the record and every impact).
    window : ImpactWindow
        The impact.
    sensor : Sensor
    contact_end : float
        A time after the contact has ended [s] (the bound of the first lobe).
    segment : slice
        The impact's segment in the record.
    modes : list of (float, float)
        The record's structure modes (:func:`record_modes`).
    noise : ColouredNoise, optional
        The record's noise (:func:`dem_check.campaign.local.record_noise`): the
        crosstalk's covariance is then that under it (:attr:`Crosstalk.covariance`).

    Returns
    -------
    Crosstalk
        On the segment's samples.
    """
    t = np.asarray(detection.record.t)
    none = Crosstalk((), np.zeros(segment.stop - segment.start))
    if not modes:
        return none
    index = detection.impacts.index(window)
    previous = detection.impacts[index - 1].end if index > 0 else float(t[0])
    base = window.baseline_window
    # a baseline before the impact (not after its ringing: a short pre-trigger); the
    # fitted onset can lie before the baseline's end (dem_check.campaign.onsets)
    pre = (max(previous, window.onset - SPAN), base[1]) if base[0] < window.onset else None
    post = (
        contact_end + sensor.period,
        min(_following(detection, index, sensor), contact_end + SPAN),
    )
    first = min(segment.start, int(np.searchsorted(t, pre[0]))) if pre else segment.start
    stop = max(segment.stop, int(np.searchsorted(t, post[1], side="right")))
    tt = t[first:stop]
    yy = np.asarray(detection.record.values[first:stop], dtype=float)
    in_post = (tt >= post[0]) & (tt <= post[1])
    if in_post.sum() < 16:
        return none
    in_pre = (tt >= pre[0]) & (tt < pre[1]) if pre else np.zeros(tt.size, dtype=bool)
    start = pre[1] if pre else window.onset
    pulse = (tt >= start) & (tt < contact_end)
    autocovariance = None if noise is None else noise.autocovariance(tt.size)
    found = fit_crosstalk(
        tt,
        yy,
        sensor,
        window.onset,
        pulse,
        in_pre | in_post,
        post[0],
        modes,
        drop=False,
        autocovariance=autocovariance,
    )
    return found.cropped(slice(segment.start - first, segment.stop - first))


def removed_from_impulse(share, error):
    """Whether an impact's crosstalk is taken off its impulse.

    Removing the crosstalk takes its share ``s`` off the impulse and adds the share's
    own error (standard error ``e``, :meth:`Crosstalk.share`); leaving it in leaves the
    true share ``b``. The squared error is smaller with the removal when ``b**2 > e**2``;
    ``s**2 - e**2`` is the unbiased estimate of ``b**2``, so the share is removed when
    ``s**2 > 2 e**2`` (no tuned threshold: the comparison of the two mean squared
    errors, each impact's own).

    Parameters
    ----------
    share : float
        The crosstalk's share of the impulse [N*s].
    error : float
        Its standard error [N*s].

    Returns
    -------
    bool
    """
    return share**2 > 2.0 * error**2
