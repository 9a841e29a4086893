"""A lean DOP853 integrator for the nonlinear contact pieces, with per-step dense output.

The contact pieces of a Hertz-family impact are small (four states) and short (a few
dozen steps), so the cost of :class:`scipy.integrate.DOP853` is mostly its general
machinery, not arithmetic. This module runs the same method with the same coefficients
(taken from scipy's class), error norm and step-size control, without that machinery:
the right-hand side is an autonomous ``f(y)``, events are checked by the caller after
each step, and each step's 7th-order interpolant is kept as plain arrays so that a whole
output grid is evaluated at once (:class:`contactlab.kernels.segments.DenseSteps`).

References
----------
Hairer E., Norsett S.P., Wanner G. (1993) Solving Ordinary Differential Equations I:
Nonstiff Problems, 2nd ed., Springer, Sec. II.4-II.6 (DOP853, step-size control, initial
step). scipy.integrate.DOP853 (the coefficient tables and error norm used here).
"""

import math

import numpy as np
from scipy.integrate import DOP853 as _SCIPY

__all__ = ["Stepper"]

_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
"""Step-size control of scipy's Runge-Kutta solvers (Hairer's defaults)."""

_EXPONENT = -1.0 / (_SCIPY.error_estimator_order + 1)
_STAGES = _SCIPY.n_stages
_A_ROWS = [np.array(_SCIPY.A[s, :s]) for s in range(_STAGES)]
_A_EXTRA_ROWS = [np.array(a[: _STAGES + 1 + i]) for i, a in enumerate(_SCIPY.A_EXTRA)]


class Stepper:
    """DOP853 steps of ``y' = f(y)`` from ``y0`` at ``t0``.

    Parameters
    ----------
    fun : callable
        ``fun(y) -> ndarray`` (n,), the right-hand side (autonomous).
    t0 : float
        Start [s].
    y0 : array_like
        Initial state (n,).
    rtol : float
        Relative tolerance.
    atol : ndarray
        Absolute tolerance per state component.
    first_step : float, optional
        First step to try; default :meth:`initial_step`.
    separate : bool, default False
        Combine the two error estimates per component (:meth:`error_norm`): the warped
        start of a contact piece.

    Attributes
    ----------
    t, y : float, ndarray
        Time and state after the last accepted step.
    t_old, y_old : float, ndarray
        The same before it.
    """

    def __init__(self, fun, t0, y0, rtol, atol, first_step=None, separate=False):
        self._fun, self._separate = fun, separate
        self.t = self.t_old = float(t0)
        self.y = self.y_old = np.asarray(y0, dtype=float)
        self._rtol, self._atol = rtol, atol
        self._f = fun(self.y)
        self._K = np.empty((_SCIPY.A_EXTRA.shape[0] + _STAGES + 1, self.y.size))
        self._h = self.initial_step() if first_step is None else first_step

    @property
    def rtol(self):
        """Relative tolerance [-]."""
        return self._rtol

    def _norm(self, x, scale):
        x = x / scale
        return math.sqrt(float(x @ x) / x.size)

    def initial_step(self):
        """Hairer's starting step (Sec. II.4): a first-order guess, refined once."""
        y, f = self.y, self._f
        scale = self._atol + np.abs(y) * self._rtol
        d0, d1 = self._norm(y, scale), self._norm(f, scale)
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        d2 = self._norm(self._fun(y + h0 * f) - f, scale) / h0
        if max(d1, d2) <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / (_SCIPY.error_estimator_order + 1))
        return min(100.0 * h0, h1)

    def step(self, t_bound):
        """One accepted step, not beyond ``t_bound`` [s]; returns False if the step size
        underflows (the solution is not resolvable at this tolerance)."""
        t, y, f, K = self.t, self.y, self._f, self._K
        min_step = 10.0 * abs(math.nextafter(t, math.inf) - t)
        h = max(self._h, min_step)
        rejected = False
        while True:
            if h < min_step:
                return False
            t_new = min(t + h, t_bound)
            h = t_new - t
            K[0] = f
            for s in range(1, _STAGES):
                K[s] = self._fun(y + h * (_A_ROWS[s] @ K[:s]))
            y_new = y + h * (_SCIPY.B @ K[:_STAGES])
            f_new = self._fun(y_new)
            K[_STAGES] = f_new
            scale = self._atol + np.maximum(np.abs(y), np.abs(y_new)) * self._rtol
            error = self.error_norm(K[: _STAGES + 1], h, scale)
            if error < 1.0:
                factor = _MAX_FACTOR if error == 0 else min(_MAX_FACTOR, _SAFETY * error**_EXPONENT)
                self._h = h * (min(1.0, factor) if rejected else factor)
                break
            h *= max(_MIN_FACTOR, _SAFETY * error**_EXPONENT)
            rejected = True
        self.t_old, self.y_old, self._f_old, self._h_done = t, y, f, h
        self.t, self.y, self._f = t_new, y_new, f_new
        return True

    def undo(self):
        """Return to the last step's start (the next :meth:`step` may take a shorter one)."""
        self.t, self.y, self._f = self.t_old, self.y_old, self._f_old

    def error_norm(self, K, h, scale):
        """A step's error norm [-] from its stages ``K`` (13, n), length ``h`` and scale.

        scipy's and Hairer's (``DOP853``, Sec. II.10): ``h ||e5||**2 / sqrt(||e5||**2 +
        0.01 ||e3||**2)`` with the 5th- and 3rd-order estimates' rms norms over all
        components, which behaves like an 8th-order estimate as long as both estimates
        come from the same smooth solution. ``separate``: the same combination per
        component, then their rms. The warped start needs it: there the grain's free
        flight ``x2 = v0 s**4`` is exact at orders 5 and 8 but not at 3, so its 3rd-order
        estimate (1e8 tolerances on the first long step) filled the common denominator
        and let the velocity's 5th-order estimate of 8e3 tolerances pass as 0.7: an
        elastic rebound 106 rtol off ``e = 1`` (docs/verification.md, finding 11).
        """
        err5 = (_SCIPY.E5 @ K) / scale
        err3 = (_SCIPY.E3 @ K) / scale
        if self._separate:
            e5, e3 = err5 * err5, err3 * err3
            kept = e5 > 0.0
            total = float(np.sum(e5[kept] ** 2 / (e5[kept] + 0.01 * e3[kept])))
            return abs(h) * math.sqrt(total / scale.size)
        e5, e3 = float(err5 @ err5), float(err3 @ err3)
        if e5 == 0.0 and e3 == 0.0:
            return 0.0
        return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * scale.size)

    def interpolant(self):
        """Coefficients ``F`` (7, n) of the last step's 7th-order interpolant.

        ``y(t_old + x h) = y_old + x (F0 + (1 - x) (F1 + x (F2 + (1 - x) (F3 + ...))))``,
        three extra stages as in DOP853.
        """
        K, h, y_old = self._K, self._h_done, self.y_old
        for i, a in enumerate(_A_EXTRA_ROWS):
            K[_STAGES + 1 + i] = self._fun(y_old + h * (a @ K[: a.size]))
        delta = self.y - y_old
        F = np.empty((_SCIPY.D.shape[0] + 3, y_old.size))
        F[0] = delta
        F[1] = h * K[0] - delta
        F[2] = 2.0 * delta - h * (self._f + K[0])
        F[3:] = h * (_SCIPY.D @ K)
        return F
