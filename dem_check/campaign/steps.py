"""DC offset steps: level changes that persist, found and removed before impacts are
looked for (step 0 of :mod:`dem_check.campaign.detection`).

A charge amplifier's range change or reset shifts a record's level and the level stays;
an impact's signal returns to the level it left once the contact and the sensor's
ringing are over. :func:`dem_check.campaign.noise` follows most steps with its running
baseline, but not one within a fraction of a block of a record's edge, under fast
drift, or just before or inside an impact (issue 22: 25 invented impacts in 100
records with two steps each, ``benchmarks/bench_steps.py``). So steps are found
explicitly:

1. **Period means.** The record is cut into blocks of one sensor period; a block's mean
   holds no sensor ringing (a full period of it averages out), so what is left is the
   level, the noise averaged over the period, and impacts' main lobes. Blocks inside
   the impacts found on a first pass (with their ringing) are left out.
2. **Level change.** At each boundary between the blocks left, the median of the
   :data:`WINDOW_PERIODS` blocks after less that of the blocks before (fewer at the
   record's edges, down to one block). A masked impact is one boundary: the level
   after its ringing against the level before it.
3. **Drift.** A drift adds its slope times the time between the two windows' median
   blocks' centres; the slope is the median rate of the changes over :data:`DRIFT_WINDOWS`
   windows before and after (a step raises it at about one window of boundaries), and
   is taken off.
4. **Significance.** The change over its noise: the median absolute change over the
   record (most boundaries hold no step) scaled for windows shortened at the edges, or,
   where larger, the changes' spread within :data:`DRIFT_WINDOWS` windows either side
   (a level that does not stay: a plate mode's slow ringing moves the medians up and
   down, a step at fewer than half of those boundaries) and, for windows further apart
   than a window (masked impacts between or among them), the spread of the record's
   changes between full windows as far apart (hum's and drift's curvature, which the
   slope does not take off, grows with the distance). A change of :data:`STEP_SIGMAS`
   or more, the largest within a window, is a step.
5. **Where.** Between the two windows, the sample where the level changes: the
   least-absolute-deviation split between the two levels of the record averaged over one
   sensor period (samples far from both levels, an impact's main lobe, count for
   neither). One within a period of a window's end (not the record's) is none
   (:func:`dem_check.campaign.step_windows.placed_inside`).

A step found across an impact is placed with the sensor's free ringing fitted
(:mod:`dem_check.campaign.step_ringing`). Runs of the first pass that are steps are
:mod:`dem_check.campaign.step_runs`'s; runs from the record's start or to its end are
:mod:`dem_check.campaign.step_edges`'. Each step is taken off the record (the later
samples shifted by its height) and the impacts are then found on what is left; each is
listed as a row with status ``"offset step"`` (:func:`dem_check.campaign.detection.find_impacts`).
"""

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import maximum_filter1d, median_filter, uniform_filter1d

from contactlab.signals import MAD_TO_SIGMA, robust_noise
from dem_check.campaign.step_ringing import difference_sigma, read_across
from dem_check.campaign.step_windows import placed_inside
from dem_check.campaign.window_medians import running_nanmedian, window_medians

__all__ = [
    "STEP_SIGMAS",
    "WINDOW_PERIODS",
    "OffsetStep",
    "block_levels",
    "drift_slopes",
    "find_steps",
    "level_error",
    "merge_steps",
    "period_noise",
    "remove_steps",
    "settle_steps",
    "split",
]

WINDOW_PERIODS = 16
"""Blocks (sensor periods) on each side of a boundary whose median is the level there
[-]: 0.4 ms for a 40 kHz sensor; an impact's main lobe that the first pass missed
(a few periods) moves a median of 16 little."""

DRIFT_WINDOWS = 4
"""The drift's slope is the median rate of the level changes over this many windows
before and after a boundary [-]: a step moves the rate at about one window of them."""

STEP_SIGMAS = 8.0
"""Smallest level change that is a step, in noise sigmas of the level change [-]."""

LEAST_HEIGHT = 3.0
"""Smallest step, in noise sigmas of the samples (on first differences) [-]: the level
change of a long quiet stretch is known far better than that, and an impact's lobe
just outside the first pass's run or its ringing's mean moves it by that much."""

FLAT_RATIO = 1.5
"""A run at a record's edge is a step when the record's spread within it is at most this
many times the spread of the quiet samples beside it [-] (an impact's lobe and ringing
spread it far more)."""

PASSES = 3
"""Searches of the record, each after the steps found before are taken off [-]."""

FAR_SIGMAS = 4.0
"""A period-averaged sample further than the step's height plus this many of its noise
sigmas from both levels (an impact's main lobe) does not place the step [-]."""


@dataclass(frozen=True)
class OffsetStep:
    """A DC offset step of a record."""

    index: int
    """First sample at the new level."""
    height: float
    """New level less old [N]."""
    significance: float
    """Height over the noise of the level change [-]."""
    window: tuple
    """``(first, stop)`` sample indices searched for it (the two windows' inner
    ends)."""
    lobe: tuple = None
    """``(first, stop)`` sample indices of the impact's main lobe it lies in, somewhere,
    when it cannot be told from the impact there (placed at the lobe's middle); else
    None (:mod:`dem_check.campaign.step_ringing`)."""
    note: str = ""
    """How it was told from an impact, when that needed a model (``"; ..."``, appended
    to its row's reason; :mod:`dem_check.campaign.edge_models`)."""

    def reason(self, t):
        """The reason of its ``"offset step"`` row; ``t``: the record's sample times [s]."""
        at = float(t[self.index])
        reason = (
            f"the level changed by {self.height:.4g} N at {at:.6g} s and stayed "
            f"({self.significance:.3g} sigma of a level change): a DC offset step, not an "
            "impact (an impact's signal returns to its level after the contact and the "
            "sensor's ringing); the record after it was shifted back before impacts were "
            f"looked for{self.note}"
        )
        if self.lobe is not None:
            reason += (
                f"; it lies somewhere inside the impact's main lobe from "
                f"{float(t[self.lobe[0]]):.6g} to {float(t[self.lobe[1] - 1]):.6g} s and "
                "cannot be told from the impact there: placed at the lobe's middle, the "
                "impact's samples between it and the true step read its height off"
            )
        return reason


def _local_spread(changes, half):
    """Spread [N] of the level ``changes`` within ``half`` boundaries either side of
    each (1.4826 times their median absolute deviation from their running median)."""
    width = 2 * half + 1
    centred = changes - median_filter(changes, width, mode="nearest")
    return MAD_TO_SIGMA * median_filter(np.abs(centred), width, mode="nearest")


def _gap_spread(levels, firsts, stops, slope, counts):
    """Spread [N] of the drift-corrected level change at each boundary whose two
    windows lie further apart than a window (masked blocks between or among them),
    read on the record: the changes between every two full windows of unmasked blocks
    the same number of blocks apart (0 where none is further apart, or fewer than
    four windows of such pairs)."""
    size = WINDOW_PERIODS
    period = int(np.max(stops - firsts))
    blocks = firsts // period
    grid = np.full(int(blocks[-1]) + 1, np.nan)
    grid[blocks] = levels
    out = np.zeros(levels.size - 1)
    if grid.size < 2 * size:
        return out
    # medians of the full windows of unmasked blocks starting at each block (nan else)
    medians = np.median(np.lib.stride_tricks.sliding_window_view(grid, size), axis=1)
    on_grid = np.interp(np.arange(grid.size), blocks[1:], slope) * period
    j = np.arange(1, levels.size)
    n_before, n_after = counts
    reach = blocks[np.minimum(j + n_after - 1, levels.size - 1)] - blocks[j - n_before] + 1
    gaps = reach - n_before - n_after
    for gap in np.unique(gaps[gaps > 0]):
        i = np.arange(max(medians.size - size - gap, 0))
        change = medians[i + size + gap] - medians[i] - on_grid[i + size] * (size + gap)
        change = change[np.isfinite(change)]
        if change.size >= 4 * size:
            spread = MAD_TO_SIGMA * np.median(np.abs(change - np.median(change)))
            out[gaps == gap] = spread
    return out


def block_levels(values, period, masked):
    """Mean of each block of ``period`` samples left after the mask, with its first
    sample index and centre index."""
    firsts = np.arange(0, values.size, period)
    stops = np.r_[firsts[1:], values.size]
    sums = np.add.reduceat(values, firsts)
    hit = np.add.reduceat(masked.astype(int), firsts) > 0
    keep = ~hit
    firsts, stops = firsts[keep], stops[keep]
    return sums[keep] / (stops - firsts), firsts, stops


def _level_changes(levels, firsts, stops):
    """Drift-corrected level change at each boundary, its significance, the drift's
    slope [N per sample] and the level just before the boundary (module steps 2-4)."""
    size = WINDOW_PERIODS
    before, after, (n_before, n_after) = window_medians(levels, size)
    # each window's time: its blocks' median centre (under a drift, the median level's;
    # their mean lies in the gap of a window across a masked impact: seed 281 of
    # bench_weak_impacts.py, a 0.10 N change of a linear drift read as a step)
    centres, j = 0.5 * (firsts + stops - 1).astype(float), np.arange(1, levels.size)
    lo = j - n_before  # the centres ascend: the median is the middle one (or two)
    left = 0.5 * (centres[lo + (n_before - 1) // 2] + centres[lo + n_before // 2])
    right = 0.5 * (centres[j + (n_after - 1) // 2] + centres[j + n_after // 2])
    span = np.maximum(right - left, 1.0)
    change = after - before
    # the median rate of change over DRIFT_WINDOWS windows either side: a step raises
    # the rate at fewer than a window of boundaries, the drift at all of them
    full = (n_before == size) & (n_after == size)
    slope = running_nanmedian(np.where(full, change / span, np.nan), DRIFT_WINDOWS * size)
    corrected = change - slope * span
    scale = np.sqrt((1.0 / n_before + 1.0 / n_after) * size / 2.0)
    reference = corrected[full] if full.sum() >= 4 * size else corrected
    spread = MAD_TO_SIGMA * np.median(np.abs(reference - np.median(reference)))
    spread = np.maximum(spread, _local_spread(corrected / scale, DRIFT_WINDOWS * size))
    spread = np.maximum(spread, _gap_spread(levels, firsts, stops, slope, (n_before, n_after)))
    error = np.maximum(spread * scale, np.finfo(float).tiny)
    significance = np.abs(corrected) / error
    edge = firsts[j].astype(float)
    level = before + slope * (edge - left)  # the old level at the boundary
    return {
        "height": corrected,
        "significance": significance,
        "slope": slope,
        "level": level,
        "error": error,
    }


def split(x, level, height, noise):
    """Index in ``x`` of the least-absolute-deviation split between ``level`` and
    ``level + height``, samples far from both left out, and how many were left out."""
    old, new = x - level, x - (level + height)
    cost = np.abs(old) - np.abs(new)
    far = np.minimum(np.abs(old), np.abs(new)) > abs(height) + FAR_SIGMAS * noise
    cost[far] = 0.0
    return int(np.argmin(np.r_[0.0, np.cumsum(cost)])), int(far.sum())


def _place(values, period, window, boundary, change, noise):
    """Index of the first sample at the new level in ``window`` (module step 5): the
    split on the record averaged over one period (no sensor ringing), then on the
    samples themselves within a period of it (a step left a period's width off would
    leave a pulse behind), unless most of those are far from both levels (ringing)."""
    first, stop = window
    level, slope, height = change

    def levelled(lo, hi, x):
        return x - slope * (np.arange(lo, hi) - boundary)

    averaged = uniform_filter1d(values[first:stop], period, mode="nearest")
    coarse = first + split(levelled(first, stop, averaged), level, height, noise[0])[0]
    lo, hi = max(first, coarse - period), min(stop, coarse + period)
    fine, far = split(levelled(lo, hi, values[lo:hi]), level, height, noise[1])
    return lo + fine if 2 * far < hi - lo else coarse


def _one_pass(values, period, masked, ring):
    levels, firsts, stops = block_levels(values, period, masked)
    if levels.size < 2:
        return []
    changes = _level_changes(levels, firsts, stops)
    significance = changes["significance"]
    size = WINDOW_PERIODS
    largest = significance == maximum_filter1d(significance, 2 * size + 1, mode="constant")
    noise = (difference_sigma(levels), difference_sigma(values))  # period means, samples
    found = []
    high = np.abs(changes["height"]) >= LEAST_HEIGHT * noise[1]
    chosen = []  # medians tie: equal largest changes at neighbouring boundaries are one
    # a change across an impact under the threshold may be a step pair's sum, whose own
    # level changes inflate its noise: it is read too (_pair_significance)
    j = np.arange(1, levels.size)
    held = np.r_[0, np.cumsum(masked)]  # masked samples before each index
    windows = (
        firsts[np.maximum(j - size // 2, 0)],
        stops[np.minimum(j + size // 2, levels.size - 1)],
    )
    across = (held[windows[1]] > held[windows[0]]) & (ring is not None)
    for k in np.flatnonzero(((significance >= STEP_SIGMAS) | across) & largest & high):
        if not chosen or k - chosen[-1] > size:
            chosen.append(k)
    for k in chosen:
        # a step moves the medians for half a window either side of it
        lo, hi = max(k + 1 - size // 2, 0), min(k + 1 + size // 2, levels.size - 1)
        window = (int(firsts[lo]), int(stops[hi]))
        change = (changes["level"][k], changes["slope"][k], changes["height"][k])
        index = _place(values, period, window, int(firsts[k + 1]), change, noise)
        lobe, height = None, float(changes["height"][k])
        if ring is not None and masked[window[0] : window[1]].any():  # across an impact
            first, stop = window
            x = values[first:stop] - change[1] * (np.arange(first, stop) - firsts[k + 1])
            # the height read again on the samples, the ringing fitted
            height, placed, other = read_across(
                x, change[0], change[2], period, FAR_SIGMAS * noise[0], ring
            )
            if placed is not None:
                index = first + placed[0]
                lobe = None if placed[1] is None else tuple(first + i for i in placed[1])
            sigmas = _both(other, period, noise)
            if sigmas:  # a step before the impact and one in its ringing
                pair = [
                    OffsetStep(at, h, sigma, window)
                    for at, h, sigma in zip(
                        (index, first + other[0]), other[1], sigmas, strict=True
                    )
                ]
                if (
                    significance[k] >= STEP_SIGMAS
                    or _pair_significance(values, period, masked, pair, k, changes) >= STEP_SIGMAS
                ):
                    found += pair
                continue
        inside = placed_inside(index, window, values.size, period)
        if not (masked[window[0] : window[1]].any() or inside):
            continue  # no impact in the window, its samples at one level
        if significance[k] >= STEP_SIGMAS and abs(height) >= LEAST_HEIGHT * noise[1]:
            found.append(OffsetStep(index, height, float(significance[k]), window, lobe))
    return found


def _pair_significance(values, period, masked, pair, k, changes):
    """The level change at boundary ``k`` across an impact (the sum of a step ``pair``
    before it and in its ringing, :func:`second_across`) over its noise read on the
    record with the pair taken out [-]. The noise of a level change is the spread of the
    record's changes where there is no step; the pair's sum moves the changes at the
    boundaries within half a window of it (a quarter of a 5 ms record's boundaries) and
    the drift's slope read over four windows, so read on the record as it comes it
    counts the pair's own changes as noise (seed 4 of a step before an impact and one
    in its ringing: 0.048 N, against 0.034 N with the two true steps taken out)."""
    rest = remove_steps(values, pair)
    levels, firsts, stops = block_levels(rest, period, masked)
    error = _level_changes(levels, firsts, stops)["error"][k]
    return abs(float(changes["height"][k])) / error


def _both(other, period, noise):
    """The significances of the two steps of :func:`second_across` (each height over the
    standard error of its two levels), or None unless both reach :data:`STEP_SIGMAS` of
    those and :data:`LEAST_HEIGHT` sample sigmas (``noise``: of the period means and of
    the samples [N])."""
    if other is None:
        return None
    out = []
    for height, sides in zip(other[1], other[2], strict=True):
        error = np.hypot(*(level_error(noise[0], period, n) for n in sides))
        sigmas = abs(height) / max(error, np.finfo(float).tiny)
        if sigmas < STEP_SIGMAS or abs(height) < LEAST_HEIGHT * noise[1]:
            return None
        out.append(float(sigmas))
    return out


def find_steps(values, period, masked, ring=None):
    """The DC offset steps of a record (module docstring).

    Parameters
    ----------
    values : numpy.ndarray
        The record [N], finite.
    period : int
        The sensor's period [samples], >= 1.
    masked : numpy.ndarray of bool
        Samples of the impacts found on a first pass, with their ringing.
    ring : tuple, optional
        ``(sensor, dt)``: the sensor and the sampling interval [s]; a step found across
        an impact is then placed with the sensor's free ringing fitted
        (:func:`dem_check.campaign.step_ringing.read_across`).

    Returns
    -------
    list of OffsetStep
        In time order. Steps closer than a window find one another's medians moved:
        after the steps found are taken off, the record is searched again (up to
        :data:`PASSES` times).
    """
    found, settled, rest = [], [], np.asarray(values, dtype=float)
    least = LEAST_HEIGHT * difference_sigma(rest)
    for _ in range(PASSES):
        more = _one_pass(rest, period, masked, ring)
        if not more:
            break
        found += more
        rest = remove_steps(rest, more)
        settled, taken_back = settle_steps(found, period, least)
        if taken_back:
            break
    return settled


def drift_slopes(values, period, masked):
    """The drift's slope at every sample [N per sample]: that of the period means'
    level changes (module step 3) at each boundary, interpolated between them (0 where
    the record holds too few blocks)."""
    levels, firsts, stops = block_levels(np.asarray(values, dtype=float), period, masked)
    if levels.size < 2:
        return np.zeros(len(values))
    slope = _level_changes(levels, firsts, stops)["slope"]
    return np.interp(np.arange(len(values)), firsts[1:], slope)


def period_noise(values, period):
    """Noise of one period's mean of the record [N], on first differences of the means
    (drift and steps move few of them)."""
    means = uniform_filter1d(values, period, mode="nearest")[period // 2 :: period]
    if means.size < 3:
        return robust_noise(values)
    return float(difference_sigma(means))


def level_error(noise, period, samples):
    """Standard error [N] of a level read on ``samples`` samples: the period means'
    noise over the periods they span, ``noise * sqrt(period / samples)`` (exact for
    white noise, fewer than a period included)."""
    return noise * np.sqrt(period / samples)


def merge_steps(steps, reach):
    """Steps found again at one place on a later pass (a remainder of a step first read
    with a neighbour's height) made one: heights added, the larger significance kept;
    in time order.

    Parameters
    ----------
    steps : list of OffsetStep
    reach : int
        Largest distance [samples] between two indices that are one place.
    """
    out = []
    for step in sorted(steps, key=lambda step: step.index):
        if out and step.index - out[-1].index <= reach:
            last = out[-1]
            significance = max(last.significance, step.significance)
            height = last.height + step.height
            out[-1] = OffsetStep(
                last.index, height, significance, last.window, last.lobe, last.note
            )
        else:
            out.append(step)
    return out


def settle_steps(steps, period, least):
    """The steps of several passes made one list (:func:`merge_steps` within an eighth
    of a sensor period), less the places whose heights add up to under ``least``: there
    a later pass took back what an earlier one read (seed 11 of
    ``benchmarks/bench_weak_impacts.py``: a 0.112 N step read across an impact, then
    -0.124 N at the same place, listed as a -0.012 N step before). A pass after such a
    place would read the first step again, so the search stops there.

    Parameters
    ----------
    steps : list of OffsetStep
        Every pass's steps.
    period : int
        The sensor's period [samples].
    least : float
        Smallest height of a step [N]: :data:`LEAST_HEIGHT` sample-noise sigmas.

    Returns
    -------
    list of OffsetStep
        In time order.
    bool
        Whether a place was taken back (the search stops).
    """
    merged = merge_steps(steps, max(1, period // 8))
    kept = [step for step in merged if abs(step.height) >= least]
    return kept, len(kept) < len(merged)


def remove_steps(values, steps):
    """The record with each step taken off: every sample from a step's index on
    shifted by minus its height [N]."""
    out = np.array(values, dtype=float)
    for step in steps:
        out[step.index :] -= step.height
    return out
