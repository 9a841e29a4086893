"""The baseline under a pulse at a record's first sample: fitted after it, extrapolated back.

A record that starts at an impact (no pre-trigger) has no quiet samples before the pulse.
Block medians then put the baseline there by extrapolating the outer blocks' slope, and a
drift that curves within a few blocks (thermal or charge-amplifier wander over a short
record) leaves it several noise sigmas off; the residual's choice between neighbouring
block levels (:func:`contactlab.signals.running_baseline`) is worse still next to a pulse,
whose samples pull the local mean up (issue 22: a 2 N impact read as 1 N under a drift of
about 700 N/s). So the level under the pulse is read where the record is quiet: a
line, or a quadratic where its curvature is :data:`CURVATURE_SIGMAS` standard errors,
fitted with a robust loss (scipy's ``least_squares``, ``soft_l1``: a weak bounce or a
burst in the fit window is down-weighted, not followed) on :data:`HEAD_FIT_BLOCKS`
blocks of samples after the pulse and its ringing (past other pulses left out), and
extrapolated back to the record's first sample. Its standard error, from the fit's
covariance with the residual's autocorrelation time counted, is returned so a threshold
can take it in.

The same fit gives the single-trace paths their baseline under a pulse at a record's
start (:func:`contactlab.inverse.local_baseline.head_baseline`): there the window starts
at the contact's end and the sensor's free ringing is fitted with the polynomial
(:func:`head_fit`'s ``columns``), as the local baseline fits it with its line.
"""

from typing import NamedTuple

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import median_abs_deviation

from contactlab.errors import ParameterError

__all__ = [
    "CURVATURE_SIGMAS",
    "HEAD_DEGREE",
    "HEAD_FIT_BLOCKS",
    "HEAD_MIN_SAMPLES",
    "HeadFit",
    "head_fit",
    "head_level",
]

HEAD_DEGREE = 2
"""Highest degree of the polynomial fitted after the pulse [-]: a drift that curves over
the fit window (issue 22's record: its slope fell from 720 to 460 N/s over 1.5 ms) is
followed; a cubic would scatter more when extrapolated back over the pulse."""

CURVATURE_SIGMAS = 3.0
"""The quadratic term is kept when it is this many of its standard errors [-]; else the
level is a line (whose extrapolation back over the pulse scatters much less)."""

HEAD_FIT_BLOCKS = 1.0
"""Length of the fit window after the pulse [blocks of the running baseline]: long
against the pulse it is extrapolated over, short against the drift's curvature."""

HEAD_MIN_SAMPLES = 64
"""Fewest quiet samples the fit needs [-] (16 per coefficient and more)."""


def _robust_fit(x, values, degree, columns=None):
    """Coefficients of a polynomial of ``degree`` in ``x`` (then of ``columns``, fitted
    with it) fitted with the ``soft_l1`` loss, and their covariance: the robust noise of
    the residual, times its integrated autocorrelation time (1/f noise leaves fewer
    independent samples than there are)."""
    design = np.vander(x, degree + 1, increasing=True)
    if columns is not None:
        design = np.concatenate([design, columns], axis=1)
    start, *_ = np.linalg.lstsq(design, values, rcond=None)
    noise = float(median_abs_deviation(values - design @ start, scale="normal"))
    if noise > 0.0:  # an exactly constant stretch is its own level
        start = least_squares(lambda c: design @ c - values, start, loss="soft_l1", f_scale=noise).x
    left = values - design @ start
    spectrum = np.fft.rfft(left - left.mean(), 2 * left.size)
    correlation = np.fft.irfft(np.abs(spectrum) ** 2)[: left.size]
    correlation = correlation / correlation[0] if correlation[0] > 0.0 else correlation
    positive = np.cumprod(correlation[1:] > 0.0).astype(bool)  # the initial positive run
    time = 1.0 + 2.0 * float(np.sum(correlation[1:][positive]))
    return start, noise**2 * time * np.linalg.inv(design.T @ design)


class HeadFit(NamedTuple):
    """The level fitted after a pulse at a record's start (:func:`head_fit`); its
    methods evaluate it at sample indices (extrapolated back over the pulse, and on past
    the fit window)."""

    coefficients: np.ndarray
    """The polynomial's coefficients, lowest power first, in ``(index - head) / scale``."""
    covariance: np.ndarray
    """Their covariance (the residual's autocorrelation time counted)."""
    extra: np.ndarray
    """Coefficients of the ``columns`` fitted with it (empty without)."""
    window: tuple
    """The fit window ``(head, last)``: the first sample after the pulse (the
    polynomial's origin) and the last sample fitted (indices)."""
    scale: float
    """Samples from ``head`` to just past the last sample fitted [-]."""

    @property
    def degree(self):
        """Degree of the polynomial kept (1 or :data:`HEAD_DEGREE`) [-]."""
        return self.coefficients.size - 1

    def _powers(self, index, size):
        at = (np.asarray(index, dtype=float) - self.window[0]) / self.scale
        return np.vander(at, size, increasing=True)

    def level(self, index):
        """The level at sample ``index`` (array) [unit of y]."""
        return self._powers(index, self.coefficients.size) @ self.coefficients

    def error(self, index):
        """The level's standard error at sample ``index`` [unit of y]."""
        powers = self._powers(index, self.coefficients.size)
        return np.sqrt(np.einsum("ij,jk,ik->i", powers, self.covariance, powers))


def head_fit(y, head, width, exclude=None, columns=None):
    """The level of a record's first ``head`` samples (a pulse at its start), fitted
    after them and extrapolated back (module docstring).

    Parameters
    ----------
    y : numpy.ndarray
        Finite samples (any unit), checked by the caller.
    head : int
        Samples at the record's start that hold the pulse (and its ringing unless
        ``columns`` fit it), >= 1.
    width : int
        Block length of the running baseline [samples]: the fit window holds
        :data:`HEAD_FIT_BLOCKS` of them after ``head``.
    exclude : numpy.ndarray of bool, optional
        Samples left out of the fit (other pulses): the window reaches past them.
    columns : numpy.ndarray, optional
        Regressors fitted together with the polynomial (``(y.size, m)``; e.g. the
        sensor's free ringing after a contact), not part of the level.

    Returns
    -------
    HeadFit

    Raises
    ------
    ParameterError
        Fewer than :data:`HEAD_MIN_SAMPLES` samples after the pulse, ``exclude`` left out.
    """
    index = np.arange(head, y.size)
    if exclude is not None:  # the window reaches past other pulses to hold its samples
        index = index[~exclude[head:]]
    index = index[: max(HEAD_MIN_SAMPLES, round(HEAD_FIT_BLOCKS * width))]
    if index.size < HEAD_MIN_SAMPLES:
        raise ParameterError(
            f"only {index.size} quiet samples after the pulse at the record's start (head = "
            f"{head} samples; need {HEAD_MIN_SAMPLES}): no baseline to extrapolate under it; "
            "record a pre-trigger"
        )
    stop = int(index[-1]) + 1
    scale = float(stop - head)
    x = (index - head) / scale
    extra = None if columns is None else columns[index]
    degree = HEAD_DEGREE
    coefficients, covariance = _robust_fit(x, y[index], degree, extra)
    if abs(coefficients[degree]) < CURVATURE_SIGMAS * np.sqrt(covariance[degree, degree]):
        degree -= 1
        coefficients, covariance = _robust_fit(x, y[index], degree, extra)
    return HeadFit(
        coefficients=coefficients[: degree + 1],
        covariance=covariance[: degree + 1, : degree + 1],
        extra=coefficients[degree + 1 :],
        window=(head, stop - 1),
        scale=scale,
    )


def head_level(y, head, width, exclude, level, residual):
    """Put the level of the first ``head`` samples (a pulse at the record's start) and of
    the fit window after them into ``level``, and ``y`` less it into ``residual``; return
    its standard error (module docstring; :func:`head_fit`).

    Parameters
    ----------
    y : numpy.ndarray
        Finite samples (any unit), checked by the caller.
    head : int
        Samples at the record's start that hold the pulse and its ringing, >= 1.
    width : int
        Block length of the running baseline [samples]: the fit window holds
        :data:`HEAD_FIT_BLOCKS` of them after ``head``.
    exclude : numpy.ndarray of bool or None
        Samples left out of the fit (other pulses): the window reaches past them.
    level, residual : numpy.ndarray
        The running baseline's level and residual (``y``'s size), changed in place over
        the pulse and the fit window.

    Returns
    -------
    numpy.ndarray
        The standard error of the level at every sample (unit of ``y``; 0 past the fit
        window), from the fit's covariance and the robust noise of its residual.

    Raises
    ------
    ParameterError
        Fewer than :data:`HEAD_MIN_SAMPLES` samples after the pulse, ``exclude`` left out.
    """
    fit = head_fit(y, head, width, exclude)
    stop = fit.window[1] + 1
    level[:stop] = fit.level(np.arange(stop))
    residual[:stop] = y[:stop] - level[:stop]
    error = np.zeros(y.size)
    error[:stop] = fit.error(np.arange(stop))
    return error
