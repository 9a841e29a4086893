"""The level part of :func:`contactlab.signals.running_baseline`: block medians, their
interpolation, and each sample's nearest block level (its residual).

It depends only on the samples and the block length, not on the samples left out of the
local noise nor on a pulse at the record's start, so a caller that reads the noise of
one record several ways (:func:`dem_check.campaign.noise.noise_floor`: a first pass, then
with the pulses found left out, then the quietest block) computes it once and passes it
to :func:`contactlab.signals.levels_baseline` and :func:`contactlab.signals.quiet_window`.
"""

from typing import NamedTuple

import numpy as np

from contactlab.errors import ParameterError
from contactlab.kernels.levels import nearest_residual
from contactlab.validation import check_count, check_samples

__all__ = ["EDGE_QUIET", "LOCAL_MEAN_FRACTION", "MAD_TO_SIGMA", "BlockLevels", "block_levels"]

MAD_TO_SIGMA = 1.482602218505602
"""Standard deviation of Gaussian noise per median absolute deviation, ``1 / Phi^-1(3/4)``
[-]: ``robust_noise`` reads the noise as this many MADs, which a pulse covering less
than half of the samples cannot move far (breakdown point 50 %)."""

EDGE_QUIET = 3.0
"""Largest robust noise of a record's first or last eighth of a block, in white-noise
sigmas, for it to give the level before a step in the first block (after one in the
last) [-]: 1/f noise and hum add a little to the white noise over so short a stretch; a
pulse of 6 sigmas or more with its ringing adds more."""

LOCAL_MEAN_FRACTION = 8
"""The level of a sample is chosen by the mean of the samples on one side of it over
this fraction of a block [-]: long enough to average the noise out (so the choice does
not follow the noise and shrink the residual)."""


class BlockLevels(NamedTuple):
    """The running baseline's levels of a record (see :func:`block_levels`)."""

    y: np.ndarray
    """The samples (any unit), as checked."""
    width: int
    """Block length [samples]."""
    edges: np.ndarray
    """Block boundaries [samples]: block ``k`` is ``y[edges[k]:edges[k + 1]]``."""
    level: np.ndarray
    """The block medians interpolated between the block centres (unit of ``y``); read
    only: :func:`contactlab.signals.levels_baseline` copies it before changing it."""
    residual: np.ndarray
    """``y`` minus each sample's nearest block level (unit of ``y``); read only."""
    block: np.ndarray
    """Each sample's block index [-]."""


def _block_medians(y, width):
    """Median and MAD-noise of consecutive blocks of ``width`` samples (the last block
    takes the remainder, or joins the one before it when shorter than half a block)."""
    count = max(1, round(y.size / width))
    edges = np.linspace(0, y.size, count + 1).round().astype(int)
    medians = np.empty(count)
    for k in range(count):
        medians[k] = np.median(y[edges[k] : edges[k + 1]])
    return edges, medians


def _edge_levels(y, span, medians):
    """Levels the first block has before it and the last block after it: the median of
    the record's first (last) ``span`` samples when they are quiet, else the outer
    block's median.

    A DC offset step in the first block leaves the samples before it with no block level
    of their own (the block's median is the level after the step), and one in the last
    block those after it. The record's first ``span`` samples give their level, if they
    hold no pulse: their robust noise must be at most :data:`EDGE_QUIET` times the
    white noise of the outer block (read on its first differences, which a step, drift
    or a pulse barely moves), else a record that starts at an impact would offer the
    impact's own level as a baseline."""
    levels = []
    block = span * LOCAL_MEAN_FRACTION
    for part, outer, edge in (
        (y[:span], medians[0], y[:block]),
        (y[-span:], medians[-1], y[-block:]),
    ):
        differences = np.diff(edge)
        white = MAD_TO_SIGMA * float(np.median(np.abs(differences - np.median(differences))))
        level = float(np.median(part))
        spread = MAD_TO_SIGMA * float(np.median(np.abs(part - level)))
        levels.append(level if spread <= EDGE_QUIET * white / np.sqrt(2.0) else outer)
    return levels


def block_levels(y, width):
    """The running baseline's level and residual of a record (the method:
    :func:`contactlab.signals.running_baseline`).

    Parameters
    ----------
    y : array_like
        Finite samples (any unit), at least 2 blocks.
    width : int
        Block length [samples], >= 8.

    Returns
    -------
    BlockLevels

    Raises
    ------
    ParameterError
        Bad ``width``, non-finite samples or too few blocks.
    """
    width = check_count("width", width, low=8)
    y = check_samples("y", y)
    if y.size < 2 * width:
        raise ParameterError(
            f"running_baseline needs at least two blocks of {width} samples in y; got {y.size}"
        )
    edges, medians = _block_medians(y, width)
    index = np.arange(y.size)
    centres = 0.5 * (edges[:-1] + edges[1:] - 1)
    level = np.interp(index, centres, medians)
    if medians.size > 1:  # beyond the outer centres, the outer slopes go on (drift)
        head, tail = index < centres[0], index > centres[-1]
        slope = np.diff(medians) / np.diff(centres)
        level[head] = medians[0] + slope[0] * (index[head] - centres[0])
        level[tail] = medians[-1] + slope[-1] * (index[tail] - centres[-1])
    block = np.repeat(np.arange(medians.size), np.diff(edges))
    span = max(2, width // LOCAL_MEAN_FRACTION)
    head, tail = _edge_levels(y, span, medians)
    residual = nearest_residual(y, level, block, medians, head, tail, span)  # compiled
    return BlockLevels(y, width, edges, level, residual, block)
