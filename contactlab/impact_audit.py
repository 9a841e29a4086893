"""The audit of a normal impact (:meth:`contactlab.ImpactResult.audit`).

Over the first contact, from the touch to the first separation: the energy ledger of
:mod:`contactlab.audit` (no rotation, no friction) and the checks ``energy`` (and
``euler_step`` for the Euler method),
``one_sided`` (where the law has a force formula the solver follows: not the prescribed
trapezoid, not the Euler reference method, whose contact end is step-limited by
construction), ``damper``, ``momentum_normal`` and ``residual``.
"""

import math

import numpy as np

from contactlab.audit import Audit, Check, EnergyLedger, elastic_energy, energy_check, worst_of
from contactlab.quadrature import gauss_rule

__all__ = ["EULER_ENERGY", "audit_impact", "energy_tolerance"]

EXACT_ROUNDING = 1e-9
"""Tolerance [-] of the ``energy`` check of the exact solver (modal solutions and roots to
machine precision; measured <= 1e-13)."""

PULL_ROUNDING = 1e-8
"""Tolerance [-] of ``one_sided``, of the peak force: a branch formula such as
``k (d - d0)`` cancels digits where the overlap is large against the force (a 0.05 N force
cap flowing to 0.4 m of overlap: 1.7e-9, the worst measured over the matrix)."""

ADAPTIVE_ROUNDING = 100.0
"""``energy`` tolerance of the adaptive solver in units of its ``rtol``: the end states carry
its error, up to ``rtol`` per step (worst measured over the matrix: 28 rtol, elastic Hertz
on a sensor)."""

EULER_ENERGY = 1e-3
"""``energy`` tolerance [-] of the Euler reference method. Explicit Euler gains energy on a
contact: each step multiplies an oscillator's energy by ``1 + (omega dt)**2``, so a contact
of ``pi / omega`` gains about ``pi omega dt``: 1.4e-5 at the paper's step (1e-10 s) on its
hard grain (omega 4.5e4 rad/s), 1.4e-4 at a ten times coarser step (restitution within
1e-4). A step that creates 1e-3 of the impact energy is too coarse for a reference and is
reported, by the ``energy`` check where it shows, by ``euler_step`` (the same estimate
``pi**2 dt / t_c`` from the step and the contact time) where a damper hides it: a damped
contact at a step too coarse loses the wrong amount of energy instead (Kuwabara-Kono at
1e-6 s: e = 0.90 for 0.82)."""

QUADRATURE_TOLERANCE = 1e-7
"""Tolerance [-] of ``residual``, ``damper`` (of the impact energy) and ``momentum_normal``
(of ``m v0``): Gauss-Legendre on graded panels of the dense solution (measured <= 1e-9 on
exact and adaptive results)."""

EULER_QUADRATURE = 1e-3
"""The same for the Euler method, whose states are interpolated linearly between its
records and whose contact end is step-limited (first order in the step)."""


def energy_tolerance(result):
    """The ``energy`` tolerance [-] of a result's solver (see the constants above)."""
    if result.method == "euler":
        return EULER_ENERGY
    if result.method == "adaptive":
        return ADAPTIVE_ROUNDING * (result.rtol or 1e-10)
    return EXACT_ROUNDING


def audit_impact(result, full=True):
    """Energy ledger and invariants of an :class:`~contactlab.ImpactResult`.

    Parameters
    ----------
    result : contactlab.ImpactResult
        The impact.
    full : bool, default True
        With the ledger, the one-sided force on Gauss-Legendre nodes, the damper's work and
        the momentum balance; False: the ``energy`` check (and ``euler_step``) alone,
        what :func:`contactlab.simulate_impact` runs by default (one state evaluation).

    Returns
    -------
    contactlab.audit.Audit
        Without checks when the first contact has not ended in the window (the Euler
        method stops at the window's end).
    """
    sensor = result.sensor
    if not result.contact_intervals:  # an Euler window that ends inside the first contact
        return Audit(None, ())
    start, end = result.contact_intervals[0]
    final = result._at(end)[0][0]
    m2 = result.grain.mass
    with np.errstate(over="ignore", invalid="ignore"):  # an overflowed state reads as inf
        ledger = EnergyLedger(
            kinetic_in=0.5 * m2 * result.velocity**2,
            translation_out=0.5 * m2 * final[3] ** 2,
            sensor_left=sensor.energy(final[0], final[1]),
        )
    energy_in = ledger.kinetic_in
    prescribed = (
        "a prescribed force pulse ignores the bodies' motion: on a sensor lighter than the "
        "grain its impulse m v0 leaves the plate more energy than came in"
        if result.law.prescribed
        else ""
    )
    checks = [energy_check(ledger, energy_tolerance(result), prescribed)]
    if result.method == "euler":
        checks.append(
            Check(
                "euler_step",
                math.pi**2 * result.time_step / (end - start),
                EULER_ENERGY,
                "impact energy (explicit Euler's gain on an undamped contact this long)",
            )
        )
    if not full:
        return Audit(None, tuple(checks))
    work = result._integrate(lambda st, f: f * (st[:, 3] - st[:, 1]), start, end)
    left = elastic_energy(result.law, final[2] - final[0])
    ledger = EnergyLedger(
        kinetic_in=energy_in,
        translation_out=ledger.translation_out,
        sensor_left=ledger.sensor_left,
        sensor_damper=0.0
        if sensor.is_rigid
        else result._integrate(lambda st, f: sensor.damping * st[:, 1] ** 2, start, end),
        normal_damper=work - left,
        normal_elastic_left=left,
    )
    impulse = result._integrate(lambda st, f: f, start, end)
    momentum = m2 * result.velocity
    tolerance = EULER_QUADRATURE if result.method == "euler" else QUADRATURE_TOLERANCE
    one_sided = _one_sided(result, start, end)
    checks += [] if one_sided is None else [one_sided]
    checks += [
        Check(
            "damper",
            -ledger.normal_damper / energy_in,
            tolerance,
            "impact energy",
            math.nan,
            prescribed,
        ),
        Check(
            "momentum_normal",
            abs(impulse - m2 * (result.velocity - final[3])) / momentum,
            tolerance,
            "impact momentum m v0",
        ),
        Check("residual", abs(ledger.residual) / energy_in, tolerance, "impact energy"),
    ]
    return Audit(ledger, tuple(checks))


def _one_sided(result, start, end):
    """Worst pull of the law's unclipped branch formula over the first contact, on
    Gauss-Legendre nodes of its contact segments; None where the solver follows no
    formula (Euler, the prescribed trapezoid)."""
    law = result.law
    if result.method == "euler" or law.prescribed:
        return None
    worst, max_overlap = [], 0.0
    for seg in result.segments:
        if seg.kind != "contact" or seg.t1 <= start or seg.t0 >= end:
            continue
        branch = law.branch(seg.branch, max_overlap)
        # inside the segment only: its end is the root where the force reached zero, taken
        # on its crossed side (roots.crossed_side), a rounding below zero by design
        nodes, _ = gauss_rule(seg.t0, seg.t1, graded=True, graded_end=True)
        st = seg.states(nodes - seg.t0)
        d, r = st[:, 2] - st[:, 0], st[:, 3] - st[:, 1]
        if branch.loading:
            max_overlap = max(max_overlap, float(d.max()))
        pull = -np.asarray(branch.force(d, r), dtype=float) / result.peak_contact_force
        worst.append(worst_of(np.where(d >= 0.0, pull, -math.inf), nodes))
    if not worst:
        return None
    value, at = max(worst)
    return Check("one_sided", value, PULL_ROUNDING, "peak contact force", at)
