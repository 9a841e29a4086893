"""Sphere-sphere oblique impacts: tests 7 and 8 through the exact pair reduction.

Two free spheres meeting along a fixed normal are one sphere of mass ``m*`` on a rigid
plane with the pair's ``E*``, ``G*`` and ``R*`` (:mod:`contactlab.analytic.pair`): the
impact runs in :func:`contactlab.simulate_oblique` and each sphere's velocities follow
from its impulses (:func:`contactlab.analytic.pair_rebound`).

Axes: ``n`` from sphere 1 to sphere 2, ``t`` tangential, spins about ``n x t``; the contact
slips at ``s = (v1t - v2t) + R1 w1 + R2 w2``.
"""

import math

import numpy as np

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi.cases import TEST8_PARTNERS
from contactlab.benchmarks.chung_ooi.grading import grain, row
from contactlab.benchmarks.chung_ooi.oblique import (
    ANGLES,
    HISTORIES,
    closed_form_holds,
    contact_momentum,
    worst_momentum_row,
)
from contactlab.plausibility import internal

__all__ = ["pair_impact", "pair_spin_test", "unequal_pair_test"]


def _pair_laws(material1, radius1, material2, radius2, restitution, friction, history):
    """Equivalent sphere and laws: ``(grain, normal law, tangential law)``."""
    m1, m2 = grain(material1, radius1).mass, grain(material2, radius2).mass
    mass = analytic.effective_mass(m1, m2)
    radius = analytic.effective_radius(radius1, radius2)
    moduli = (
        material1.youngs_modulus,
        material1.poisson_ratio,
        material2.youngs_modulus,
        material2.poisson_ratio,
    )
    k_hertz = analytic.hertz_stiffness(analytic.effective_modulus(*moduli), radius)
    if restitution == 1.0:
        normal = cl.laws.Hertz(k_hertz)
    else:
        damping = analytic.tsuji_damping_coefficient(k_hertz, mass, restitution, "force")
        normal = cl.laws.HertzDamped(k_hertz, damping)
    k_mindlin = analytic.mindlin_stiffness_coefficient(
        analytic.effective_shear_modulus(*moduli), radius
    )
    tangential = cl.laws.Mindlin(k_mindlin, friction, history=history)
    with internal():  # the benchmark's 0.1 m spheres are no grains
        body = cl.Grain(diameter=2 * radius, mass=mass)
    return body, normal, tangential, (m1, m2)


def pair_impact(spheres, before, restitution, friction, history="total"):
    """Both spheres after an oblique impact (exact pair reduction).

    Parameters
    ----------
    spheres : ((Material, float), (Material, float))
        Each sphere's material and radius [m].
    before : contactlab.analytic.PairRebound
        Velocities before the impact; ``normal1 - normal2 > 0`` (approaching).
    restitution, friction : float
        Normal restitution (realised exactly) and Coulomb friction [-].
    history : {"total", "incremental"}
        Mindlin history form.

    Returns
    -------
    (PairRebound, ObliqueResult)
        The velocities after, and the equivalent sphere's impact.
    """
    (material1, radius1), (material2, radius2) = spheres
    body, normal, tangential, masses = _pair_laws(
        material1, radius1, material2, radius2, restitution, friction, history
    )
    vn = before.normal1 - before.normal2
    vt = before.tangential1 - before.tangential2
    spin = -(radius1 * before.spin1 + radius2 * before.spin2) / body.radius
    sign = -1.0 if vt < 0.0 else 1.0  # run with vt >= 0 (angle in [0, pi/2)), mirror back
    res = cl.simulate_oblique(
        body,
        cl.Sensor.rigid(),
        normal,
        tangential,
        math.hypot(vn, vt),
        math.atan2(abs(vt), vn),
        spin=sign * spin,
    )
    normal_impulse = body.mass * (vn + res.rebound_normal_velocity)
    tangential_impulse = sign * body.mass * (res.tangential_velocity - abs(vt))
    after = analytic.pair_rebound(
        masses, (radius1, radius2), before, normal_impulse, tangential_impulse
    )
    return after, res


def _slip(state, radii):
    return state.tangential1 - state.tangential2 + radii[0] * state.spin1 + radii[1] * state.spin2


def pair_spin_test(case, material):
    """Test 7: identical spheres, spins +w and -w: no slip, spins and vt unchanged."""
    radius, speed, mu, e = (
        case.inputs[k]
        for k in ("radius [m]", "speed of each sphere [m/s]", "friction [-]", "restitution")
    )
    rows, out = [], []
    for degrees in ANGLES:
        spin = speed / radius * math.tan(math.radians(degrees))
        before = analytic.PairRebound(speed, -speed, 0.0, 0.0, spin, -spin)
        after, _ = pair_impact(((material, radius), (material, radius)), before, e, mu)
        out.append((spin, after.spin1, after.tangential1))
        rows += [
            row(case, material, f"w1' at w = {spin:.4g} rad/s [rad/s]", after.spin1, spin),
            row(
                case,
                material,
                f"v1t' at w = {spin:.4g} rad/s [m/s]",
                after.tangential1,
                0.0,
                scale=radius * spin,
            ),
        ]
    rows.append(row(case, material, f"restitution for e = {e:g} [-]", -after.normal1 / speed, e))
    return rows, np.array(out)


def unequal_pair_test(case, material):
    """Test 8: sphere 1 spins onto a large, heavy sphere 2 at rest.

    Graded: the realised restitution; the equivalent sphere's angular momentum about the
    contact point (exact, worst angle); beta against gross sliding where that holds
    (:func:`~contactlab.benchmarks.chung_ooi.oblique.closed_form_holds`: not at test 8's
    e = 0.5, whose curves are drawn).
    """
    radius, radius2, vn, mu, e = (
        case.inputs[k]
        for k in (
            "radius [m]",
            "second radius [m]",
            "normal speed [m/s]",
            "friction [-]",
            "restitution",
        )
    )
    spheres = ((material, radius), (TEST8_PARTNERS[material.name], radius2))
    rows, curves = [], {}
    for history in HISTORIES:
        out, momenta = [], []
        for degrees in ANGLES:
            slip = vn * math.tan(math.radians(degrees))
            before = analytic.PairRebound(vn, 0.0, 0.0, 0.0, slip / radius, 0.0)
            after, res = pair_impact(spheres, before, e, mu, history)
            beta = -_slip(after, (radius, radius2)) / slip
            realised = res.restitution
            out.append((3.5 * mu * (1 + e) * vn / slip, beta))
            equivalent = (res.rebound_normal_velocity, res.tangential_velocity)
            momenta.append(
                (
                    contact_momentum(res.grain, (*equivalent, res.angular_velocity)),
                    contact_momentum(res.grain, (vn, 0.0, res.spin)),
                )
            )
            if closed_form_holds(e) and analytic.slides_throughout(
                analytic.ObliqueImpact(vn, 0.0, -slip / radius, radius, realised, mu)
            ):
                theory = 3.5 * mu * (1 + realised) * vn / slip - 1.0
                label = f"beta at tan = {slip / vn:.3g}, {history} [-]"
                rows.append(row(case, material, label, beta, theory))
        label = f"equivalent I w + m R vt after, worst angle, {history} [kg*m**2/s]"
        rows.append(worst_momentum_row(case, material, label, momenta))
        curves[history] = np.array(out)
    rows.append(row(case, material, f"restitution for e = {e:g} [-]", realised, e))
    return rows, curves
