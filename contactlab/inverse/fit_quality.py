"""Is a fitted law consistent with the trace? Chi-squared against the noise, and whiteness.

A fit is judged by two tests on its normalised residuals ``(S1_model - S1) / sigma``,
``sigma`` the noise read in a window free of the pulse
(:func:`contactlab.inverse.noise_window.clean_noise_window`):

* **size**: the reduced chi-squared is the ratio of the residual variance to the noise
  variance. Both are estimated, from ``n - p`` and ``m - 1`` degrees of freedom (``n``
  fitted samples, ``p`` fitted quantities, ``m`` noise samples), so under the model with
  white Gaussian noise it follows Fisher's ``F(n - p, m - 1)``, not ``chi2(n - p) / (n -
  p)``: with ``m`` = 1000 noise samples its spread is ``sqrt(2/(n - p) + 2/(m - 1))``,
  not ``sqrt(2/(n - p))``. The p-value is two-sided: a chi-squared far *below* 1 means
  the noise was over-estimated (a noise window holding part of the pulse), which makes
  every interval too wide and every chi-squared test blind.
* **whiteness**: the Ljung-Box portmanteau statistic of the residuals' autocorrelation
  over :data:`WHITENESS_LAGS` lags, against ``chi2(lags)`` (Ljung & Box 1978). A law that
  misses the pulse's shape leaves a smooth residual, correlated from sample to sample,
  even when its chi-squared is hidden by a large noise; coloured noise (a filter in the
  acquisition) passes the chi-squared (its variance is right) but makes the intervals
  too narrow. The baseline's own whiteness tells the two apart.

The fit is ``consistent`` when the optimiser converged and neither test rejects at
:data:`ALPHA`.

References
----------
Ljung G.M., Box G.E.P. (1978) On a measure of lack of fit in time series models.
Biometrika 65, 297-303. DOI 10.1093/biomet/65.2.297.
Bevington P.R., Robinson D.K. (2003) Data Reduction and Error Analysis for the Physical
Sciences, 3rd ed., McGraw-Hill, ch. 11 (chi-squared test of a fit).
"""

from dataclasses import dataclass

import numpy as np
from scipy import stats

from contactlab.errors import ContactlabWarning, ParameterError
from contactlab.validation import check_count

__all__ = ["ALPHA", "WHITENESS_LAGS", "FitQuality", "FitQualityWarning", "judge_fit", "ljung_box"]

ALPHA = 0.01
"""Significance level of each test [-]: a correct law with white noise is called
inconsistent in about 2 % of traces (two tests at 1 %)."""

WHITENESS_LAGS = 20
"""Lags of the Ljung-Box statistic [samples]. A misfit is smooth on the scale of the
sensor's period (tens to hundreds of samples), so it correlates every one of them; more
lags add power against it and against slowly coloured noise."""


class FitQualityWarning(ContactlabWarning):
    """The fitted law is not consistent with the trace; the message says why (the
    fit's ``quality.reasons``)."""


def ljung_box(x, lags=WHITENESS_LAGS):
    """Ljung-Box statistic of a series and its p-value against ``chi2(lags)``.

    ``Q = n (n + 2) sum_{k=1}^{h} r_k**2 / (n - k)``, with ``r_k`` the sample
    autocorrelation at lag ``k`` of the mean-removed series and ``h = lags``.

    Parameters
    ----------
    x : array_like
        The series, 1-D, finite, of at least ``lags + 2`` samples.
    lags : int, default :data:`WHITENESS_LAGS`
        Number of lags ``h``, >= 1.

    Returns
    -------
    statistic : float
        ``Q`` [-].
    p_value : float
        ``P(chi2(h) >= Q)`` [-]: small when the series is correlated.
    """
    x = np.asarray(x, dtype=float)
    n = x.size
    lags = check_count("lags", lags)
    if n < lags + 2:
        raise ParameterError(f"the Ljung-Box statistic over {lags} lags needs {lags + 2} samples")
    d = x - x.mean()
    denominator = d @ d
    k = np.arange(1, lags + 1)
    r = np.array([d[j:] @ d[:-j] for j in k]) / denominator
    q = n * (n + 2.0) * np.sum(r**2 / (n - k))
    return float(q), float(stats.chi2.sf(q, lags))


@dataclass(frozen=True)
class FitQuality:
    """The judgement of a fit (see the module's description); probabilities in [0, 1]."""

    reduced_chi_squared: float
    """Sum of squared normalised residuals over ``n - p`` [-]; 1 for a consistent fit."""
    degrees_of_freedom: int
    """``n - p``: fitted samples minus fitted quantities."""
    noise_samples: int
    """``m``: samples of the noise window."""
    p_value: float
    """Two-sided probability of a reduced chi-squared this far from 1 under
    ``F(n - p, m - 1)`` [-]."""
    whiteness_statistic: float
    """Ljung-Box ``Q`` of the residuals over ``lags`` lags [-]."""
    whiteness_p_value: float
    """``P(chi2(lags) >= Q)`` for the residuals [-]."""
    noise_whiteness_p_value: float
    """The same for the noise window's samples [-]: small when the noise is coloured."""
    noise_window: tuple
    """The noise window ``(start, end)`` [s]."""
    converged: bool
    """Whether the optimiser met its tolerances."""
    lags: int = WHITENESS_LAGS
    """Lags of the Ljung-Box statistics: :data:`WHITENESS_LAGS`, or a quarter of the
    samples of a shorter series."""
    alpha: float = ALPHA
    """Significance level of each test [-]."""

    @property
    def reasons(self):
        """Why the fit is not consistent: one sentence per failed check (empty if it is)."""
        out = []
        if not self.converged:
            out.append("the optimiser did not converge (raise max_nfev)")
        if self.p_value < self.alpha:
            if self.reduced_chi_squared > 1.0:
                out.append(
                    f"reduced chi^2 {self.reduced_chi_squared:.3g} is too large for the noise "
                    f"(p = {self.p_value:.2g}): the law does not describe the signal"
                )
            else:
                out.append(
                    f"reduced chi^2 {self.reduced_chi_squared:.3g} is too small for the noise "
                    f"(p = {self.p_value:.2g}): the noise window holds signal, or the noise "
                    "is over-estimated"
                )
        if self.whiteness_p_value < self.alpha:
            cause = (
                "the noise itself is coloured (its window's Ljung-Box p = "
                f"{self.noise_whiteness_p_value:.2g}), so the intervals are too narrow"
                if self.noise_whiteness_p_value < self.alpha
                else "the law leaves a systematic misfit"
            )
            out.append(
                f"the residuals are correlated (Ljung-Box p = {self.whiteness_p_value:.2g} "
                f"over {self.lags} lags): {cause}"
            )
        return out

    @property
    def consistent(self):
        """True when the optimiser converged and neither test rejects at ``alpha``."""
        return not self.reasons

    def to_dict(self):
        """The ``quality`` block of FIT.json (plain JSON numbers, all finite)."""
        return {
            "consistent": self.consistent,
            "reasons": self.reasons,
            "reduced_chi_squared [-]": self.reduced_chi_squared,
            "degrees_of_freedom": self.degrees_of_freedom,
            "noise_samples": self.noise_samples,
            "p_value [-]": self.p_value,
            "whiteness": {
                "test": "ljung-box",
                "lags": self.lags,
                "statistic [-]": self.whiteness_statistic,
                "p_value [-]": self.whiteness_p_value,
                "noise_p_value [-]": self.noise_whiteness_p_value,
            },
            "noise_window [s]": list(self.noise_window),
            "alpha [-]": self.alpha,
        }

    def summary(self):
        """One line of text: the verdict and the numbers behind it."""
        verdict = "consistent" if self.consistent else "NOT consistent"
        numbers = (
            f"reduced chi^2 {self.reduced_chi_squared:.3g} (p = {self.p_value:.2g}), "
            f"residual whiteness p = {self.whiteness_p_value:.2g}"
        )
        reasons = "".join(f"\n  - {r}" for r in self.reasons)
        return f"fit quality: {verdict}: {numbers}{reasons}"


def judge_fit(normalised_residuals, fitted, noise_samples, noise_window, converged):
    """Judge a fit from its residuals.

    Parameters
    ----------
    normalised_residuals : numpy.ndarray
        ``(S1_model - S1) / sigma`` at the fitted samples, in time order [-].
    fitted : int
        Number of fitted quantities ``p``.
    noise_samples : numpy.ndarray
        The noise window's samples, minus their mean (signal unit).
    noise_window : (float, float)
        The noise window [s].
    converged : bool
        Whether the optimiser converged.

    Returns
    -------
    FitQuality
    """
    dof = normalised_residuals.size - fitted
    noise_dof = noise_samples.size - 1
    reduced = float(normalised_residuals @ normalised_residuals) / dof
    tail = min(stats.f.cdf(reduced, dof, noise_dof), stats.f.sf(reduced, dof, noise_dof))
    lags = min(WHITENESS_LAGS, normalised_residuals.size // 4)
    q, p_white = ljung_box(normalised_residuals, lags)
    return FitQuality(
        reduced_chi_squared=reduced,
        degrees_of_freedom=int(dof),
        noise_samples=int(noise_samples.size),
        p_value=float(min(1.0, 2.0 * tail)),
        whiteness_statistic=q,
        whiteness_p_value=p_white,
        noise_whiteness_p_value=ljung_box(noise_samples, min(lags, noise_samples.size // 4))[1],
        noise_window=tuple(float(v) for v in noise_window),
        converged=bool(converged),
        lags=lags,
    )
