"""Least-squares coefficients and their covariance, under white noise or under stationary
coloured noise of a given autocovariance (the structure modes' crosstalk fits,
:mod:`contactlab.inverse.crosstalk` and :mod:`contactlab.inverse.crosstalk_driven`).
"""

import numpy as np
from scipy import fft

__all__ = ["coloured_covariance", "linear_least_squares", "toeplitz_quadratic"]


def linear_least_squares(design, y):
    """Least-squares coefficients of ``design @ c = y`` and their covariance under white
    noise (the residual's variance over the degrees of freedom).

    Parameters
    ----------
    design : numpy.ndarray
        ``(samples, columns)`` design matrix.
    y : numpy.ndarray
        ``(samples,)`` values fitted (any unit; the coefficients carry it over the
        columns').

    Returns
    -------
    tuple of numpy.ndarray
        ``(coefficients, covariance)``: ``(columns,)`` and ``(columns, columns)``.
    """
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coefficients
    dof = max(design.shape[0] - design.shape[1], 1)
    return coefficients, np.linalg.pinv(design.T @ design) * float(residual @ residual) / dof


def coloured_covariance(design, autocovariance):
    """Covariance of least-squares coefficients under stationary noise of the given
    autocovariance: ``(X'X)^-1 X' R X (X'X)^-1`` (``R`` Toeplitz).

    Parameters
    ----------
    design : numpy.ndarray
        ``(samples, columns)`` design matrix ``X``.
    autocovariance : numpy.ndarray
        The noise's autocovariance at lags ``0, 1, ...`` samples, at least ``samples``
        of them (unit of the data squared).

    Returns
    -------
    numpy.ndarray
        ``(columns, columns)``, unit of the coefficients squared.
    """
    inverse = np.linalg.pinv(design.T @ design)
    return inverse @ toeplitz_quadratic(autocovariance, design) @ inverse


def toeplitz_quadratic(autocovariance, x):
    """``x' R x`` for the symmetric Toeplitz ``R`` of ``autocovariance``.

    ``R`` is embedded in a circulant of a fast FFT length; its product with the
    zero-padded columns, taken against them, is Parseval's sum over their spectra
    (forward FFTs only). ``scipy.linalg.matmul_toeplitz`` takes its FFT at ``2 n - 1``,
    for the campaign's stretches of 5-20 thousand samples often a slow length, and
    returns ``R x``, whose product with ``x'`` needs inverse FFTs too.

    Parameters
    ----------
    autocovariance : numpy.ndarray
        Lags ``0, 1, ...``, at least ``len(x)`` of them (any unit).
    x : numpy.ndarray
        ``(samples, columns)``.

    Returns
    -------
    numpy.ndarray
        ``(columns, columns)``.
    """
    n = x.shape[0]
    size = fft.next_fast_len(2 * n - 1, real=True)
    lags = np.asarray(autocovariance, dtype=float)[:n]
    column = np.concatenate([lags, np.zeros(size - 2 * n + 1), lags[:0:-1]])
    spectrum = fft.rfft(column).real  # a symmetric sequence: a real spectrum
    columns = fft.rfft(x, size, axis=0)
    weights = np.full(spectrum.size, 2.0)  # the half spectrum's bins stand for two
    weights[0] = 1.0
    if size % 2 == 0:
        weights[-1] = 1.0  # Nyquist
    product = (columns.conj().T * (weights * spectrum)) @ columns
    return product.real / size
