"""A box of offset steps over an impact at a record's first sample: the lobe and up to
two steps fitted at once, adopted only where the steps beat the lobe model's own error
(issue 22).

:func:`dem_check.campaign.edge_models.start_fit` tells a run from the record's first
sample apart as a level step or an impact's lobe. When both are there (a step down and
a step up a tenth of a millisecond apart over an impact at the first sample: seed 15 of
``benchmarks/bench_steps.py``) neither model fits, the lobe less badly, and the run is
left to the impacts: the box reads as a ``negative`` impact and the true one is missed.

The combined model is the edge's line, the lobe (its family, onset and duration refitted
with the steps) and one or two unit steps, each placed at the best sample of the window
(greedily, then each placed again with the other and the refitted lobe). Two steps
always lower the chi-squared: they absorb noise, and on a strong impact they absorb the
lobe model's own error (a rigid wall's contact through the sensor is not the grain's:
on strong impacts at the first sample a box of 0.2-0.3 N is drawn into the lobe,
chi-squared 962 -> 556 on 383 samples). That error grows with the lobe: its chi-squared
is a fraction of the lobe's whitened energy ``E = A**2 |W r|**2 / sigma**2`` (``r`` the
lobe's unit column off the line, ``W`` the noise model's whitening filter, ``sigma`` the
innovation's standard deviation). So each step must lower the chi-squared (against the
combined model without it) by more than

``STEP_SIGMAS**2 + MODEL_ERROR * E``:

the 8 standard errors every step must reach, and the share of the lobe's energy that
steps absorb on impacts without any (:data:`MODEL_ERROR`, measured on strong impacts at
the first sample with every effect of the hard mix; module ``benchmarks/bench_edges.py``
and ``docs/campaign.md``, "A box of steps over an impact at the first sample").
"""

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from dem_check.campaign.edge_models import (
    _lobe_fit,
    _Lobes,
    _Projector,
    start_window,
    window_samples,
)

__all__ = ["MODEL_ERROR", "BoxFit", "box_fit", "start_box", "start_steps"]

MODEL_ERROR = 0.1
"""Share of the lobe's whitened energy [-] by which each step must lower the
chi-squared beyond ``STEP_SIGMAS**2`` (the lobe model's own error). Measured on 48
impacts at the first sample without steps (1, 2 and 5 MHz, 0.2-2.5 m/s): a step absorbs
at most 0.0098 of it with two steps, 0.027 with one; seed 15's steps: 1.14."""

STEP_SIGMAS = 8.0
"""Each step's chi-squared drop must reach this many standard errors squared [-], as
every step's height must (:data:`dem_check.campaign.steps.STEP_SIGMAS`)."""

ROUNDS = 3
"""Rounds of placing the steps given the lobe and fitting the lobe given the steps [-]."""


@dataclass(frozen=True)
class BoxFit:
    """The combined model of an edge window (module docstring)."""

    adopted: bool
    """Whether every step beats the noise and the lobe model's error."""
    indices: tuple
    """Each step's place: first sample at its new level (record index), in time order."""
    heights: tuple
    """Each step's height [N] (new level less old)."""
    drops: tuple
    """Each step's chi-squared drop against the combined model without it [-]."""
    chi2: float
    """Chi-squared of the combined model [-]."""
    lobe_chi2: float
    """Chi-squared of the lobe model alone [-]."""
    energy: float
    """The lobe's whitened energy ``E`` [-] (chi-squared units)."""
    lobe: tuple
    """``(family, damping, t0 [s from the record's start], tau [s], A [N])`` refitted."""

    def reason(self):
        """The comparison in words, for a step row."""
        family, damping, t0, tau, amplitude = self.lobe
        drops = ", ".join(f"{d:.4g}" for d in self.drops)
        return (
            f"a contact's force through the sensor ({family}, damping {damping:.2g}, "
            f"{amplitude:.3g} N from {t0:.4g} s over {tau:.3g} s) and {len(self.indices)} "
            f"steps fit the record's edge with chi-squared {self.chi2:.4g} against "
            f"{self.lobe_chi2:.4g} for the lobe alone; each step lowers it by {drops}, "
            f"more than {STEP_SIGMAS:g}**2 plus {MODEL_ERROR:g} of the lobe's energy "
            f"{self.energy:.4g} (the lobe model's own error)"
        )


def _steps(n, places):
    """Unit step columns at ``places`` (window indices)."""
    return (np.arange(n)[:, None] >= np.asarray(places, dtype=int)[None, :]).astype(float)


def _white_steps(projector, n, places):
    """:func:`_steps` whitened by ``projector``'s filter: one whitened step, shifted to
    each place (as :meth:`dem_check.campaign.edge_models._Lobes.white_columns`)."""
    places = np.asarray(places, dtype=int)
    last = int(places.max())
    white = projector.whiten((np.arange(-last, n - int(places.min())) >= 0).astype(float))
    return white[np.arange(n - projector.order)[:, None] + (last - places)[None, :]]


def _place_steps(y, period, noise, fixed, count):
    """The least-squares places of ``count`` (1 or 2) steps on the window, the line and
    the ``fixed`` columns (or none) fitted with them: chi-squared and the places. Every
    place, or pair of places on a grid of a sixteenth of a sensor period, is tried at
    once from the whitened step columns' inner products; each place of a pair is then
    refined at every sample within a grid step, the other held."""
    n = y.size
    if count == 1:
        return _place_among(y, period, noise, fixed, np.arange(1, n))
    grid = max(1, round(period / 16))
    places = np.arange(1, n, grid)
    projector = _Projector(y, period, noise, fixed)
    u = _white_steps(projector, n, places)
    u -= projector.basis @ (projector.basis.T @ u)
    b, gram = u.T @ projector.y_off, u.T @ u
    g = np.diag(gram).copy()
    total = float(projector.y_off @ projector.y_off)
    det = np.outer(g, g) - gram * gram
    num = np.outer(b * b, g) - 2.0 * np.outer(b, b) * gram + np.outer(g, b * b)
    upper = np.triu(det > 1e-12 * np.outer(g, g), 1)
    explained = np.full(det.shape, -np.inf)
    explained[upper] = num[upper] / det[upper]
    i, j = np.unravel_index(int(np.argmax(explained)), explained.shape)
    chosen = [int(places[i]), int(places[j])]
    if grid == 1:
        return (total - explained[i, j]) / projector.scale**2, chosen
    for k in range(2):  # each place refined within a grid step, the other held
        other = _steps(n, [chosen[1 - k]])
        near = np.arange(max(1, chosen[k] - grid + 1), min(n, chosen[k] + grid))
        near = near[near != chosen[1 - k]]
        fixed_k = other if fixed is None else np.column_stack([fixed, other])
        chi2, (chosen[k],) = _place_among(y, period, noise, fixed_k, near)
    return chi2, chosen


def _place_among(y, period, noise, fixed, places):
    """Chi-squared and the best of ``places`` for one step, the line and ``fixed``
    fitted with it."""
    projector = _Projector(y, period, noise, fixed)
    chi2 = projector.fit_white(_white_steps(projector, y.size, places))[0]
    k = int(np.nanargmin(chi2))
    return float(chi2[k]), [int(places[k])]


def _alternate(y, period, noise, lobes, grid, count, lobe, memo):
    """Steps placed given the lobe and the lobe fitted given the steps, in turn
    (:data:`ROUNDS` times), from ``lobe`` (None: the steps on the line alone first):
    chi-squared, the places and the lobe. ``memo`` holds the window's fits already made
    (the same places, or the same lobe, give the same fit: the two starts often meet)."""
    chosen = None
    for _ in range(ROUNDS):
        key = ("places", count, lobe)
        if key not in memo:
            fixed = None if lobe is None else _column(lobes, lobe)[:, None]
            memo[key] = sorted(_place_steps(y, period, noise, fixed, count)[1])
        if memo[key] == chosen:
            break  # the lobe fitted given these places already
        chosen = memo[key]
        key = ("lobe", *chosen)
        if key not in memo:
            projector = _Projector(y, period, noise, _steps(y.size, chosen))
            memo[key] = _lobe_fit(projector, lobes, grid, positive=True)
        chi2, lobe = memo[key]
    return chi2, chosen, lobe


def _chi2(y, period, noise, columns):
    """Chi-squared of the line and ``columns`` and the amplitude of the last one."""
    projector = _Projector(y, period, noise, columns[:, :-1])
    chi2, amplitude, _ = projector.fit(columns[:, -1:])
    return float(chi2[0]), float(amplitude[0])


def box_fit(values, window, ring, noise, onsets, lobe_chi2, steps=(2, 1)):
    """The line, an impact's lobe and up to two offset steps fitted to a window at the
    record's start (module docstring).

    Parameters
    ----------
    values : numpy.ndarray
        The record [N].
    window : tuple
        ``(first, stop)`` sample indices of the window (as
        :func:`dem_check.campaign.edge_models.judge_edge`'s).
    ring : tuple
        ``(sensor, dt)``.
    noise : ARNoise or float
        The noise model (:func:`dem_check.campaign.edge_models.edge_noise`).
    onsets : tuple
        ``(earliest, latest)`` onsets of the lobe [samples from the window's first].
    lobe_chi2 : float
        Chi-squared of the lobe alone on the window [-].
    steps : tuple of int, default (2, 1)
        Numbers of steps fitted in turn (each 1 or 2): the first fit adopted is
        returned, else the last.

    Returns
    -------
    BoxFit
    """
    y, period = window_samples(values, window, ring)
    earliest, latest = onsets
    grid = np.arange(earliest, latest + 1, max(1, round(period / 16)))
    lobes = _Lobes(y.size, max(0, -earliest) + 2, ring)
    alone = _lobe_fit(_Projector(y, period, noise), lobes, grid, positive=True)[1]
    memo = {}
    for count in steps:
        # two starts: the lobe fitted alone, whose misfit can draw the steps to its own
        # error, and the steps placed on the line alone, whose misfit is the lobe
        fits = [
            _alternate(y, period, noise, lobes, grid, count, start, memo) for start in (alone, None)
        ]
        box = _judge(y, period, noise, lobes, min(fits, key=lambda fit: fit[0]))
        if box.adopted:
            break
    family, damping, t0, tau, amplitude = box.lobe
    return dataclasses.replace(
        box,
        indices=tuple(window[0] + p for p in box.indices),
        lobe_chi2=lobe_chi2,
        lobe=(family, damping, t0 + window[0] * ring[1], tau, amplitude),
    )


def _judge(y, period, noise, lobes, fit):
    """The :class:`BoxFit` of a fit ``(chi2, places, lobe)`` on the window (indices
    and ``t0`` from its first sample, ``lobe_chi2`` not set): each step's drop against
    the model without it, the lobe's energy and whether the steps are adopted."""
    _, chosen, lobe = fit
    n = y.size
    lobe_column = _column(lobes, lobe)
    columns = np.column_stack([lobe_column, _steps(n, chosen)])
    chi2, drops, heights = math.nan, [], []
    for k, place in enumerate(chosen):
        others = np.delete(columns, 1 + k, axis=1)
        without = _chi2(y, period, noise, others)[0]
        ordered = np.column_stack([others, _steps(n, [place])])
        chi2, height = _chi2(y, period, noise, ordered)
        drops.append(without - chi2)
        heights.append(height)
    error = _Projector(y, period, noise).fit(lobe_column[:, None])[2][0]
    energy = float((lobe[4] / error) ** 2)  # A**2 |W r|**2 / sigma**2, A with the steps
    passes = all(d > STEP_SIGMAS**2 + MODEL_ERROR * energy for d in drops)
    adopted = bool(chosen) and energy >= STEP_SIGMAS**2 and passes
    return BoxFit(
        adopted=adopted,
        indices=tuple(chosen),
        heights=tuple(heights),
        drops=tuple(drops),
        chi2=chi2,
        lobe_chi2=math.nan,
        energy=energy,
        lobe=lobe,
    )


def _column(lobes, lobe):
    """The lobe's unit column on the window (``lobe`` as :func:`_lobe_fit` returns it)."""
    family, damping, t0, tau, _ = lobe
    return lobes.columns((family, damping), [t0], tau)[:, 0]


def start_box(values, index, runs, reach, ring, lobe_chi2):
    """:func:`box_fit` on the window of
    :func:`dem_check.campaign.edge_models.start_fit` for a step found ``index`` samples
    after the record's start whose edge fit preferred the lobe (chi-squared
    ``lobe_chi2``); arguments as :func:`~dem_check.campaign.edge_models.start_fit`'s."""
    window, noise, onsets = start_window(values, index, runs, reach, ring)
    return box_fit(values, window, ring, noise, onsets, lobe_chi2)


def start_steps(values, index, runs, reach, ring, lobe_chi2):
    """The steps of :func:`start_box` when it adopts them, else none: ``(index, height
    [N], significance [-], window, note)`` each, the significance the square root of
    its chi-squared drop, the window from the first sample to the last step, the note
    the fit's comparison (for its row's reason)."""
    box = start_box(values, index, runs, reach, ring, lobe_chi2)
    if not box.adopted:
        return []
    note = f"; {box.reason()}: a box of offset steps over an impact at the first sample"
    window = (0, max(box.indices) + 1)
    return [
        (at, height, float(np.sqrt(drop)), window, note)
        for at, height, drop in zip(box.indices, box.heights, box.drops, strict=True)
    ]
