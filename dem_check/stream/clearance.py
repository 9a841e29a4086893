"""Keeping a stream's insertions clear of the particles already in flight.

Every particle is placed on its free path (:mod:`dem_check.stream.feed`); a new one must
not overlap, at the later of the two insertions, any particle placed before it that has
not yet reached the plate. A particle is a sphere or, for straw, the capsule round its
spheres' centres (a segment of half-length ``half`` along ``axis``, which does not turn
in free flight) with its spheres' radius. :class:`Placed` keeps the placed particles in
arrays, so that a feed of thousands is checked in numpy rather than in a Python loop.
"""

import numpy as np

__all__ = ["CLEARANCE", "Placed", "segment_distances"]

CLEARANCE = 1.05
"""Smallest distance at insertion over the sum of radii [-]."""


def segment_distances(d, u, h, w, k):
    """Distances between the segment ``c + s u``, ``s`` in [-h, h], and the segments
    ``c0 + t w``, ``t`` in [-k, k], with ``d = c - c0`` (rows of ``d``, ``w``, ``k``;
    unit or zero ``u``, ``w``; Ericson 2005, Real-Time Collision Detection, 5.1.9: solve
    for ``s``, clamp, solve for ``t``, clamp, solve for ``s`` again, clamp)."""
    d, w, k = np.atleast_2d(d), np.atleast_2d(w), np.atleast_1d(k)
    b, c, e = w @ u, d @ u, np.einsum("ij,ij->i", w, d)
    denominator = 1.0 - b * b
    skew = denominator > 1e-12
    s = np.where(skew, np.clip((b * e - c) / np.where(skew, denominator, 1.0), -h, h), 0.0)
    t = np.clip(e + b * s, -k, k)
    s = np.clip(b * t - c, -h, h)
    return np.linalg.norm(d + s[:, None] * u - t[:, None] * w, axis=1)


class Placed:
    """The particles placed so far: insertion time ``t0`` [s], position and velocity
    there [m, m/s], shape ``(radius, axis, half)`` [m, -, m] and touch time [s]."""

    def __init__(self, capacity, gravity):
        self.count, self.gravity = 0, np.asarray(gravity, dtype=float)
        self.t0, self.t_aim = np.empty(capacity), np.empty(capacity)
        self.radius, self.half = np.empty(capacity), np.empty(capacity)
        self.x0, self.v0, self.axis = (np.empty((capacity, 3)) for _ in range(3))

    def add(self, t0, position, velocity, shape, t_aim):
        """Place one more particle."""
        n = self.count
        self.t0[n], self.x0[n], self.v0[n], self.t_aim[n] = t0, position, velocity, t_aim
        self.radius[n], self.axis[n], self.half[n] = shape
        self.count += 1

    def clear(self, position, velocity, shape, at):
        """Whether a particle inserted at ``position`` with ``velocity`` at time ``at``
        clears, at the later of the two insertions, every placed particle not yet at the
        plate (free paths under gravity)."""
        n, g = self.count, self.gravity
        when = np.maximum(at, self.t0[:n])
        live = self.t_aim[:n] > when
        if not live.any():
            return True
        when = when[live]
        a, b = (when - self.t0[:n][live])[:, None], (when - at)[:, None]
        other = self.x0[:n][live] + self.v0[:n][live] * a + 0.5 * g * a * a
        mine = position + velocity * b + 0.5 * g * b * b
        radius, axis, half = shape
        gap = segment_distances(mine - other, axis, half, self.axis[:n][live], self.half[:n][live])
        return bool((gap >= CLEARANCE * (radius + self.radius[:n][live])).all())
