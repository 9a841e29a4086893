"""Fixture: LAMMPS' granular update rules written out as a plain fixed-step integrator.

Velocity Verlet as ``fix nve/sphere`` does it (half kick, drift, forces from the half-step
velocities, half kick) with the tangential history of ``gran_sub_mod_tangential.cpp``:
increment by ``slip dt`` (``mindlin``, ``linear_history``) or ``-kt slip dt``
(``mindlin/force``), trial force, Coulomb rescaling of force and history. Independent of
contactlab's solver: it shares no code with it.
"""

import math

import pytest


def _lammps_rules(mass, radius, k_hertz, tangential, vn, vt, spin, steps):
    """Rebound ``(vn', vt', spin')`` of a sphere on a rigid flat, Hertz normal force.

    ``tangential`` is ``(kind, stiffness(d), mu)`` with kind "displacement" or "force".
    The step is the Hertz contact time over ``steps``.
    """
    kind, stiffness, mu = tangential
    inertia = 0.4 * mass * radius**2
    factor = 2.868266  # Hertz contact time constant (contact-laws note)
    t_c = factor * (mass**2 / (k_hertz**2 * 16.0 / 9.0 * vn)) ** 0.2
    dt = t_c / steps
    d, v, u, w, h = 0.0, vn, vt, spin, 0.0  # overlap, normal and tangential velocity, spin
    normal_force = tangential_force = 0.0
    touched = False
    while True:
        v -= 0.5 * dt * normal_force / mass
        u += 0.5 * dt * tangential_force / mass
        w -= 0.5 * dt * radius * tangential_force / inertia
        d += dt * v
        if d <= 0.0:
            if touched:
                return -v, u, w
            normal_force = tangential_force = 0.0
            continue
        touched = True
        normal_force = k_hertz * d**1.5
        slip = u - radius * w
        kt = stiffness(d)
        if kind == "force":
            h -= kt * slip * dt
            trial = h
        else:
            h += slip * dt
            trial = -kt * h
        cap = mu * normal_force
        if abs(trial) > cap:
            trial = math.copysign(cap, trial)
            h = trial if kind == "force" else -trial / kt
        tangential_force = trial
        v -= 0.5 * dt * normal_force / mass
        u += 0.5 * dt * tangential_force / mass
        w -= 0.5 * dt * radius * tangential_force / inertia


@pytest.fixture
def lammps_rules():
    """The function :func:`_lammps_rules`."""
    return _lammps_rules
