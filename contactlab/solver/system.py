"""The two-mass grain/sensor system: its matrices, right-hand side and signal.

State vector everywhere: ``y = [x1, v1, x2, v2]`` (sensor displacement [m] and velocity
[m/s], grain displacement [m] and velocity [m/s]), axis along the grain's travel; overlap
``d = x2 - x1``, rate ``d' = v2 - v1``. The helpers here are shared by the exact and the
adaptive contact pieces.
"""

import math

import numpy as np

from contactlab.kernels.rules import contact_matrix
from contactlab.solver.propagators import linear_flow

__all__ = [
    "System",
    "event_directions",
    "force_scales",
    "overlap_rate",
]


class System:
    """Masses and sensor element; the linear algebra of the pieces."""

    def __init__(self, grain, sensor):
        self.m2 = grain.mass
        self.rigid = sensor.is_rigid
        self.m1, self.k1, self.c1 = sensor.mass, sensor.stiffness, sensor.damping
        if not self.rigid:
            self.sensor_flow = linear_flow(
                [[0.0, 1.0], [-self.k1 / self.m1, -self.c1 / self.m1]],
                force_scales(self.k1, self.m1),
            )

    def contact_flow(self, k, c):
        """The :class:`~contactlab.solver.propagators.LinearFlow` of a linear contact branch."""
        scale = None
        if k > 0.0:
            scale = force_scales(k, self.m2)
            if not self.rigid:
                scale = force_scales(self.k1, self.m1) + scale
        return linear_flow(self.contact_matrix(k, c), scale)

    def contact_matrix(self, k, c):
        """System matrix under a contact force ``k d + c d' + f0`` (rigid: grain only;
        :func:`contactlab.kernels.rules.contact_matrix`)."""
        return contact_matrix(self.m1, self.k1, self.c1, self.m2, k, c, self.rigid)

    def rhs(self, force):
        """Right-hand side ``y' = f(y)`` for a contact force function of (d, d').

        The state is unpacked to Python floats and the law's formula evaluated on them
        (the ``_*_raw`` formulas of :mod:`contactlab.laws` take floats): one call costs
        about a microsecond, against ten for the same arithmetic through numpy scalars.
        """
        m1, m2, k1, c1 = self.m1, self.m2, self.k1, self.c1
        if self.rigid:

            def f(y):
                _, _, x2, v2 = y.tolist()
                return np.array([0.0, 0.0, v2, -force(x2, v2) / m2])

        else:

            def f(y):
                x1, v1, x2, v2 = y.tolist()
                s2 = force(x2 - x1, v2 - v1)
                return np.array([v1, (s2 - k1 * x1 - c1 * v1) / m1, v2, -s2 / m2])

        return f


def force_scales(stiffness, mass):
    """Scales ``(k, k / omega)`` that make a mass's displacement and velocity forces [N].

    ``k x`` and ``k v / omega`` (``omega = sqrt(k / m)``) are of one size in a
    spring-mass oscillation: the coordinates in which
    :class:`~contactlab.solver.propagators.LinearFlow` computes modes to full accuracy.
    """
    return (stiffness, stiffness / math.sqrt(stiffness / mass))


def overlap_rate(states):
    return states[:, 2] - states[:, 0], states[:, 3] - states[:, 1]


def event_directions(branch):
    """Crossing directions of a contact piece's events: contact end (the force falls to
    zero), then the branch's exits."""
    return [-1] + [e.direction for e in branch.exits]
