"""Samples held at an instrument's rail: a clipped peak.

An ADC that is overdriven writes its rail value (most instruments; a few write +-inf,
which the readers keep as *overrange*). A clipped peak is a run of samples exactly at
the record's largest (or smallest) value. A smooth peak recorded with few bits also
holds its top value for a few samples, so a run counts as clipped only if

- it is at least :data:`CLIP_RUN` samples long, and
- either the record is dithered by noise (local noise at least :data:`DITHER_STEPS`
  quantisation steps: noise then almost never repeats a value three times), or the
  signal steps onto and off the run by at least :data:`ENTRY_STEPS` quantisation steps
  (a smooth peak of a parabola's shape enters a plateau of ``L`` samples by about
  ``4 q / L``, less than two steps ``q``).
"""

import numpy as np

__all__ = ["CLIP_RUN", "clipped_samples"]

CLIP_RUN = 3
"""Fewest consecutive samples at the rail that make a clip [-]."""

DITHER_STEPS = 2.0
"""Local noise, in quantisation steps, above which repeated values are not chance [-]."""

ENTRY_STEPS = 3.0
"""Smallest step onto and off a clipped run, in quantisation steps [-]."""


def _quantum(values):
    """The record's quantisation step: its smallest nonzero difference of values."""
    levels = np.unique(values)
    steps = np.diff(levels)
    return float(steps.min()) if steps.size else 0.0


def _runs_at(values, level):
    """``(first, last)`` of each run of samples exactly equal to ``level``."""
    at = np.flatnonzero(values == level)
    if at.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(at) > 1)
    firsts = np.concatenate([[0], breaks + 1])
    lasts = np.concatenate([breaks, [at.size - 1]])
    return list(zip(at[firsts].tolist(), at[lasts].tolist(), strict=True))


def clipped_samples(values, noise):
    """Indices of the samples on a clipped run (module docstring).

    Parameters
    ----------
    values : numpy.ndarray
        The record's finite samples (any unit).
    noise : float
        Its typical noise (same unit).

    Returns
    -------
    numpy.ndarray of int
        Sorted indices (empty when nothing is clipped).
    """
    values = np.asarray(values, dtype=float)
    quantum = _quantum(values)
    dithered = quantum == 0.0 or noise >= DITHER_STEPS * quantum
    found = []
    for level in (values.max(), values.min()):
        for first, last in _runs_at(values, level):
            if last - first + 1 < CLIP_RUN:
                continue
            before = abs(level - values[first - 1]) if first > 0 else np.inf
            after = abs(level - values[last + 1]) if last + 1 < values.size else np.inf
            if dithered or min(before, after) >= ENTRY_STEPS * quantum:
                found.append(np.arange(first, last + 1))
    return np.unique(np.concatenate(found)) if found else np.zeros(0, dtype=int)
