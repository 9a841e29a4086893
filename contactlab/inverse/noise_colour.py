"""Coloured noise: an autoregressive model of a record's quiet samples and its whitening.

Laboratory noise is not white: 1/f (flicker) noise of the charge amplifier, wander and
hum leave it correlated over many samples. A least-squares fit that treats it as white
weighs its slow part like its fast part, and a regularisation parameter chosen by
generalised cross-validation, which assumes white noise, then fits the slow part as
signal. Generalised least squares removes the correlation first: with the noise an
autoregressive process ``e[n] = a_1 e[n-1] + ... + a_p e[n-p] + w[n]`` (``w`` white),
the filter ``A(z) = 1 - a_1 z**-1 - ... - a_p z**-p`` applied to the data and to the
columns of the model leaves white noise ``w`` (the innovations), on which least squares
and GCV are what they assume.

The model is fitted by Burg's method (``statsmodels.regression.linear_model.burg``),
stable for the near-unit-root processes that 1/f noise gives, with the order chosen by
the Bayesian information criterion ``n ln(sigma_p**2) + p ln n`` (Schwarz 1978).

References
----------
Burg J.P. (1975) Maximum entropy spectral analysis. PhD thesis, Stanford University.
Schwarz G. (1978) Estimating the dimension of a model. Ann. Stat. 6, 461-464.
DOI 10.1214/aos/1176344136
Kay S.M. (1988) Modern Spectral Estimation. Prentice Hall, ch. 7 (AR order selection).
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from contactlab.errors import ParameterError
from contactlab.inverse.ringdown import free_ringing_residual
from contactlab.validation import check_count

__all__ = [
    "MAX_ORDER",
    "MIN_SAMPLES_PER_ORDER",
    "NOISE_MODELS",
    "WHITE_ALPHA",
    "ARNoise",
    "block_noise_model",
    "describe_model",
    "fit_ar_noise",
    "ringing_residual",
    "whiten_problem",
]

MAX_ORDER = 12
"""Highest autoregressive order tried [-]. On the realistic records of
``docs/campaign.md`` with 1/f noise BIC picked orders 1-4 on baseline windows of 80-200
blocks and 3-7 on post-contact windows of 400; 12 leaves room for hum and an
acquisition filter."""

WHITE_ALPHA = 0.01
"""Level of the test against white noise that an autoregressive model must pass [-]
(likelihood ratio, chi-squared with ``p`` degrees of freedom, the level shared among the
orders tried). BIC alone takes an order 1 model for white noise about once in 25 windows
of 80 blocks (its penalty ``ln n`` is a chi-squared(1) quantile of 0.96); measured on the
campaign's records without 1/f noise, a spurious AR(1) of coefficient -0.18 moved one
reconstructed peak from +1.5 % to +5.7 %. The test at 1 % for the order BIC picked still
took 3.1 % of white windows of 80 samples (the best of 8 orders); shared among them,
0.3-0.4 % (1000 windows each of 80, 200 and 1000 samples)."""

MIN_SAMPLES_PER_ORDER = 10
"""Fewest samples per autoregressive coefficient [-]: the order tried is at most the
number of samples over this (each coefficient's standard error about 1/sqrt(n))."""


@dataclass(frozen=True)
class ARNoise:
    """An autoregressive noise model ``e[n] = sum_k a_k e[n-k] + w[n]`` (signal unit).

    ``coefficients`` are ``a_1 ... a_p`` (empty: white noise), ``innovation`` the standard
    deviation of ``w`` and ``samples`` the number of samples it was fitted on.
    """

    coefficients: np.ndarray
    innovation: float
    samples: int

    @property
    def order(self):
        """The model's order ``p`` [-]."""
        return int(self.coefficients.size)

    def whiten(self, values):
        """``A(z)`` applied along the first axis: ``w[n] = x[n] - sum_k a_k x[n-k]``.

        The first ``p`` rows, which need samples before the array, are dropped: the
        result has ``len(values) - p`` rows.
        """
        values = np.asarray(values, dtype=float)
        p = self.order
        out = values[p:].copy()
        for k, a in enumerate(self.coefficients, start=1):
            out -= a * values[p - k : values.shape[0] - k]
        return out


def fit_ar_noise(noise, max_order=MAX_ORDER):
    """Fit an autoregressive model to noise samples, the order chosen by BIC.

    Parameters
    ----------
    noise : array_like
        Consecutive noise samples (signal unit), at least ``2 * MIN_SAMPLES_PER_ORDER``;
        their mean is removed.
    max_order : int, default :data:`MAX_ORDER`
        Highest order tried (at most ``len(noise) // MIN_SAMPLES_PER_ORDER``).

    Returns
    -------
    ARNoise
        Order 0 (white) when no order lowers the criterion.

    Raises
    ------
    ParameterError
        Too few samples, non-finite samples or constant samples.
    """
    from statsmodels.regression.linear_model import burg  # heavy import: only here

    x = np.asarray(noise, dtype=float).ravel()
    max_order = check_count("max_order", max_order, 0)
    if x.size < 2 * MIN_SAMPLES_PER_ORDER or not np.all(np.isfinite(x)):
        raise ParameterError(
            f"noise must hold at least {2 * MIN_SAMPLES_PER_ORDER} finite samples; got "
            f"{x.size} ({int(np.sum(~np.isfinite(x)))} not finite)"
        )
    x = x - x.mean()
    variance = float(x @ x) / x.size
    if not variance > 0.0:
        raise ParameterError("noise is constant: no noise model can be fitted")
    n = x.size
    best = (n * math.log(variance), np.zeros(0), variance)
    tried = min(max_order, n // MIN_SAMPLES_PER_ORDER)
    for order in range(1, tried + 1):
        coefficients, sigma2 = burg(x, order=order, demean=False)
        score = n * math.log(float(sigma2)) + order * math.log(n)
        if score < best[0]:
            best = (score, np.asarray(coefficients, dtype=float), float(sigma2))
    order = best[1].size
    # likelihood ratio against white noise, chi2(order) under it (Wilks); the level
    # shared among the orders tried (Bonferroni), since BIC picked the best of them
    ratio = n * math.log(variance / best[2])
    if order and ratio < chi2.isf(WHITE_ALPHA / tried, order):
        return ARNoise(coefficients=np.zeros(0), innovation=math.sqrt(variance), samples=n)
    return ARNoise(coefficients=best[1], innovation=math.sqrt(best[2]), samples=n)


NOISE_MODELS = ("ar", "white")
"""Noise models of the Tikhonov reconstruction: ``"ar"`` (fitted on the quiet samples,
generalised least squares) or ``"white"`` (ordinary least squares)."""


def block_noise_model(quiet, q, kind="ar"):
    """The noise model of the block means of ``q`` samples, fitted on quiet samples.

    Parameters
    ----------
    quiet : numpy.ndarray
        Consecutive samples holding noise only (signal unit): the record less its
        baseline over the baseline window.
    q : int
        Samples per block.
    kind : {"ar", "white"}
        ``"white"`` returns ``None``.

    Returns
    -------
    ARNoise or None
        ``None`` for ``"white"`` or when the quiet samples make fewer than
        ``2 * MIN_SAMPLES_PER_ORDER`` blocks (white noise is then assumed).
    """
    blocks = quiet.size // q
    if kind == "white" or blocks < 2 * MIN_SAMPLES_PER_ORDER:
        return None
    return fit_ar_noise(quiet[-blocks * q :].reshape(blocks, q).mean(axis=1))


def whiten_problem(model, h, data, before, q, block_noise):
    """The least-squares problem ``h f = data`` with its noise whitened.

    Parameters
    ----------
    model : ARNoise or None
        The block noise (``None``: white, returned unchanged).
    h : numpy.ndarray
        Model matrix, one row per data block.
    data : numpy.ndarray
        Block means.
    before : numpy.ndarray
        Samples preceding the first block, where the model is zero (the force is zero
        before the contact window); up to ``p`` blocks of them start the filter, the
        rows without them are dropped.
    q : int
        Samples per block.
    block_noise : float
        Standard deviation of a block mean's noise when it is white.

    Returns
    -------
    h, data : numpy.ndarray
        The whitened matrix and data.
    noise : float
        Standard deviation of the whitened noise (the innovation's).
    """
    if model is None or model.order == 0:
        return h, data, block_noise if model is None else model.innovation
    extra = min(model.order, before.size // q)
    lead = before[before.size - extra * q :].reshape(extra, q).mean(axis=1)
    h = np.vstack([np.zeros((extra, h.shape[1])), h])
    return model.whiten(h), model.whiten(np.concatenate([lead, data])), model.innovation


def describe_model(model):
    """The noise model as parameters of a result (JSON-ready)."""
    if model is None or model.order == 0:
        return {"noise_model": "white"}
    return {
        "noise_model": f"AR({model.order})",
        "ar_coefficients [-]": [float(a) for a in model.coefficients],
        "innovation [N]": model.innovation,
    }


def ringing_residual(t, y, window, sensor):
    """The record less the sensor's free ringing and a line over ``window`` [s].

    After the contact the sensor rings freely; what its fitted ringing and a line (the
    drift, as the baseline window's line before a pulse) leave is the noise: the quiet
    samples of a record that starts at its pulse.

    Parameters
    ----------
    t, y : numpy.ndarray
        Time [s] and signal [N].
    window : (float, float)
        ``[start, end]`` [s], after the contact.
    sensor : Sensor
        Its resonance and damping ratio give the ringing.

    Returns
    -------
    numpy.ndarray
        The residual on the window's samples [N].
    """
    inside = (t >= window[0]) & (t <= window[1])
    return free_ringing_residual(t[inside], y[inside], sensor, degree=1)
