"""Runs of the first pass that are offset steps, not impacts: two steps closer than the
period means' windows (issue 22).

Two DC offset steps a fraction of a millisecond apart leave the samples between them
off the running baseline, which follows neither: the first pass reads them as a run.
A box (a step and its opposite) then reads as an impact, and being masked as one it is
invisible to :func:`dem_check.campaign.steps.find_steps`, whose medians would see only
the two steps' sum anyway. So each run is tested against the model of a record that
holds no impact: a level that changes once or twice (a change point model) on the drift
of its neighbourhood.

1. **Neighbourhood.** The run with its mask (two periods before, its quiet hold after)
   and up to :data:`CONTEXT_PERIODS` unmasked sensor periods on each side, less the
   drift's slope there (:func:`dem_check.campaign.steps.drift_slopes`).
2. **Change points.** The exact least-squares piecewise constant fit with one and with
   two change points (``ruptures.KernelCPD``, linear kernel: Killick et al. 2012's
   dynamic programme, compiled) on means of an eighth of a sensor period; each change
   point is then placed on the samples by a least-absolute-deviation split between its
   two levels.
3. **No impact left.** The record less the fit, averaged over one sensor period (the
   sensor's ringing averages out, an impact's main lobe does not), stays within
   :data:`FLAT_SIGMAS` of the neighbourhood's own spread of period means (hum and 1/f
   noise included), and the run's samples spread no more than :data:`FLAT_RATIO` times
   the quiet samples beside it. One change point is tried first.
4. **Significance.** Each change is at least :data:`~dem_check.campaign.steps.STEP_SIGMAS`
   standard errors of the difference of its two levels (each read on the samples of
   its piece) and :data:`~dem_check.campaign.steps.LEAST_HEIGHT` sample-noise sigmas.

A step inside an impact's ringing is not such a run (the impact's lobe is left over):
the period means find it across the masked impact. A step a few periods before an
impact starts the impact's run: :func:`head_steps` reads it on the run's head, one flat
level up to the lobe's rise.

References
----------
Killick, R., Fearnhead, P. and Eckley, I. A. (2012) Optimal detection of changepoints
with a linear computational cost. J. Am. Stat. Assoc. 107, 1590-1598. Truong, C.,
Oudre, L. and Vayatis, N. (2020) Selective review of offline change point detection
methods. Signal Processing 167, 107299 (``ruptures``).
"""

import itertools

import numpy as np
import ruptures
from scipy.ndimage import median_filter, uniform_filter1d

from contactlab.signals import robust_noise
from dem_check.campaign.edge_models import tail_fit
from dem_check.campaign.plate_swings import judged_steps
from dem_check.campaign.step_edges import edge_steps
from dem_check.campaign.step_ringing import difference_sigma, rise
from dem_check.campaign.steps import (
    FLAT_RATIO,
    LEAST_HEIGHT,
    STEP_SIGMAS,
    WINDOW_PERIODS,
    OffsetStep,
    block_levels,
    drift_slopes,
    find_steps,
    level_error,
    period_noise,
    remove_steps,
    split,
)

__all__ = [
    "CONTEXT_PERIODS",
    "FLAT_SIGMAS",
    "end_pairs",
    "head_steps",
    "run_steps",
    "search_steps",
]

CONTEXT_PERIODS = 8
"""Unmasked sensor periods on each side of a run that give its levels before and after
[-] (half a window of :data:`~dem_check.campaign.steps.WINDOW_PERIODS`)."""

FLAT_SIGMAS = 6.0
"""Largest deviation of the period-averaged record from the change point fit, in sigmas
of the record's period means about their running median (:func:`_period_spread`) [-]:
1/f noise and hum wander the period means of a box of two steps (1/f noise as large as
the white noise) by up to 5 of them over 0.5 ms; an impact's main lobe leaves 16-44
(measured on the hard mix of ``benchmarks/bench_steps.py``)."""

LOCAL_WINDOWS = 2
"""Windows (:data:`~dem_check.campaign.steps.WINDOW_PERIODS` periods each) on each side of
a run over which the period means' spread is read as well [-] (0.8 ms at 40 kHz, less
than the plate modes' decay)."""

DECIMATION = 8
"""Means per sensor period the change points are searched on [-]."""

HEAD_PERIODS = 4
"""Sensor periods at the head of a run that are one level when a step starts it [-]
(:func:`head_steps`; a step closer to the impact is placed across it:
:mod:`dem_check.campaign.step_ringing`)."""

BOX_PERIODS = 6
"""Shortest time between two steps read on one run, in sensor periods [-] (0.15 ms at
40 kHz): a shorter pair is an impact's main lobe as well. A 0.32 N bounce of the hard
grain (whose damped contact steps its force on at the touch) fits a box of 65 us with
edges as sharp as a step's and a top flat to the noise; a weak impact 0.25 ms after a
true step fits a pair 64 us apart that does not return to its level (both measured,
the second on the hard mix of ``benchmarks/bench_steps.py``)."""


def _context(masked, lo, hi, size):
    """Indices ``(start, stop)`` reaching up to ``size`` unmasked samples before ``lo``
    and after ``hi`` (stopping at the next masked sample)."""
    before = np.flatnonzero(masked[max(0, lo - size) : lo])
    start = max(0, lo - size) + (int(before[-1]) + 1 if before.size else 0)
    after = np.flatnonzero(masked[hi : hi + size])
    stop = min(masked.size, hi + size) if not after.size else hi + int(after[0])
    return start, stop


def _period_spread(values, period, masked):
    """Spread [N] of the record's period means outside the impacts about their running
    median over a window (:data:`~dem_check.campaign.steps.WINDOW_PERIODS` + 1 means):
    the white noise averaged over a period and the slower noise (1/f, hum) that moves a
    level read over a window."""
    levels = block_levels(values, period, masked)[0]
    if levels.size < 2:
        return 0.0
    return robust_noise(levels - median_filter(levels, WINDOW_PERIODS + 1, mode="nearest"))


def _fit(x, period, changes):
    """Change points of ``x`` (module step 2) and the piecewise-median fit."""
    q = max(1, period // DECIMATION)
    means = x[: x.size // q * q].reshape(-1, q).mean(axis=1)
    if means.size < 2 * changes + 2:
        return None
    coarse = ruptures.KernelCPD(kernel="linear", min_size=1).fit(means)
    cuts = [0, *(q * b for b in coarse.predict(n_bkps=changes)[:-1]), x.size]
    noise = difference_sigma(x)
    for k in range(1, len(cuts) - 1):  # on the samples, between the two levels
        lo, hi = max(cuts[k - 1] + 1, cuts[k] - q), min(cuts[k + 1] - 1, cuts[k] + q)
        level = np.median(x[cuts[k - 1] : cuts[k]])
        height = np.median(x[cuts[k] : cuts[k + 1]]) - level
        cuts[k] = lo + split(x[lo:hi], level, height, noise)[0]
    pieces = [x[a:b] for a, b in itertools.pairwise(cuts)]
    if min(piece.size for piece in pieces) < 1:
        return None
    fitted = np.concatenate([np.full(p.size, np.median(p)) for p in pieces])
    return cuts, pieces, fitted


def _steps_of(x, start, period, fit, quiet, settles=False):
    """The fit's change points as :class:`OffsetStep` if they explain the record
    (module steps 3 and 4), else None; ``settles``: two changes closer than
    :data:`BOX_PERIODS` are steps too when the last level is not the first (an impact's
    lobe returns to its level)."""
    cuts, pieces, fitted = fit
    spread = uniform_filter1d(x - fitted, period, mode="nearest")
    if np.max(np.abs(spread)) > FLAT_SIGMAS * quiet["periods"]:
        return None
    inner = (x - fitted)[cuts[0] + quiet["before"] : cuts[-1] - quiet["after"]]
    if inner.size and robust_noise(inner) > FLAT_RATIO * quiet["samples"]:
        return None
    found = []
    if len(pieces) == 3 and pieces[1].size < BOX_PERIODS * period:
        if not settles or _net(pieces, period, quiet["noise"]) < STEP_SIGMAS:
            return None  # an impact's main lobe as well
    for k in range(1, len(cuts) - 1):
        old, new = pieces[k - 1], pieces[k]
        height = float(np.median(new) - np.median(old))
        error = np.hypot(*(level_error(quiet["noise"], period, p.size) for p in (old, new)))
        significance = abs(height) / max(error, np.finfo(float).tiny)
        if significance < STEP_SIGMAS or abs(height) < LEAST_HEIGHT * quiet["samples"]:
            return None
        window = (start + cuts[k - 1], start + cuts[k + 1])
        found.append(OffsetStep(start + cuts[k], height, float(significance), window))
    return found


def _net(pieces, period, noise):
    """The last piece's level less the first's over its standard error [-]."""
    first, last = pieces[0], pieces[-1]
    error = np.hypot(*(level_error(noise, period, p.size) for p in (first, last)))
    return abs(float(np.median(last) - np.median(first))) / max(error, np.finfo(float).tiny)


def end_pairs(values, runs, period, masked, slopes):
    """Two offset steps in a run to the record's last sample, closer than
    :data:`BOX_PERIODS` (which a single step's test at the edge,
    :func:`dem_check.campaign.step_edges.edge_steps`, does not read): the change point model
    with two changes on the run and the unmasked periods before it, the level at the end
    not the one before the run (seed 48 of the hard mix of ``benchmarks/bench_steps.py``:
    steps of -0.72 and 0.16 N 76 us apart, 0.12 ms before the end at 1 MHz, read as a
    ``negative`` impact).

    Parameters
    ----------
    values, period, masked, slopes
        As for :func:`run_steps`.
    runs : list of tuple
        ``(first, last)`` of the runs to the record's end.

    Returns
    -------
    list of OffsetStep
        Both steps of every run the model with two changes explains; a run it does not
        explain gives none.
    """
    values = np.asarray(values, dtype=float)
    noise = period_noise(values, period)
    out = []
    for first, _ in runs:
        start = _context(masked, first, first, CONTEXT_PERIODS * period)[0]
        if first - start < period:
            continue
        x = values[start:] - slopes[first] * (np.arange(start, values.size) - first)
        side = x[: first - start]
        quiet = {
            "noise": noise,
            "samples": robust_noise(side - np.median(side)),
            "periods": max(_period_spread(values, period, masked), noise),
            "before": first - start,
            "after": 0,
        }
        fit = _fit(x, period, 2)
        out += (_steps_of(x, start, period, fit, quiet, settles=True) if fit else None) or []
    return out


def run_steps(values, runs, period, masked, slopes):
    """The offset steps that make up whole runs of the first pass (module docstring).

    Parameters
    ----------
    values : numpy.ndarray
        The record [N], finite.
    runs : list of tuple
        ``(first, last, lo, hi)``: a run's first and last sample and its mask
        ``[lo, hi)`` (sample indices); runs at the record's edges are left to
        :func:`dem_check.campaign.step_edges.edge_steps`.
    period : int
        The sensor's period [samples].
    masked : numpy.ndarray of bool
        Samples of the first pass's impacts, with their ringing.
    slopes : numpy.ndarray
        The drift's slope at every sample [N per sample].

    Returns
    -------
    list of tuple
        ``(run, steps)``: each run (as given) that is one or two steps, and its
        :class:`~dem_check.campaign.steps.OffsetStep` list.
    """
    values = np.asarray(values, dtype=float)
    noise = period_noise(values, period)
    spread = max(_period_spread(values, period, masked), noise)
    size = CONTEXT_PERIODS * period
    out = []
    for run in runs:
        _, _, lo, hi = run
        start, stop = _context(masked, lo, hi, size)
        # the period means' spread around the run too, where larger: a strong impact's
        # plate modes swing the level there for milliseconds (1890 Hz on seed 1 of the
        # hard mix: 0.13 N over a 0.22 ms box, the neighbourhood's spread 0.035 N
        # against the record's 0.0185)
        near = slice(
            max(0, lo - LOCAL_WINDOWS * WINDOW_PERIODS * period),
            hi + LOCAL_WINDOWS * WINDOW_PERIODS * period,
        )
        local = max(spread, _period_spread(values[near], period, masked[near]))
        # the quiet hold after the run (up to the next run's mask) is a level too
        if lo - start < period or stop - hi + hi - run[1] < period:
            continue
        x = values[start:stop] - slopes[lo] * (np.arange(start, stop) - lo)
        # each side about its own level: a step between them is no noise
        sides = [side for side in (x[: lo - start], x[hi - start :]) if side.size >= period]
        levelled = np.concatenate([side - np.median(side) for side in sides])
        quiet = {
            "noise": noise,
            "samples": robust_noise(levelled),
            "periods": local,
            "before": lo - start,
            "after": stop - hi,
        }
        for changes in (1, 2):
            fit = _fit(x, period, changes)
            steps = _steps_of(x, start, period, fit, quiet) if fit else None
            if steps:
                out.append((run, steps))
                break
    return out


def head_steps(values, runs, period, masked, slopes):
    """Offset steps at the head of a run of the first pass: a step a few periods before
    an impact starts the run (the running baseline follows neither), and the impact's
    lobe follows. Its first :data:`HEAD_PERIODS` periods are then one level, as flat as
    the quiet samples before the run (their standard deviation: a lobe raises it) and
    off the level there by :data:`~dem_check.campaign.steps.STEP_SIGMAS` standard errors
    of the two levels and :data:`~dem_check.campaign.steps.LEAST_HEIGHT` sample sigmas.
    The level change across the impact does not see it under drift and hum (a 0.275 N
    step 0.12 ms before an impact read 5.5 sigmas there: seed 14 of the hard mix of
    ``benchmarks/bench_steps.py``); placed by the least-absolute-deviation split.

    Parameters
    ----------
    values, runs, period, masked, slopes
        As for :func:`run_steps`.

    Returns
    -------
    list of OffsetStep
        One step for each run whose head holds one; its window runs from the
        neighbourhood's start to the head's end (sample indices).
    """
    values = np.asarray(values, dtype=float)
    noise = period_noise(values, period)
    out = []
    for first, last, lo, hi in runs:
        start, stop = _context(masked, lo, hi, CONTEXT_PERIODS * period)
        head = first + HEAD_PERIODS * period
        if first - start < period or head > last:
            continue
        x = values[start:stop] - slopes[lo] * (np.arange(start, stop) - lo)
        level, quiet = float(np.median(x[: first - start])), robust_noise(x[: first - start])
        at = split(
            x[: head - start],
            level,
            float(np.median(x[first - start : head - start])) - level,
            quiet,
        )[0]
        new = float(np.median(x[at : at + HEAD_PERIODS * period]))
        # the run may start a sample or two before the step; the head lasts to the rise
        old, new = x[:at], x[at : rise(x, at, (new, new), period)]
        if old.size < period or new.size < HEAD_PERIODS * period:
            continue
        height = float(np.median(new) - np.median(old))
        error = np.hypot(*(level_error(noise, period, part.size) for part in (old, new)))
        significance = abs(height) / max(error, np.finfo(float).tiny)
        if np.std(new) > FLAT_RATIO * quiet or significance < STEP_SIGMAS:
            continue
        if abs(height) < LEAST_HEIGHT * quiet:
            continue
        # a head longer than BOX_PERIODS is a longer level than a contact's
        if new.size < BOX_PERIODS * period and not _stays(x, hi - start, level, height):
            continue
        out.append(OffsetStep(start + at, height, float(significance), (start, head)))
    return out


def _stays(x, hi, level, height):
    """Whether a head step's level stays after the run (``x[hi:]``, the drift taken off):
    nearer the new level ``level + height`` than the old ``level`` [N]. A bounce of the
    hard grain fits a box of 65 us with a top flat to the noise and returns to the
    level (:data:`BOX_PERIODS`)."""
    if x.size <= hi:
        return False
    after = float(np.median(x[hi:]))
    return abs(after - level - height) < abs(after - level)


def search_steps(values, runs, period, hold, ring=None):
    """Every offset step of a record, from its first pass's candidate runs: runs that
    are steps (:func:`run_steps`), steps on the period means outside the other runs
    (:func:`dem_check.campaign.steps.find_steps`) and at the record's edges
    (:func:`dem_check.campaign.step_edges.edge_steps`).

    Parameters
    ----------
    values, runs, period
        As for :func:`dem_check.campaign.step_edges.edge_steps`.
    hold : int
        Samples past a run's last one that still belong to it (its quiet hold; the
        ``reach`` of :func:`~dem_check.campaign.step_edges.edge_steps`).
    ring : tuple, optional
        ``(sensor, dt)``, for steps found across an impact
        (:func:`dem_check.campaign.steps.find_steps`) and at the record's edges
        (:func:`dem_check.campaign.step_edges.edge_steps`).

    Returns
    -------
    list of OffsetStep
        In time order.
    """
    n = len(values)
    masked = np.zeros(n, dtype=bool)
    inner = []
    for k, (first, last) in enumerate(runs):
        # a run to the record's end is left in: a step there that the running baseline
        # missed reads as such a run, and the levels on both sides of it are needed
        if last + hold < n:  # with the lobe's rise before
            lo, hi = max(0, first - 2 * period), last + hold + 1
            masked[lo:hi] = True
            if first >= period:  # a run from the start is edge_steps' to judge
                following = runs[k + 1][0] - 2 * period if k + 1 < len(runs) else n
                inner.append((first, last, lo, max(last + 1, min(hi, following))))
    slopes = drift_slopes(values, period, masked)
    boxed = run_steps(values, inner, period, masked, slopes)
    found = [step for _, steps in boxed for step in steps]
    taken = [run for run, _ in boxed]
    found += head_steps(values, [r for r in inner if r not in taken], period, masked, slopes)
    for (_, _, lo, hi), _ in boxed:
        masked[lo:hi] = False  # a level now, no impact
    rest = remove_steps(values, found)
    levels = {run[0] for run, _ in boxed}
    edges = edge_steps(rest, [r for r in runs if r[0] not in levels], period, hold, ring)
    ends = [r for r in runs if r[0] >= period and r[1] + hold >= n]
    if ends and not any(e.index >= ends[-1][0] - period for e in edges):
        edges += end_pairs(rest, ends[-1:], period, masked, slopes)
    # an edge step's height is read on all the samples on its edge's side: it replaces
    # a step found on the period means' shortened windows there
    near = [(e.window[0] - period, e.window[1] + period) for e in edges]
    means = find_steps(rest, period, masked, ring)
    means = [s for s in means if not any(lo <= s.index < hi for lo, hi in near)]
    if ends and ring is not None:  # in a run to the end: a step, or an impact cut there?
        tail = ends[-1][0] - period
        means = [
            s
            for s in means
            if s.index < tail or tail_fit(rest, s.index, ends[-1][0], runs, hold, ring).step
        ]
    if ring is not None:  # in an impact's ringing: a step, or the plate's swing?
        means = judged_steps(rest, means, runs, period, ring)
    return sorted(found + means + edges, key=lambda step: step.index)
