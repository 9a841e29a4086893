"""Choosing the Tikhonov parameter lambda of :func:`contactlab.inverse.reconstruct_force`.

The problem ``min ||H f - s||**2 + lambda**2 ||D f||**2`` with ``D`` the first difference
is brought to standard form (``f = f0 + cumulative sum of the penalised differences``,
Elden 1977) and reduced by one SVD, so that the residual and the effective number of
parameters are known in closed form for every lambda; lambda is then chosen by
generalised cross-validation or by the discrepancy principle.

References
----------
Hansen P.C. (1994) Regularization Tools. Numer. Algorithms 6, 1-35.
DOI 10.1007/BF02149761
Elden L. (1977) Algorithms for the regularization of ill-conditioned least squares
problems. BIT 17, 134-145. DOI 10.1007/BF01932285
Hastie T., Tibshirani R., Friedman J. (2009) The Elements of Statistical Learning, 2nd
ed., Springer, section 7.10 (the one-standard-error rule).
"""

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from contactlab.errors import ParameterError

__all__ = ["CRITERIA", "StandardForm"]


class StandardForm:
    """Tikhonov problem with a first-difference penalty, reduced by one SVD.

    With ``f = f0 * 1 + C d`` (``C`` cumulative sums, ``d`` the differences) the
    penalty is ``||d||**2`` and ``f0`` is free; projecting ``f0`` out (Elden 1977)
    leaves a standard-form problem solved for every lambda by the SVD's filter factors.
    ``h`` is the model matrix, ``y`` the data (one entry per row); ``smoothest`` makes
    GCV take the smoothest of its near-equal local minima (a whitened problem, whose
    noise model was estimated: :func:`contactlab.inverse.reconstruct_force`).
    """

    def __init__(self, h, y, smoothest=False):
        self.y = y
        self.smoothest = smoothest
        self.ones = h.sum(axis=1)
        self.hd = np.cumsum(h[:, ::-1], axis=1)[:, ::-1][:, 1:]
        project = self._project
        # QR first, then the SVD of the small triangular factor: the same singular
        # values and vectors as the SVD of the tall matrix, at a fraction of its cost
        q, r = np.linalg.qr(project(self.hd))
        u, self.s, _ = np.linalg.svd(r)
        yp = project(y)
        self.beta = u.T @ (q.T @ yp)
        self.outside = max(float(yp @ yp - self.beta @ self.beta), 0.0)

    def _project(self, a):
        scale = self.ones @ self.ones
        if a.ndim == 1:
            return a - self.ones * (self.ones @ a) / scale
        return a - np.outer(self.ones, self.ones @ a) / scale

    def residual2(self, lam):
        """Squared residual norm of the unconstrained solution."""
        filt = lam**2 / (self.s**2 + lam**2)
        return float(np.sum((filt * self.beta) ** 2)) + self.outside

    def dof(self, lam):
        """Trace of the influence matrix (effective number of parameters)."""
        return 1.0 + float(np.sum(self.s**2 / (self.s**2 + lam**2)))

    def bracket(self):
        """Range of log10(lambda) worth searching."""
        top = math.log10(self.s[0])
        return top - 8.0, top + 1.0


def _gcv(problem, noise):
    """Generalised cross-validation: minimise ``||r||**2 / (m - dof)**2``.

    With ``problem.smoothest`` the largest lambda among the score's local minima within
    one standard error of the lowest, ``sqrt(2 / (m - dof))`` of it, is taken (the
    one-standard-error rule of cross-validation, Hastie, Tibshirani & Friedman 2009,
    7.10, applied to the minima only).
    """
    rows = problem.y.size
    lo, hi = problem.bracket()
    grid = np.linspace(lo, hi, 91)

    def score(loglam):
        lam = 10.0**loglam
        return problem.residual2(lam) / (rows - problem.dof(lam)) ** 2

    values = np.array([score(v) for v in grid])
    best = int(np.argmin(values))
    if problem.smoothest:
        tolerance = math.sqrt(2.0 / (rows - problem.dof(10.0 ** grid[best])))
        inner = values[1:-1]
        minima = np.flatnonzero((inner <= values[:-2]) & (inner <= values[2:])) + 1
        best = int(max(minima[values[minima] <= (1.0 + tolerance) * values[best]], default=best))
    left, right = grid[max(best - 1, 0)], grid[min(best + 1, grid.size - 1)]
    return 10.0 ** minimize_scalar(score, bounds=(left, right), method="bounded").x


def _discrepancy(problem, noise):
    """Discrepancy principle: ``||r||**2 = m sigma**2`` (Morozov)."""
    target = problem.y.size * noise**2
    lo, hi = problem.bracket()

    def excess(loglam):
        return problem.residual2(10.0**loglam) - target

    if excess(lo) > 0.0 or excess(hi) < 0.0:
        raise ParameterError(
            f"the discrepancy principle has no solution: the baseline noise "
            f"({noise:.3g} per data block) is outside the range of residuals the model "
            "allows (a wrong sensor model, a baseline window that is not noise, or a "
            "drifting signal); use regularization='gcv'"
        )
    return 10.0 ** brentq(excess, lo, hi, xtol=1e-3)


CRITERIA = {"gcv": _gcv, "discrepancy": _discrepancy}
"""Regularisation-parameter choices: name -> function(problem, block noise) -> lambda."""
