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

import numpy as np

__all__ = ["AffineForceStates", "DenseStates", "LinearContactStates"]


class LinearContactStates:
    """Exact states under a linear contact branch ``S2 = k d + c d' + f0`` (k > 0).

    Parameters
    ----------
    system : contactlab.solver.system.System
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
        self._offset = np.array([0.0, 0.0, -f0 / k, 0.0])  # the equilibrium of the branch
        z0 = np.asarray(y0, dtype=float) - self._offset
        self._trajectory = flow.trajectory(z0[2:] if self._rigid else z0)
        self.rate = flow.fastest_rate

    def _moving(self, out):
        """The columns of ``out`` the flow moves (on a wall only the grain's; the plate's
        are set to rest)."""
        if not self._rigid:
            return out
        out[:, :2] = 0.0
        return out[:, 2:]

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        out = np.empty((tau.size, 4))
        self._moving(out)[...] = self._trajectory(tau)
        out += self._offset
        return out

    def grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        self._trajectory.grid(tau[0], step, tau.size, out=self._moving(out))
        out += self._offset
        return out


class AffineForceStates:
    """Exact states under a prescribed contact force ``S2 = a + b tau`` [N].

    The grain's motion is a cubic in ``tau``; the sensor's is its free flow about the
    particular solution ``x1 = p + q tau`` of ``m1 x1'' + c1 x1' + k1 x1 = a + b tau``,
    i.e. ``q = b / k1`` and ``p = a / k1 - c1 b / k1**2``.

    Parameters
    ----------
    system : contactlab.solver.system.System
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
    """States of an adaptive piece from its integrator's per-step interpolants.

    Parameters
    ----------
    t0 : float
        Start of the piece [s] (local time 0).
    steps : contactlab.solver.dop853.DenseSteps or None
        The steps in time (absolute [s]) from local time ``switch`` on.
    start : contactlab.solver.dop853.DenseSteps, optional
        Steps in ``s = tau**(1/4)`` (state and ``s``) before local time ``switch``: the
        start of a contact, integrated in that variable (see
        :func:`contactlab.solver.adaptive.adaptive_contact`).
    switch : float, default 0
        Local time [s] where ``start`` hands over to ``steps``.
    size : int, default 4
        Number of state components returned (the first ``size`` of the integrated ones).
    """

    def __init__(self, t0, steps, start=None, switch=0.0, size=4):
        self._t0, self.steps, self.start, self.switch = t0, steps, start, switch
        self._size = size

    def _early(self, tau):
        if self.start is None:
            return np.zeros(tau.shape, dtype=bool)
        return tau < self.switch if self.steps is not None else np.ones(tau.shape, bool)

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s] (any order)."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        early = self._early(tau)
        if tau.size == 1:  # the metrics' root finders ask one time at a time
            if early[0]:
                return self.start.at(max(float(tau[0]), 0.0) ** 0.25)[None, : self._size]
            return self.steps.at(self._t0 + float(tau[0]))[None, :]
        out = np.empty((tau.size, self._size))
        if early.any():
            out[early] = self.start(np.maximum(tau[early], 0.0) ** 0.25)[:, : self._size]
        if not early.all():
            out[~early] = self.steps(self._t0 + tau[~early])
        return out

    def grid(self, tau, step, out):
        """Write the states at increasing local times ``tau`` [s] into ``out`` (n, 4)."""
        split = int(np.count_nonzero(self._early(tau)))  # the early times come first
        if split:
            out[:split] = self.start(np.maximum(tau[:split], 0.0) ** 0.25)[:, : self._size]
        if split < tau.size:
            self.steps(self._t0 + tau[split:], out=out[split:])
        return out
