"""A fixed-step replica of Kratos' ``DEM_D_Hertz_viscous_Coulomb`` sphere-wall contact, with
each of its three hard-wired tangential rules switchable (issue 27).

Read from github.com/KratosMultiphysics/Kratos, ``applications/DEMApplication/``:

* ``custom_elements/spheric_particle.cpp``, ``ComputeBallToRigidFaceContactForceAndMoment``:
  the indentation ``d = R - dist``, the arm from the centre to the contact point
  ``-n dist = -n (R - d)`` (``actual_arm_vector``), the contact-point velocity ``v + w x
  arm`` (``tangential_vel``), the displacement increment ``DELTA_DISPLACEMENT`` plus the
  arm's change under the step's ``DELTA_ROTATION``, ``previous_indentation = d +
  LocalDeltDisp[2]``; the moment ``arm x F`` (``ComputeMomentsWithWalls``);
* ``custom_constitutive/DEM_D_Hertz_viscous_Coulomb_CL.cpp``: ``Kn = 2 E* sqrt(R d)``,
  ``Kt = 4 G* Kn / E*``, ``Fn = 2/3 Kn d - 2 gamma sqrt(m Kn) vn`` clipped at zero;
  ``CalculateTangentialForceWithNeighbour``: ``Fe = F_old - Kt ds``, rescaled ``F_old
  sqrt(d / d_prev) - Kt ds`` while ``d < d_prev``; the viscous ``Fv = -2 gamma sqrt(m Kt)
  s'``; the Coulomb limit on ``|Fe + Fv|`` with its four cases;
* the translational and rotational schemes ``Symplectic_Euler`` / ``Direct_Integration``:
  ``v += F/m dt``, ``x += v dt``, ``w += M/I dt``, ``DELTA_ROTATION = w dt``.

Switches (``Rules``), each one of the DEM codes' conventions (``docs/dem-conventions.md``):

* ``arm``: ``"R-d"`` (Kratos) or ``"R"`` (LAMMPS, contactlab) for the torque and the
  contact point's slip;
* ``history``: ``"rescaled"`` (Kratos; LAMMPS ``mindlin_rescale/force``),
  ``"incremental"`` (LAMMPS ``mindlin/force``, contactlab ``history="incremental"``) or
  ``"total"`` (LAMMPS ``mindlin``, contactlab ``history="total"``: ``F = -Kt xi`` with the
  total slip ``xi``, ``xi`` cut back to ``mu N / Kt`` in sliding);
* ``damping``: ``"tied"`` (Kratos: ``2 gamma sqrt(m Kt)``, ``gamma`` the normal one) or
  ``"none"``;
* ``cap``: ``"elastic"`` (Kratos' four Coulomb cases on the elastic and viscous parts) or
  ``"total"`` (LAMMPS: the total scaled to ``mu N``, the elastic part set to the rest).

The attribution of the differences rule by rule is the package's
(:mod:`contactlab.benchmarks.chung_ooi.attribution`, run by ``contactlab benchmark
chung-ooi --engines lammps,kratos``); this replica is the independent check of those
rules against Kratos' own arithmetic (``tests/dem_check/engines/kratos/test_rules.py``,
``tests/contactlab/solver/test_conventions.py``).
"""

import math
from dataclasses import dataclass

__all__ = ["KRATOS", "Rebound", "Rules", "replica"]


@dataclass(frozen=True)
class Rules:
    """Tangential conventions of a contact (see the module docstring)."""

    arm: str = "R-d"
    history: str = "rescaled"
    damping: str = "tied"
    cap: str = "elastic"


KRATOS = Rules()
"""Kratos' ``DEM_D_Hertz_viscous_Coulomb``."""


@dataclass(frozen=True)
class Rebound:
    """Velocities after the impact: normal (away) [m/s], tangential [m/s], spin [rad/s]."""

    rebound_normal_velocity: float
    tangential_velocity: float
    angular_velocity: float


def _total_coulomb(fe, fv, limit):
    """LAMMPS' cap: the total scaled to ``limit``, the viscous part kept and the elastic
    (stored) part set to the rest (``gran_sub_mod_tangential.cpp``)."""
    if abs(fe + fv) <= limit:
        return fe, fv
    return math.copysign(limit, fe + fv) - fv, fv


def _coulomb(fe, fv, limit):
    """Kratos' Coulomb cases on the tangential elastic ``fe`` and viscous ``fv`` (scalars)."""
    if abs(fe + fv) <= limit:
        return fe, fv
    if fe * fv >= 0.0:
        if abs(fe) > limit:
            return math.copysign(limit, fe), 0.0
        return fe, fv * (limit - abs(fe)) / abs(fv)
    if abs(fv) >= abs(fe):
        return fe, fv * (limit + abs(fe)) / abs(fv)
    return math.copysign(limit, fe), 0.0


def replica(
    mass, radius, k_hertz, k_mindlin, friction, gamma, velocity, angle, spin, dt, rules=KRATOS
):
    """One oblique impact on a rigid wall under ``rules``, stepped as Kratos steps it.

    Parameters
    ----------
    mass, radius : float
        The sphere [kg, m].
    k_hertz, k_mindlin : float
        ``kH`` (``Fn = kH d**1.5``) [N/m**1.5] and ``k_mindlin`` (``Kt = k_mindlin
        sqrt(d)``) [N/m**1.5].
    friction : float
        Coulomb coefficient [-].
    gamma : float
        Kratos' damping ratio ``DAMPING_GAMMA`` [-].
    velocity, angle, spin : float
        Impact speed [m/s], angle from the normal [rad], initial spin [rad/s].
    dt : float
        Time step [s].
    rules : Rules

    Returns
    -------
    Rebound
    """
    vn = velocity * math.cos(angle)
    vx, vz, w = velocity * math.sin(angle), -vn, spin
    z = radius + 3.5 * vn * dt
    dx = dz = dtheta = 0.0
    inertia = 0.4 * mass * radius * radius
    history = 0.0  # tangential elastic force (incremental forms) or total slip (total)
    touched = False
    while True:
        d = radius - z
        fx = fz = 0.0
        if d > 0.0:
            touched = True
            arm = radius - d if rules.arm == "R-d" else radius
            slip_rate = vx - w * arm
            ds = dx - arm * math.sin(dtheta)
            dn = dz - arm * (1.0 - math.cos(dtheta))
            kn = 1.5 * k_hertz * math.sqrt(d)
            kt = k_mindlin * math.sqrt(d)
            normal = k_hertz * d**1.5 - 2.0 * gamma * math.sqrt(mass * kn) * vz
            normal = max(normal, 0.0)
            ct = 2.0 * gamma * math.sqrt(mass * kt) if rules.damping == "tied" else 0.0
            fv = -ct * slip_rate
            if rules.history == "total":
                history += ds
                fe = -kt * history
            else:
                previous = d + dn
                old = (
                    history * math.sqrt(d / previous)
                    if (rules.history == "rescaled" and previous > d)
                    else history
                )
                fe = old - kt * ds
            cap = _coulomb if rules.cap == "elastic" else _total_coulomb
            fe, fv = cap(fe, fv, friction * normal)
            history = -fe / kt if rules.history == "total" else fe
            fx, fz = fe + fv, normal
            torque = -arm * fx
        else:
            if touched and vz > 0.0:
                return Rebound(vz, vx, w)
            history, torque = 0.0, 0.0
        vx += fx / mass * dt
        vz += fz / mass * dt
        w += torque / inertia * dt
        dx, dz, dtheta = vx * dt, vz * dt, w * dt
        z += dz
