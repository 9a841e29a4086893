"""Offset steps at a record's edges: a first-pass run from the record's first sample or
to its last that is a level change, not an impact (issue 22; step 0 of
:mod:`dem_check.campaign.detection`, beside :mod:`dem_check.campaign.steps`, whose period
means need a window on each side of a step).

On one side of such a step the record stays at one level, as flat as the noise on the
other side, where an impact's main lobe and ringing are not; near the start, or within
a sensor period of the end, a step and an impact's lobe are told apart by fitting both
(:mod:`dem_check.campaign.edge_models`, :mod:`dem_check.campaign.edge_boxes`).
"""

import numpy as np

from contactlab.signals import robust_noise
from dem_check.campaign.edge_boxes import start_steps
from dem_check.campaign.edge_models import end_fit, start_fit
from dem_check.campaign.steps import (
    FLAT_RATIO,
    STEP_SIGMAS,
    WINDOW_PERIODS,
    OffsetStep,
    level_error,
    period_noise,
    split,
)

__all__ = ["edge_steps"]


def edge_steps(values, runs, period, reach, ring=None):
    """Steps that the first pass read as a run to the record's last sample, or from its
    first: on one side of the step the record stays at one level, as flat as the noise on
    the other side, where an impact's main lobe and ringing are not.

    A step near an edge leaves few samples on that side, so its height is known less
    well: it must reach :data:`STEP_SIGMAS` standard errors of the difference of the two
    levels, each the period means' noise over the periods it spans
    (:func:`level_error`).

    Parameters
    ----------
    values : numpy.ndarray
        The record [N], finite.
    runs : list of tuple
        ``(first, last)`` sample indices of the first pass's candidate runs.
    period : int
        The sensor's period [samples].
    reach : int
        Samples past a run's last one that still belong to it (its quiet hold).
    ring : tuple, optional
        ``(sensor, dt)``: the sensor and the sampling interval [s]. A step at the start,
        or within a sensor period of the end, is then told from an impact's lobe by
        fitting both (:mod:`dem_check.campaign.edge_models`; a box of steps over an
        impact at the start with it, :mod:`dem_check.campaign.edge_boxes`) instead of by the
        flatness of its side (and at the end without the :data:`STEP_SIGMAS` test, which
        so few samples cannot pass: the run reached the detection threshold).

    Returns
    -------
    list of OffsetStep
        In time order.
    """
    values = np.asarray(values, dtype=float)
    n = values.size
    noise = period_noise(values, period)
    found = _end_steps(values, runs, period, reach, noise, ring=ring, all_runs=runs)
    # a step near the start is one near the end of the record read backwards: its index
    # there is where the old level ends, and its height changes sign
    mirrored = [(n - 1 - last, n - 1 - first) for first, last in runs]
    for step in _end_steps(
        values[::-1], mirrored, period, reach, noise, start_side=True, ring=ring
    ):
        window, index, note = (0, n - step.window[0]), n - step.index, ""
        if ring is not None:
            fit = start_fit(values, index, runs, reach, ring)
            box = start_steps(values, index, runs, reach, ring, fit.lobe_chi2)
            found += [OffsetStep(*row[:4], note=row[4]) for row in box]  # over a lobe
            if box or not fit.step:
                continue  # or an impact's lobe alone
            index = fit.index  # placed by the fit, under the record's noise model
            note = f"; {fit.reason()}: a level change within one sample is no sensor's response"
        found.append(OffsetStep(index, -step.height, step.significance, window, note=note))
    return sorted(found, key=lambda step: step.index)


def _end_steps(values, runs, period, reach, noise, start_side=False, ring=None, all_runs=()):
    """:func:`edge_steps` at the record's end: runs to its last sample (``start_side``:
    the record read backwards, the flatness left to :func:`edge_steps` when ``ring`` is
    given)."""
    size = WINDOW_PERIODS * period
    found = []
    for first, last in runs:
        if first < period or last + reach < values.size:  # not a run to the end
            continue
        # the running baseline may follow a step for a while: the run can start late
        start = max(period, first - size // 2)
        run, before = values[start:], values[start - min(start, size) : start]
        tail = np.median(values[first:][-max(2, (values.size - first) // 4) :])  # end level
        level = float(np.median(before))
        at = start + split(run, level, tail - level, np.inf)[0]
        new, old = values[at:], values[max(0, at - size) : at]
        if ring is not None and not start_side:  # a step in the last sensor period?
            fit = end_fit(values, at, first, all_runs, reach, ring)
            if fit.step:
                step = (fit.index, fit.height, fit.significance, (first, values.size))
                found.append(OffsetStep(*step, note=fit.note))
                continue
            if new.size < period:
                continue  # the start of a lobe: left to the impacts
        if new.size < 2 or old.size < period:
            continue
        # before a step at the start, the few samples are a level, not a main lobe (an
        # impact at the first sample returns to the level): their standard deviation,
        # which a lobe raises and a median absolute deviation may not, is flat too
        spread = [(np.std if start_side else robust_noise)(new), robust_noise(old)]
        height = float(np.median(new) - np.median(old))
        error = np.hypot(*(level_error(noise, period, x.size) for x in (new, old)))
        significance = abs(height) / max(error, np.finfo(float).tiny)
        flat = (start_side and ring is not None) or spread[0] <= FLAT_RATIO * spread[1]
        if flat and significance >= STEP_SIGMAS:
            found.append(OffsetStep(at, height, significance, (first, values.size)))
    return found
