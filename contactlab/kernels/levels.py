"""The running baseline's residual compiled: each sample's distance to the block level
nearest the mean of the samples on one side of it (:mod:`contactlab._block_levels`).

In numpy the side means (a cumulative sum and four shifted differences) and the choice
among four candidate levels made a dozen temporary arrays of the record's length, four
times per record in ``find_impacts`` (0.7 s of the 1.5 M-sample realistic record under
cProfile). This loop does the same operations in the same order (``numpy.cumsum``'s
running sum, the same divisions, the first nearest candidate as ``numpy.where`` keeps
it), so its residual is numpy's to the last bit
(``tests/contactlab/test_block_levels.py``).
"""

import numpy as np

from contactlab.compiled import njit

__all__ = ["nearest_residual", "side_means"]


@njit(cache=True, error_model="numpy")
def side_means(y, span):
    """Per sample, the mean of the ``span`` samples before it or of the ``span`` after
    it, whichever is nearer to the sample (one side of an offset step holds one level);
    the first sample's before is its after, the last's after its before.

    Parameters
    ----------
    y : numpy.ndarray
        The samples (any unit), at least 1.
    span : int
        Samples on each side [-], >= 1.

    Returns
    -------
    numpy.ndarray
        The nearer side's mean (unit of ``y``).
    """
    n = y.size
    total = np.empty(n + 1)
    total[0] = 0.0
    running = 0.0
    for i in range(n):  # numpy.cumsum: the first sum is the first sample itself
        running = y[i] if i == 0 else running + y[i]
        total[i + 1] = running
    head = min(span, n)
    tail = max(n - span - 1, 0)
    before = np.empty(n)
    after = np.empty(n)
    for i in range(n):
        if i < head:
            before[i] = total[i] / max(i, 1)
        else:
            before[i] = (total[i] - total[i - head]) / span
        if i < tail:
            after[i] = (total[span + 1 + i] - total[1 + i]) / span
        else:
            after[i] = (total[n] - total[i + 1]) / max(n - 1 - i, 1)
    first, last = after[0], before[n - 1]  # no samples on that side
    before[0], after[n - 1] = first, last
    nearer = np.empty(n)
    for i in range(n):
        nearer[i] = before[i] if abs(y[i] - before[i]) <= abs(y[i] - after[i]) else after[i]
    return nearer


@njit(cache=True, error_model="numpy")
def nearest_residual(y, level, block, medians, head, tail, span):
    """Each sample less the candidate level nearest its :func:`side_means`: the
    interpolated ``level``, its block's median, the block before's and the block
    after's (``head`` and ``tail`` beyond the first and last blocks), the first nearest
    in that order.

    Parameters
    ----------
    y, level : numpy.ndarray
        The samples and the interpolated block levels (any unit).
    block : numpy.ndarray
        Each sample's block index [-].
    medians : numpy.ndarray
        The block medians (unit of ``y``).
    head, tail : float
        The levels before the first block and after the last (unit of ``y``).
    span : int
        Samples on each side for the side means [-].

    Returns
    -------
    numpy.ndarray
        The residual (unit of ``y``).
    """
    local = side_means(y, span)
    last = medians.size - 1
    residual = np.empty(y.size)
    for i in range(y.size):
        k = block[i]
        chosen = level[i]
        distance = abs(local[i] - chosen)
        own = medians[k]
        before = head if k == 0 else medians[k - 1]
        after = tail if k == last else medians[k + 1]
        for candidate in (own, before, after):
            gap = abs(local[i] - candidate)
            if gap < distance:
                chosen = candidate
            distance = min(gap, distance)
        residual[i] = y[i] - chosen
    return residual
