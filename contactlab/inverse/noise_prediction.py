"""The noise under a pulse, predicted from both sides of it (Kriging).

A pulse's impulse and peak are read on the record less its baseline. Where the noise is
white, the baseline under the pulse is all there is to estimate; with 1/f (flicker)
noise the noise under the pulse is itself correlated with the samples next to it, and
its conditional mean given them can be subtracted too. With the noise stationary of
autocovariance ``C`` and the baseline a linear model ``X beta`` on the samples outside
the pulse (``o``), the best linear unbiased reading of the pulse (Kay 1993, ch. 6;
Cressie 1993, universal Kriging) is

- ``beta`` by generalised least squares on ``o``: ``(X_o' S_oo^-1 X_o)^-1 X_o' S_oo^-1 y_o``;
- the noise inside (``f``) predicted from the residual ``r_o = y_o - X_o beta``:
  ``e_f = S_fo S_oo^-1 r_o``, the conditional mean of a Gaussian noise given ``r_o``;

and the pulse is ``y_f - X_f beta - e_f``. Its error variance for a weighted sum ``w' s``
is ``w' (S_ff - S_fo S_oo^-1 S_of) w + u' (X_o' S_oo^-1 X_o)^-1 u`` with ``u = X_f' w -
X_o' S_oo^-1 S_of w`` (:func:`dem_check.campaign.bounds.free_variance`, the bound it
reaches). Any covariance gives an unbiased reading (``beta`` is unbiased and ``e_f`` is
linear in a residual of mean zero); a wrong one costs variance only.

The samples outside are averaged in blocks of :data:`BLOCK_PER_PERIOD`-th of a sensor
period: the block means keep what the slow (1/f) part of the noise says about the pulse
and make the Cholesky factor of ``S_oo`` a few hundred rows at any sampling rate.

The covariance (:class:`ColouredNoise`) is white noise plus 1/f noise of power ``1/f``
from the record's length to the Nyquist frequency, as laboratory charge amplifiers give
and :func:`dem_check.campaign.realistic_record` draws; its two levels are estimated on a
record's quiet samples (:func:`estimate_coloured_noise`) from the mean square of second
differences at lags of one sample to :data:`MAX_LAG_PERIODS` sensor periods, which
drift and hum (lines over such lags) hardly reach.

References
----------
Kay S.M. (1993) Fundamentals of Statistical Signal Processing: Estimation Theory.
Prentice Hall, ch. 6 (BLUE, Gauss-Markov).
Cressie N. (1993) Statistics for Spatial Data. Wiley, sec. 3.4 (universal Kriging).
"""

from dataclasses import dataclass

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.optimize import nnls

from contactlab.errors import ParameterError

__all__ = [
    "BLOCK_PER_PERIOD",
    "MAX_LAG_PERIODS",
    "ColouredNoise",
    "estimate_coloured_noise",
    "pink_autocovariance",
    "predict_gap",
]

BLOCK_PER_PERIOD = 10.0
"""Blocks per sensor period of the samples outside the pulse [-] (at least one sample a
block)."""

MAX_LAG_PERIODS = 2.0
"""Longest lag of the second differences the noise levels are estimated from [sensor
periods]: hum's harmonics (250 Hz) and the drift bend a line by under 0.02 noise sigmas
over 50 us, and a lag of two periods holds the 1/f noise's slope."""

LAGS = 12
"""Lags of the second differences (geometric from one sample) [-]."""


def pink_autocovariance(count, dt, record_length):
    """Autocovariance of unit-variance 1/f noise at lags ``0 .. count-1``.

    The power is ``1/f`` from ``1 / record_length`` to the Nyquist frequency (the
    periodogram's bins of a record of that length), so the autocovariance is the
    inverse FFT of ``1/k``, ``k = 1 .. N/2``, normalised to 1 at lag 0.

    Parameters
    ----------
    count : int
        Lags [samples].
    dt : float
        Sample interval [s].
    record_length : float
        Length of the record [s]: its lowest frequency.

    Returns
    -------
    numpy.ndarray
        ``count`` values [-].
    """
    total = round(record_length / dt)
    if total < count:
        raise ParameterError(f"record_length must span the {count} lags; got {record_length} s")
    power = np.zeros(total // 2 + 1)
    power[1:] = 1.0 / np.arange(1, power.size)
    shape = np.fft.irfft(power, total)[:count]
    return shape / shape[0]


@dataclass(frozen=True)
class ColouredNoise:
    """White plus 1/f noise: its levels and autocovariance."""

    white: float
    """Standard deviation of the white noise [N]."""
    pink: float
    """Standard deviation of the 1/f noise [N]."""
    dt: float
    """Sample interval [s]."""
    shape: np.ndarray
    """Unit-variance 1/f autocovariance at lags ``0, 1, ...`` samples
    (:func:`pink_autocovariance`) [-]."""

    def autocovariance(self, count):
        """The noise's autocovariance at lags ``0 .. count-1`` [N**2] (1/f noise's beyond
        :attr:`shape` held at its last value)."""
        lags = np.minimum(np.arange(count), self.shape.size - 1)
        out = self.pink**2 * self.shape[lags]
        out[0] += self.white**2
        return out


def estimate_coloured_noise(y, quiet, dt, record_length, period):
    """White and 1/f noise levels of a record, from its quiet samples.

    The mean square of the second difference ``y[n+m] - 2 y[n] + y[n-m]`` over the
    quiet samples is ``6 white**2 + pink**2 (6 - 8 rho(m) + 2 rho(2 m))`` with ``rho``
    the unit 1/f autocovariance; the two squared levels are fitted (non-negative least
    squares, relative) at :data:`LAGS` lags from one sample to :data:`MAX_LAG_PERIODS`
    sensor periods. A line (drift) cancels in a second difference.

    Parameters
    ----------
    y : numpy.ndarray
        The record [N] (offset steps removed).
    quiet : numpy.ndarray of bool
        Its samples without an impact or its ringing.
    dt : float
        Sample interval [s].
    record_length : float
        Length of the record [s] (the 1/f noise's lowest frequency).
    period : float
        Sensor period [s] (sets the longest lag).

    Returns
    -------
    ColouredNoise
        With :attr:`ColouredNoise.shape` over the record (up to ``record_length``).

    Raises
    ------
    ParameterError
        Fewer than ``2 * LAGS`` usable second differences at the longest lag.
    """
    longest = max(2, round(MAX_LAG_PERIODS * period / dt))
    lags = np.unique(np.round(np.geomspace(1, longest, LAGS)).astype(int))
    count = min(round(record_length / dt), y.size)
    shape = pink_autocovariance(count, dt, record_length)
    rows, squares = [], []
    for m in lags:
        ok = quiet[: -2 * m] & quiet[m:-m] & quiet[2 * m :]
        if np.count_nonzero(ok) < 2 * LAGS:
            raise ParameterError(
                f"quiet must hold {2 * LAGS} second differences at a lag of {m} samples; "
                f"got {np.count_nonzero(ok)}"
            )
        second = (y[2 * m :] - 2.0 * y[m:-m] + y[: -2 * m])[ok]
        squares.append(float(np.mean(second**2)))
        rows.append([6.0, 6.0 - 8.0 * shape[m] + 2.0 * shape[2 * m]])
    squares = np.array(squares)
    levels, _ = nnls(np.array(rows) / squares[:, None], np.ones(squares.size))
    white, pink = np.sqrt(levels)
    return ColouredNoise(white=float(white), pink=float(pink), dt=dt, shape=shape)


def _blocks(indices, q, backward):
    """First indices of blocks of ``q`` samples of each contiguous run of ``indices``
    (from a run's end if ``backward``: the block next to the pulse is whole)."""
    starts = [np.zeros(0, dtype=int)]
    for run in np.split(indices, np.flatnonzero(np.diff(indices) > 1) + 1):
        n = run.size // q
        if n:
            first = run[-n * q] if backward else run[0]
            starts.append(first + q * np.arange(n))
    return np.concatenate(starts)


def _box(c, q):
    """``(1/q) sum_{b<q} c[k - b]`` for every ``k`` of the symmetric array ``c``."""
    s = np.concatenate([[0.0], np.cumsum(c)])
    k = np.arange(c.size)
    return (s[k + 1] - s[np.maximum(k + 1 - q, 0)]) / q


def predict_gap(autocovariance, y, design, before, after, inside, q):
    """Baseline parameters by GLS and the noise inside predicted from both sides.

    Parameters
    ----------
    autocovariance : numpy.ndarray
        Noise autocovariance at lags ``0 .. len(y)-1`` [N**2] (those up to the span of
        the samples used are read).
    y : numpy.ndarray
        The segment [N] (``(n,)``, or ``(n, k)``: ``k`` records read at once).
    design : numpy.ndarray
        ``(len(y), m)`` baseline model (zero inside where a column is signal).
    before, after : numpy.ndarray of int
        Sample indices outside the pulse, before and after it, increasing: contiguous,
        or several contiguous runs where samples between them are left out (another
        impact's); each run is averaged in blocks of its own.
    inside : numpy.ndarray of int
        Sample indices where the noise is predicted.
    q : int
        Samples per block mean of the outside samples (the first samples of each run of
        ``before`` and the last of each run of ``after`` that fill no block are left
        out).

    Returns
    -------
    beta : numpy.ndarray
        ``m`` baseline parameters.
    noise : numpy.ndarray
        Predicted noise at ``inside`` [N].
    """
    starts = np.concatenate([_blocks(before, q, True), _blocks(after, q, False)])
    # lags within the samples used only: offsets from the first of them
    first = min(starts.min(), inside.min())
    n = max(starts.max() + q, inside.max() + 1) - first
    starts, inside = starts - first, inside - first
    y, design = y[first : first + n], design[first : first + n]
    c = np.concatenate([autocovariance[n - 1 : 0 : -1], autocovariance[:n]])  # lags -(n-1) .. n-1
    cross = _box(c, q)  # sample k, block starting at 0: lag k (offset n-1)
    within = _box(cross[::-1], q)[::-1]  # block starting at k against block at 0
    members = starts[:, None] + np.arange(q)
    block_y = y[members].mean(axis=1)
    block_x = design[members].mean(axis=1)
    lag = starts[:, None] - starts[None, :] + n - 1
    factor = cho_factor(within[lag])
    whitened = cho_solve(factor, block_x)
    beta = np.linalg.solve(block_x.T @ whitened, whitened.T @ block_y)
    alpha = cho_solve(factor, block_y - block_x @ beta)
    noise = cross[inside[:, None] - starts[None, :] + n - 1] @ alpha
    return beta, noise
