"""Exact propagation of the linear pieces of an impact.

Between events the grain/sensor system is often linear time-invariant: the free sensor,
the sensor driven by a force that is affine in time (the paper's trapezoid, a force cap,
no force at all), and the coupled system under a linear contact branch. This module
computes the modes of those pieces (:class:`LinearFlow`; their solutions are the data of
:class:`contactlab.kernels.segments.Trajectory`, modal or, when the modes are defective,
by the matrix exponential) and finds event times as roots of the exact expressions.

State vector everywhere: ``y = [x1, v1, x2, v2]`` (sensor displacement [m] and velocity
[m/s], grain displacement [m] and velocity [m/s]), axis along the grain's travel.
"""

import functools
import math

import numpy as np

from contactlab.errors import ParameterError
from contactlab.kernels import rules
from contactlab.kernels.rules import too_fast_error
from contactlab.kernels.segments import Trajectory
from contactlab.roots import crosses, earliest_root

__all__ = ["LinearFlow", "first_event", "linear_flow"]

_COND_LIMIT = 1e8
"""Largest eigenvector condition number for which the modal solution is trusted
(relative error about cond * 1e-16 = 1e-8); beyond it the matrix exponential is used."""


class LinearFlow:
    """Flow of ``z' = A z``: ``z(tau) = exp(A tau) z0`` (see :meth:`trajectory`).

    Parameters
    ----------
    matrix : numpy.ndarray
        Square system matrix ``A`` [1/s and 1/s**2 entries].
    scale : array_like, optional
        Positive diagonal ``D`` of coordinates ``D z`` in which the state's components
        are of one size (e.g. forces [N]); the eigenvectors are computed there.

    Notes
    -----
    Diagonalisable matrices (every underdamped or overdamped mode) use the modal form
    ``V exp(Lambda tau) V**-1 z0``; a near-defective matrix (critical damping) falls back
    to :func:`scipy.linalg.expm` on a stack of ``A tau``.

    An eigenvector is accurate to round-off relative to its largest component. A sensor
    displacement ``x1`` of 1e-11 m beside a grain speed of 1 m/s would lose seven digits
    that way (its signal ``k1 x1`` was off by 1e-8 relative on a stiff sensor), so the
    modes are those of ``D A D**-1``, mapped back to ``V = D**-1 V_D`` and
    ``V**-1 = V_D**-1 D``: every component keeps its own relative accuracy.
    """

    def __init__(self, matrix, scale=None):
        self.matrix = np.asarray(matrix, dtype=float)
        scale = np.ones(self.matrix.shape[0]) if scale is None else np.asarray(scale, float)
        with np.errstate(over="ignore", invalid="ignore"):
            scaled = self.matrix * np.divide.outer(scale, scale)
        if not np.isfinite(scaled).all():
            raise ParameterError(
                "the linear system's rates overflow a float (largest entry "
                f"{np.max(np.abs(self.matrix)):.3g}): a stiffness or damping too large for the "
                "bodies' masses; check their units"
            )
        eigvals, eigvecs = np.linalg.eig(scaled)
        self.modal = np.linalg.cond(eigvecs) < _COND_LIMIT
        if self.modal:
            self.eigvals = eigvals
            self._vecs = eigvecs / scale[:, None]
            self._inv = np.linalg.inv(eigvecs) * scale
            # one mode of each conjugate pair (weight 2) and the real ones (weight 1):
            # the same for every start state, so read once here, not in each trajectory
            self._keep = eigvals.imag >= 0.0
            self._rates = eigvals[self._keep].astype(complex)
            self._weight = np.where(self._rates.imag > 0.0, 2.0, 1.0)
            self._rates.flags.writeable = False  # shared by every trajectory of the flow
        self.fastest_rate = float(np.max(np.abs(eigvals))) if eigvals.size else 0.0
        """Largest ``|lambda|`` [1/s]: sets the scan step for events."""

    def trajectory(self, z0):
        """The solution from ``z0`` as data, with its modal coefficients computed once.

        Parameters
        ----------
        z0 : array_like
            Initial state (dim,).

        Returns
        -------
        contactlab.kernels.segments.Trajectory
            Rates and real weights of the modes (one of each conjugate pair, weight 2; the
            real ones, weight 1): ``u_k = c_k v_k``, modal coefficient times eigenvector;
            ``A`` and ``z0`` alone where the modes are too close to defective.
        """
        z0 = np.asarray(z0, dtype=float)
        if not self.modal:
            return Trajectory(z0, self.matrix)
        rates = self._rates
        u = (self._vecs * (self._inv @ z0.astype(complex)))[:, self._keep] * self._weight
        weights = np.empty((2 * rates.size, z0.size))
        weights[0::2] = u.real.T
        weights[1::2] = -u.imag.T
        return Trajectory(z0, self.matrix, rates, weights)


@functools.lru_cache(maxsize=1024)
def _cached_flow(entries, dim, scale):
    return LinearFlow(np.reshape(entries, (dim, dim)), scale)


def linear_flow(matrix, scale=None):
    """The :class:`LinearFlow` of ``matrix`` (and ``scale``), shared between equal calls.

    Studies solve thousands of impacts on the same sensor and a few contact stiffnesses;
    the eigendecomposition of each system matrix is done once (least-recently-used
    cache of 1024 matrices). Flows are never modified after construction.
    """
    matrix = np.asarray(matrix, dtype=float)
    scale = None if scale is None else tuple(np.asarray(scale, dtype=float).tolist())
    return _cached_flow(tuple(matrix.ravel().tolist()), matrix.shape[0], scale)


def first_event(values, tau_max, step, directions, chunk=256):
    """First zero crossing of any of several exact event functions on ``(0, tau_max]``.

    Parameters
    ----------
    values : callable
        ``values(tau) -> array (len(tau), n_events)``: event functions at local times [s].
    tau_max : float
        End of the search [s].
    step : float
        Scan step [s]; it must be short against the fastest oscillation of the events so
        that no pair of crossings falls between two scan points.
    directions : sequence of int
        Per event, as in :func:`crosses`.
    chunk : int
        Scan points evaluated per vectorised call.

    Returns
    -------
    (tau, index) or None
        Time of the earliest crossing [s], located to machine precision
        (:func:`earliest_root`), and which event it was; None if none before ``tau_max``.

    Raises
    ------
    ParameterError
        If no event is found within :data:`contactlab.kernels.rules.MAX_SCAN_POINTS` scan
        points (a run-time limit).
    """
    directions = np.asarray(directions)
    start, previous = 0.0, values(np.array([0.0]))[0]
    for _ in range(math.ceil(rules.MAX_SCAN_POINTS / chunk)):
        if start >= tau_max:
            return None
        grid = np.minimum(start + step * np.arange(1, chunk + 1), tau_max)
        grid = grid[np.concatenate(([True], np.diff(grid) > 0))]
        vals = values(grid)
        before = np.vstack((previous, vals[:-1]))
        crossed = np.where(directions < 0, crosses(before, vals, -1), crosses(before, vals, +1))
        rows = np.flatnonzero(crossed.any(axis=1))
        if rows.size:
            i = rows[0]
            lo = grid[i - 1] if i > 0 else start
            return earliest_root(
                np.flatnonzero(crossed[i]),
                lambda s, j: values(np.array([s]))[0, j],
                lo,
                grid[i],
                directions,
            )
        start, previous = grid[-1], vals[-1]
    if start >= tau_max:
        return None
    raise too_fast_error(f"scan step {step:.3g} s, still no event after {start:.3g} s")
