"""Audits of engine results: the invariants of :mod:`contactlab.audit` on an engine's steps.

An engine (pybullet, LAMMPS) records one sample per step; its result is audited like the
reduced model's (:meth:`contactlab.ImpactResult.audit`), over the first contact, with
tolerances set by the engine's step instead of a solver tolerance:

* ``energy``: the grain's kinetic energy and the sensor's energy at the end of the first
  contact against the impact energy. Velocity Verlet (both engines) keeps an oscillator's
  energy to ``(omega dt)**2``; the tolerance is ten times ``(pi dt / t_c)**2`` (the contact
  a half period) plus the end state's interpolation between two steps.
* ``one_sided``: the most tensile contact force over the contact's steps, of the peak
  (tolerance 1e-12: an engine whose force pulls is reported, whatever the step).
* ``momentum_normal``: the engine's contact impulse ``sum dt S2`` over the first contact
  against the grain's momentum change, of ``m v0``; a step's share of the impulse (two
  steps at the peak force) is the tolerance.

:func:`audit_oblique_rebound` audits an oblique rebound from its velocities alone (LAMMPS'
:class:`~dem_check.engines.lammps.oblique.LammpsOblique`): energy, angular momentum about
the contact point, and Coulomb's inequality integrated over the contact
(``|J_t| <= mu J_n``, which any capped force obeys).
"""

import math

import numpy as np

from contactlab.audit import Audit, Check, EnergyLedger, energy_check
from contactlab.oblique_result import MINDLIN_ENERGY

__all__ = ["audit_engine", "audit_oblique_rebound"]

STEP_ENERGY = 10.0
"""``energy`` tolerance in units of ``(pi dt / t_c)**2`` (velocity Verlet's energy error on a
half period of contact)."""

PULL_ROUNDING = 1e-12
"""``one_sided`` tolerance [-] of the peak force."""

REBOUND_ROUNDING = 1e-9
"""Tolerance [-] of the rebound checks of :func:`audit_oblique_rebound` (velocities read
back in double precision; the engine's own step error enters the energy, whose
tolerance is set by the step)."""


def audit_engine(result):
    """Energy, one-sided force and momentum of an engine's first contact.

    Parameters
    ----------
    result : dem_check.engines.EngineResult
        An engine's drop test.

    Returns
    -------
    contactlab.audit.Audit
        Without checks when the first contact has not ended in the record.
    """
    if not result.contact_intervals or not np.isfinite(result.contact_intervals[0][1]):
        return Audit(None, ())
    start, end = result.contact_intervals[0]
    t, dt = result.t, result.time_step
    m2, v0, sensor = result.grain.mass, result.velocity, result.sensor
    v1, v2, x1 = (float(np.interp(end, t, a)) for a in (result.v1, result.v2, result.x1))
    ledger = EnergyLedger(
        kinetic_in=0.5 * m2 * v0**2,
        translation_out=0.5 * m2 * v2**2,
        sensor_left=0.0
        if sensor.is_rigid
        else 0.5 * sensor.mass * v1**2 + 0.5 * sensor.stiffness * x1**2,
    )
    inside = (t >= start) & (t <= end)
    force = result.contact_force[inside]
    peak = float(force.max())
    slope_share = 2.0 * dt * peak / (m2 * v0)
    energy_tolerance = STEP_ENERGY * (math.pi * dt / (end - start)) ** 2 + 2.0 * slope_share
    pull = float((-force / peak).max())
    impulse = dt * float(force.sum())
    checks = (
        energy_check(ledger, energy_tolerance),
        Check(
            "one_sided",
            pull,
            PULL_ROUNDING,
            "peak contact force",
            float(t[inside][np.argmax(-force)]),
        ),
        Check(
            "momentum_normal",
            abs(impulse - m2 * (v0 - v2)) / (m2 * v0),
            slope_share,
            "impact momentum m v0",
        ),
    )
    return Audit(ledger, checks)


def audit_oblique_rebound(
    grain,
    tangential_law,
    velocity,
    angle,
    spin,
    rebound,
    *,
    energy_tolerance=REBOUND_ROUNDING,
    inertia_factor=0.4,
):
    """Audit an oblique rebound from its velocities: energy, angular momentum, Coulomb.

    Parameters
    ----------
    grain : contactlab.Grain
        The grain.
    tangential_law : contactlab.laws.TangentialLaw
        Its friction coefficient bounds the impulse ratio; a Mindlin law may gain energy
        (:data:`contactlab.oblique_result.MINDLIN_ENERGY`).
    velocity, angle, spin : float
        Impact speed [m/s], incidence [rad] and spin [rad/s] (signs of
        :func:`contactlab.simulate_oblique`).
    rebound : (float, float, float)
        Rebound normal speed away from the wall [m/s], tangential velocity [m/s], spin
        [rad/s].
    energy_tolerance : float, default 1e-9
        Tolerance of the ``energy`` check [-] (the engine's step error).
    inertia_factor : float, default 0.4
        ``I / (m R**2)`` [-].

    Returns
    -------
    contactlab.audit.Audit
    """
    m, radius = grain.mass, grain.radius
    inertia = inertia_factor * m * radius**2
    vn, vt = velocity * math.cos(angle), velocity * math.sin(angle)
    out_n, out_t, out_w = rebound
    ledger = EnergyLedger(
        kinetic_in=0.5 * m * velocity**2 + 0.5 * inertia * spin**2,
        translation_out=0.5 * m * (out_n**2 + out_t**2),
        rotation_out=0.5 * inertia * out_w**2,
    )
    normal_impulse = m * (vn + out_n)
    tangential_impulse = m * (out_t - vt)
    change = inertia * (out_w - spin) + m * radius * (out_t - vt)
    checks = (
        energy_check(
            ledger, energy_tolerance, MINDLIN_ENERGY if tangential_law.name == "mindlin" else ""
        ),
        Check(
            "momentum_angular",
            abs(change) / (m * velocity * radius),
            REBOUND_ROUNDING,
            "m V R (angular momentum about the contact point)",
        ),
        Check(
            "coulomb_impulse",
            (abs(tangential_impulse) - tangential_law.friction * normal_impulse) / (m * velocity),
            REBOUND_ROUNDING,
            "impact momentum m V (|J_t| - mu J_n)",
        ),
    )
    return Audit(ledger, checks)
