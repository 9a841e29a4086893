"""States of the exactly solvable pieces of an impact, at any times or on a uniform grid.

Two kinds of piece are linear time-invariant and solved in closed form:

* :class:`LinearContactStates`: the coupled grain and sensor under a linear contact
  branch ``S2 = k d + c d' + f0``, a flow about its equilibrium;
* :class:`AffineForceStates`: the sensor driven by a force affine in time
  ``S2 = a + b tau`` (the paper's trapezoid, a force cap, or no force at all), with the
  grain moving under the same force.

An adaptive piece (:class:`DenseStates`) is the chain of its integrator's per-step
dense outputs.

All give ``states(tau) -> (n, 4)`` at local times ``tau`` [s] and a faster
``grid(tau, step, out)`` for the uniform output grid. State vector: ``[x1, v1, x2, v2]``
(sensor displacement [m] and velocity [m/s], grain displacement [m] and velocity [m/s]).
"""

import bisect

import numpy as np
from scipy.integrate import OdeSolution

__all__ = ["AffineForceStates", "DenseStates", "LinearContactStates"]


class LinearContactStates:
    """Exact states under a linear contact branch ``S2 = k d + c d' + f0`` (k > 0).

    Parameters
    ----------
    system : contactlab.impact._System
        Masses and sensor element.
    k, c, f0 : float
        Branch stiffness [N/m], damping [N*s/m] and offset force [N].
    y0 : array_like
        State at the start of the piece.

    Attributes
    ----------
    rate : float
        Largest ``|lambda|`` of the piece's modes [1/s] (sets the event scan step).
    """

    def __init__(self, system, k, c, f0, y0):
        flow = system.contact_flow(k, c)
        self._rigid = system.rigid
        y0 = np.asarray(y0, dtype=float)
        if self._rigid:
            self._eq = np.array([-f0 / k, 0.0])
            self._trajectory = flow.trajectory(y0[2:] - self._eq)
        else:
            self._eq = np.array([0.0, 0.0, -f0 / k, 0.0])
            self._trajectory = flow.trajectory(y0 - self._eq)
        self.rate = flow.fastest_rate

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        z = self._trajectory(tau)
        if not self._rigid:
            return z + self._eq
        out = np.zeros((len(z), 4))
        out[:, 2:] = z + self._eq
        return out

    def grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        if self._rigid:
            out[:, :2] = 0.0
            self._trajectory.grid(tau[0], step, tau.size, out=out[:, 2:])
        else:
            self._trajectory.grid(tau[0], step, tau.size, out=out)
        out += np.pad(self._eq, (4 - self._eq.size, 0))
        return out


class AffineForceStates:
    """Exact states under a prescribed contact force ``S2 = a + b tau`` [N].

    The grain's motion is a cubic in ``tau``; the sensor's is its free flow about the
    particular solution ``x1 = p + q tau`` of ``m1 x1'' + c1 x1' + k1 x1 = a + b tau``,
    i.e. ``q = b / k1`` and ``p = a / k1 - c1 b / k1**2``.

    Parameters
    ----------
    system : contactlab.impact._System
        Masses and sensor element.
    a : float
        Force at the start of the piece [N].
    b : float
        Force slope [N/s].
    y0 : array_like
        State at the start of the piece.
    """

    def __init__(self, system, a, b, y0):
        self._x10, self._v10, self._x20, self._v20 = (float(v) for v in y0)
        self._a, self._b, self._m2 = a, b, system.m2
        self._rigid = system.rigid
        self.rate = 0.0
        if not self._rigid:
            self._q = b / system.k1
            self._p = a / system.k1 - system.c1 * b / system.k1**2
            flow = system.sensor_flow
            self._sensor = flow.trajectory([self._x10 - self._p, self._v10 - self._q])
            self.rate = flow.fastest_rate

    def _fill(self, tau, out):
        """Grain columns, and the sensor's particular solution added to its columns."""
        a, b, m2 = self._a, self._b, self._m2
        if a == 0.0 and b == 0.0:  # free flight: the common case, kept cheap
            np.multiply(tau, self._v20, out=out[:, 2])
            out[:, 2] += self._x20
            out[:, 3] = self._v20
        else:
            out[:, 2] = self._x20 + tau * (self._v20 - tau * (a / 2 + b / 6 * tau) / m2)
            out[:, 3] = self._v20 - tau * (a + b / 2 * tau) / m2
        if self._rigid:
            out[:, :2] = 0.0
        elif self._p != 0.0 or self._q != 0.0:
            out[:, 0] += self._p + self._q * tau
            out[:, 1] += self._q
        return out

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        out = np.empty((tau.size, 4))
        if not self._rigid:
            out[:, :2] = self._sensor(tau)
        return self._fill(tau, out)

    def grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        if not self._rigid:
            self._sensor.grid(tau[0], step, tau.size, out=out[:, :2])
        return self._fill(tau, out)


class DenseStates:
    """States of an adaptive piece from its DOP853 per-step dense outputs.

    Parameters
    ----------
    t0 : float
        Start of the piece [s] (local time 0).
    times : array_like
        Step boundaries [s], increasing, ``len(pieces) + 1`` of them.
    pieces : list of scipy.integrate.DenseOutput
        Each step's 7th-order interpolant, as :meth:`scipy.integrate.DOP853.dense_output`
        returns it (absolute time).

    Notes
    -----
    :meth:`grid` evaluates every step's interpolant at once from their coefficients
    (the ``F``, ``y_old``, ``t_old`` and ``h`` of scipy's DOP853 dense output, in its
    nested form ``y_old + x (F0 + (1 - x) (F1 + x (F2 + ...))))`` with
    ``x = (t - t_old) / h``) instead of one call per step; ``tests/test_impact.py``
    checks it against the interpolants themselves.
    """

    def __init__(self, t0, times, pieces):
        self._t0 = t0
        self._times = np.asarray(times, dtype=float)
        self._solution = OdeSolution(self._times, pieces)
        self._pieces, self._bounds = pieces, self._times.tolist()
        # (7, steps, dim): one contiguous table per coefficient, gathered per sample
        self._coefficients = np.ascontiguousarray(np.stack([p.F for p in pieces], axis=1))
        self._y_old = np.stack([p.y_old for p in pieces])
        self._steps = np.array([p.h for p in pieces])

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s] (any order)."""
        tau = np.atleast_1d(tau)
        if tau.size == 1:  # the metrics' root finders ask one time at a time
            t = self._t0 + float(tau[0])
            i = min(max(bisect.bisect_right(self._bounds, t) - 1, 0), len(self._pieces) - 1)
            return self._pieces[i](t)[None, :]
        return self._solution(self._t0 + tau).T

    def grid(self, tau, step, out):
        """Write the states at local times ``tau`` [s] into ``out`` (n, 4)."""
        t = self._t0 + tau
        which = np.searchsorted(self._times, t, side="right") - 1
        np.clip(which, 0, self._steps.size - 1, out=which)
        x = ((t - self._times[which]) / self._steps[which])[:, None]
        factors = (x, 1.0 - x)
        y = np.zeros((t.size, self._y_old.shape[1]))  # row-major like the gathered rows
        rows = np.empty_like(y)
        for i, table in enumerate(self._coefficients[::-1]):
            y += np.take(table, which, axis=0, out=rows)
            y *= factors[i % 2]
        y += np.take(self._y_old, which, axis=0, out=rows)
        out[...] = y
        return out
