"""The running baseline's residual in numpy, as ``contactlab._block_levels`` computed it
before it was compiled (session 17, ``contactlab/kernels/levels.py``): the reference that
``tests/contactlab/test_block_levels.py`` checks the kernel against (imported by name:
``tests/conftest.py`` puts this folder on the path)."""

import numpy as np


def _side_means(y, span):
    """Per sample, the mean of the ``span`` samples before it or of the ``span`` after it,
    whichever is nearer to the sample (one side of an offset step holds one level)."""
    total = np.concatenate([[0.0], np.cumsum(y)])
    n = y.size
    # sums over [max(i - span, 0), i) and (i, min(i + 1 + span, n)) as shifted slices of
    # the cumulative sum (the gathers by index arrays took most of the time)
    before = np.empty(n)
    after = np.empty(n)
    head = min(span, n)
    before[:head] = total[:head] / np.maximum(np.arange(head), 1)
    before[head:] = (total[head:n] - total[: n - head]) / span
    tail = max(n - span - 1, 0)
    after[:tail] = (total[span + 1 : span + 1 + tail] - total[1 : 1 + tail]) / span
    after[tail:] = (total[n] - total[tail + 1 : n + 1]) / np.maximum(n - 1 - np.arange(tail, n), 1)
    before[0], after[-1] = after[0], before[-1]  # no samples on that side
    return np.where(np.abs(y - before) <= np.abs(y - after), before, after)


def numpy_residual(y, level, block, medians, head, tail, span):
    """Each sample less the candidate level nearest its side mean, in numpy."""
    before = np.r_[head, medians][block]
    after = np.r_[medians, tail][block + 1]
    local_mean = _side_means(y, span)
    chosen, distance = level, np.abs(local_mean - level)
    for candidate in (medians[block], before, after):  # the first nearest, as argmin
        gap = np.abs(local_mean - candidate)
        nearer = gap < distance
        chosen, distance = np.where(nearer, candidate, chosen), np.minimum(gap, distance)
    return y - chosen
