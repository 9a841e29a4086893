"""Whether a candidate structure mode is driven by the record's impacts: one coupling
shared by every window of ringing.

The joint pencil (:func:`contactlab.inverse.crosstalk.joint_structure_modes`) tests each
candidate window by window, with an amplitude and phase of its own in each window, and a
record keeps it when it is significant after half of the impacts. A plate mode that the
weaker impacts ring under the noise fails that count: on 2 MHz records with 1/f noise as
large as the white noise and 2 % crosstalk, the plate's 4100 Hz mode was a candidate in
two of four records (4053 and 4113 Hz) but significant after two and one of eight
impacts; left out, the impacts' impulses read up to 5.1 % high, since the impulse's
integral spans half of that mode's period (``docs/campaign.md``, "Crosstalk").

A structure answers every hit through the same linear path: the ringing a mode holds in
the window after impact ``k`` is the sum of its responses to the impacts up to ``k``,
each started at that impact's onset with an amplitude in proportion to its peak, with one
complex coupling (amplitude and phase) for the record. Fitted so, with a line of each
window's own, the candidate has two coefficients for all the windows instead of two per
window, and noise, which is not locked to the onsets nor in proportion to the peaks,
does not fit them. Measured (``docs/campaign.md``, "Crosstalk", step 1), with the
standard errors under the record's white and 1/f noise: the plate's modes 7.8-15.6
standard errors; the pencil's candidates on records without crosstalk at most 3.4 (with
the white residual's errors alone, 1/f noise near a low candidate reached 5.9).
"""

import math

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.crosstalk import SIGNIFICANCE, structure_band
from contactlab.inverse.least_squares_covariance import linear_least_squares
from contactlab.validation import check_samples

__all__ = ["driven_significance"]


def _driven_columns(times, onsets, drives, frequency, zeta):
    """The mode's free ringing from each impact before ``times[0]`` (started at its
    onset, weighted by its drive), summed: two columns (cosine and sine)."""
    b = 2.0 * math.pi * frequency
    decay_rate = -zeta * b / math.sqrt(max(1.0 - zeta**2, 1e-300))
    columns = np.zeros((times.size, 2))
    for onset, drive in zip(onsets, drives, strict=True):
        if onset < times[0]:
            s = times - onset
            decay = drive * np.exp(decay_rate * s)
            columns += np.stack([decay * np.cos(b * s), decay * np.sin(b * s)], axis=1)
    return columns


def driven_significance(windows, onsets, drives, candidates, sensor, autocovariance=None):
    """Standard errors of each candidate mode's shared coupling to the impacts (module
    docstring), and whether it reaches :data:`~contactlab.inverse.crosstalk.SIGNIFICANCE`.

    Each window (less a line and the sensor's free ringing, in block means, as the joint
    pencil reads it) is fitted with a line of its own and, for every candidate together,
    the two columns of its ringing driven by the impacts before the window (onset
    ``onsets[j]``, amplitude in proportion to ``drives[j]``), shared by all the windows.

    Parameters
    ----------
    windows : sequence of (array_like, array_like)
        ``(t [s], y)`` of each window of ringing after a contact, as for
        :func:`~contactlab.inverse.crosstalk.joint_structure_modes`.
    onsets : array_like
        Every impact's onset [s] (those before a window drive it).
    drives : array_like
        Every impact's drive, in proportion to its force (its peak signal [N]).
    candidates : sequence of (float, float)
        ``(frequency [Hz], damping ratio [-])`` of each candidate.
    sensor : Sensor
    autocovariance : array_like, optional
        The record's noise autocovariance at lags of ``0, 1, ...`` samples, up to the
        span of the windows and a block (unit of the record squared; e.g.
        ``ColouredNoise.autocovariance``): the couplings' standard errors are then the
        larger of the white residual's and those of least squares under this noise,
        whose block means are correlated within and across the windows (1/f noise near
        a low-frequency candidate: :func:`_coloured_sandwich`).

    Returns
    -------
    coupling : numpy.ndarray
        Each candidate's amplitude of ringing per unit of drive at the driving impact's
        onset (unit of the record per unit of the drives: [-] for peaks in N).
    z : numpy.ndarray
        Each coupling over its standard error [-].
    significant : numpy.ndarray of bool
        ``z > SIGNIFICANCE``.
    """
    onsets, drives = check_samples("onsets", onsets), check_samples("drives", drives)
    if onsets.shape != drives.shape:
        raise ParameterError(f"onsets and drives must match; got {onsets.size} and {drives.size}")
    none = np.zeros(len(candidates)), np.zeros(len(candidates)), np.zeros(len(candidates), bool)
    if not candidates or not windows:
        return none
    count, blocks, targets, starts = len(windows), [], [], []
    first = float(check_samples("t", windows[0][0])[0])
    for k, (t, y) in enumerate(windows):
        t = check_samples("t", t)
        dt = float(t[1] - t[0])
        tau, means, step = structure_band(t, check_samples("y", y), sensor, degree=1, blocks=True)
        lines = np.zeros((tau.size, 2 * count))
        lines[:, 2 * k], lines[:, 2 * k + 1] = 1.0, tau - tau.mean()
        driven = [_driven_columns(t[0] + tau, onsets, drives, f, z) for f, z in candidates]
        blocks.append(np.concatenate([lines, *driven], axis=1))
        targets.append(means)
        size = round(step / dt)  # samples per block
        starts.append(round((float(t[0]) - first) / dt) + size * np.arange(tau.size))
    design, values = np.concatenate(blocks), np.concatenate(targets)
    if design.shape[0] <= design.shape[1]:
        return none
    coefficients, covariance = linear_least_squares(design, values)
    if autocovariance is not None:
        coloured = _coloured_sandwich(design, np.concatenate(starts), size, autocovariance)
    coupling, z = np.zeros(len(candidates)), np.zeros(len(candidates))
    for k in range(len(candidates)):
        at = slice(2 * count + 2 * k, 2 * count + 2 * k + 2)
        pair = coefficients[at]
        coupling[k] = float(np.hypot(*pair))
        # the coupling's variance along itself (as the pencil's test, crosstalk._pair)
        variance = float(pair @ covariance[at, at] @ pair)
        if autocovariance is not None:
            variance = max(variance, float(pair @ coloured[at, at] @ pair))
        variance /= max(coupling[k], 1e-300) ** 2
        z[k] = coupling[k] / math.sqrt(variance) if variance > 0.0 else 0.0
    return coupling, z, z > SIGNIFICANCE


CHUNK_ENTRIES = 2**22
"""Entries of the block covariance held at once [-] (32 MB): the covariance of every
window's block means with every other's grows as the square of a record's impacts (115
MB for the 40 windows of the 1.5 M-sample speed record; 3 GB for 200), so the sandwich
is summed over chunks of its rows."""


def _lag_covariance(span, size, autocovariance):
    """Covariance of the means of two blocks of ``size`` samples that start ``0, 1,
    ..., span + 1`` samples apart, under stationary noise of the given autocovariance
    (lags ``0, 1, ...`` samples): ``(1 / size**2) sum_d (size - |d|) r(|lag + d|)``."""
    r = np.asarray(autocovariance, dtype=float)
    if r.size < span + size + 1:
        raise ParameterError(
            f"autocovariance must hold {span + size + 1} lags (the windows' span and a "
            f"block); got {r.size}"
        )
    symmetric = np.concatenate([r[size - 1 : 0 : -1], r[: span + size + 1]])
    triangle = (size - np.abs(np.arange(1 - size, size))) / size**2
    return np.convolve(symmetric, triangle, mode="valid")


def _block_covariance(starts, others, lags):
    """Covariance of the block means starting at the sample indices ``starts`` with those
    starting at ``others`` (``lags``: :func:`_lag_covariance`)."""
    return lags[np.abs(starts[:, None] - others[None, :])]


def _coloured_sandwich(design, starts, size, autocovariance):
    """Covariance of least-squares coefficients of block means (rows of ``design``,
    starting at the sample indices ``starts``, ``size`` samples each) under stationary
    noise of the given autocovariance: ``(X'X)^-1 X' R X (X'X)^-1``, ``X' R X`` summed
    over chunks of :data:`CHUNK_ENTRIES` entries of ``R``."""
    lags = _lag_covariance(int(starts.max() - starts.min()), size, autocovariance)
    middle = np.zeros((design.shape[1], design.shape[1]))
    step = max(1, CHUNK_ENTRIES // starts.size)
    for first in range(0, starts.size, step):
        rows = slice(first, first + step)
        middle += design[rows].T @ (_block_covariance(starts[rows], starts, lags) @ design)
    inverse = np.linalg.pinv(design.T @ design)
    return inverse @ middle @ inverse
