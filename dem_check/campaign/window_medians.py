"""Medians over the sliding windows of the period means' levels, NaN left out: the
level changes and drift slopes of :func:`dem_check.campaign.steps.find_steps` (issue 22).

:func:`nan_medians` is ``numpy.nanmedian(rows, axis=1)`` by one sort of the rows: numpy
takes rows with NaN through masked arrays, a Python loop over the rows (0.3 s of the
1.5 M-sample realistic record's 10 s). The middle values are the same order statistics
and an even count's mean is numpy's ``(low + high) / 2``, so the medians are numpy's to
the last bit (``tests/dem_check/campaign/test_step_search.py``).
"""

import numpy as np

__all__ = ["nan_medians", "running_nanmedian", "window_medians"]


def nan_medians(rows):
    """Median of each row's values that are not NaN; NaN for a row with none.

    Parameters
    ----------
    rows : numpy.ndarray
        ``(rows, values)``, any unit.

    Returns
    -------
    numpy.ndarray
        One median per row, unit of ``rows``.
    """
    ordered = np.sort(rows, axis=1)  # NaN sorts last
    count = np.sum(~np.isnan(rows), axis=1)
    row = np.arange(rows.shape[0])
    low = ordered[row, np.maximum(count - 1, 0) // 2]
    high = ordered[row, np.minimum(count // 2, rows.shape[1] - 1)]
    middle = np.where(count % 2 == 1, low, (low + high) / 2.0)
    return np.where(count > 0, middle, np.nan)


def window_medians(levels, size):
    """Median of the ``size`` levels before each boundary and of those after it
    (boundary ``j`` lies between levels ``j - 1`` and ``j``, ``j = 1 .. n - 1``),
    fewer at the ends, and how many each holds."""
    pad = np.full(size, np.nan)
    windows = np.lib.stride_tricks.sliding_window_view(np.r_[pad, levels, pad], size)
    j = np.arange(1, levels.size)
    before, after = windows[j], windows[j + size]
    counts = (np.sum(~np.isnan(before), axis=1), np.sum(~np.isnan(after), axis=1))
    return nan_medians(before), nan_medians(after), counts


def running_nanmedian(values, half):
    """Median of the finite values within ``half`` places either side of each (0 where
    there is none): rates read on windows cut short at the record's edges, whose short
    span inflates a step's rate, are left out as nan."""
    pad = np.full(half, np.nan)
    windows = np.lib.stride_tricks.sliding_window_view(np.r_[pad, values, pad], 2 * half + 1)
    finite = np.isfinite(windows).any(axis=1)
    out = np.zeros(values.size)
    out[finite] = nan_medians(windows[finite])
    return out
