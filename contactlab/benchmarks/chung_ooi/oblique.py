"""Oblique impacts on a rigid plane: tests 4, 5 and 6, both Mindlin history forms.

Graded where theory is exact: in gross sliding (the contact point slides one way for the
whole impact, :func:`contactlab.analytic.slides_throughout`) the tangential impulse is
``mu`` times the normal one (:func:`contactlab.analytic.gross_sliding_rebound`). Below
the sliding limit no closed form exists (Maw et al. 1976 solved it numerically): the
curves are drawn, not graded. When a LAMMPS runner is given, it runs every impact too.
"""

import math

import numpy as np

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi import attribution
from contactlab.benchmarks.chung_ooi.grading import engine_row, grain, rebound, row
from contactlab.solver.conventions import DEM_CONVENTIONS

__all__ = [
    "ANGLES",
    "HISTORIES",
    "closed_form_holds",
    "contact_momentum",
    "impact",
    "oblique_test",
    "spin_test",
    "tangential_speed_test",
    "worst_momentum_row",
]

ANGLES = tuple(range(5, 90, 5))
"""Incidence angles [deg] (5-85, as Chung & Ooi and Kratos' 17 points)."""

HISTORIES = ("total", "incremental")
"""The Mindlin history forms run (LAMMPS ``mindlin`` and ``mindlin/force``)."""


def impact(body, normal, law, velocity, angle, spin, lammps):
    """contactlab's rebound on a rigid plane, and LAMMPS' when ``lammps`` is given.

    Returns
    -------
    (tuple, tuple or None)
        ``rebound(...)`` of each: normal speed away, tangential velocity, spin.
    """
    ours = cl.simulate_oblique(body, cl.Sensor.rigid(), normal, law, velocity, angle, spin=spin)
    theirs = None
    if lammps is not None:
        theirs = rebound(lammps(body, normal, law, velocity, angle, spin=spin))
    return rebound(ours), theirs


def _drop(case, material):
    """Test 5's or 6's sphere, its normal law and inputs: ``(body, normal, (radius [m],
    normal speed [m/s], friction [-], restitution [-]))``."""
    radius, vn, mu, e = (
        case.inputs[k] for k in ("radius [m]", "normal speed [m/s]", "friction [-]", "restitution")
    )
    body = grain(material, radius)
    return body, _elastic_or_damped(body, e), (radius, vn, mu, e)


def _elastic_or_damped(body, restitution):
    k_hertz = cl.laws.Hertz.from_material(body.material()).k_hertz
    if restitution == 1.0:
        return cl.laws.Hertz(k_hertz)
    damping = analytic.tsuji_damping_coefficient(k_hertz, body.mass, restitution, "force")
    return cl.laws.HertzDamped(k_hertz, damping)


def closed_form_holds(restitution):
    """Whether gross sliding's closed form holds throughout for a normal restitution.

    With an elastic normal force the trial force of both Mindlin forms reaches ``mu N``
    at the touch (their ratio is constant in time there) and a contact with enough slip
    slides throughout. A damped normal force jumps at the touch (``N ~ t**0.25``) while
    the tangential force grows from zero (``~ t**1.5``): the contact sticks first (0.6 %
    to 8 % of it in test 6), the impulse ratio falls short of ``mu`` (0.390 for 0.4 at
    65 deg, incremental form) and the closed form does not apply. LAMMPS does the same
    (its history starts at zero at the touch); those numbers are graded against LAMMPS.
    """
    return restitution == 1.0


def contact_momentum(body, result):
    """Angular momentum about the contact point ``I w + m R vt`` [kg*m**2/s] after.

    Conserved by any force at the contact point: ``m vt' = F`` and ``I w' = -R F``.
    """
    radius = body.radius
    return 0.4 * body.mass * radius**2 * result[2] + body.mass * radius * result[1]


def worst_momentum_row(case, material, label, momenta):
    """The graded row of the angular momentum about the contact point at the angle where
    it moved most: ``momenta`` holds ``(after, before)`` [kg*m**2/s] per angle."""
    after, before = max(momenta, key=lambda m: abs(m[0] - m[1]) / abs(m[1]))
    return row(case, material, label, after, before)


def _value(result, index):
    return None if result is None else result[index]


_LAMMPS_RULES = {"total": "lammps_mindlin", "incremental": "lammps_mindlin_force"}
"""LAMMPS' run of each history form: the preset of its keyword (``mindlin``,
``mindlin/force``)."""


def oblique_test(case, material, lammps=None, reported=None):
    """Test 4: constant speed, incidence 5-85 deg; vt' graded in gross sliding.

    ``reported``: ``{engine: oblique}`` run at every angle (once: an engine's own
    tangential rules take no history form) and reported beside, not graded (Kratos,
    ``docs/dem-conventions.md``), in the gross-sliding rows.

    ``curves[history]``: (17, 4) ``vt'/vt`` and ``R w'/vt`` of contactlab, then of LAMMPS
    (NaN when not run), at each angle.

    Every engine run (each reported engine with a preset in :data:`DEM_CONVENTIONS`, and
    LAMMPS' ``mindlin`` and ``mindlin/force``) is then attributed rule by rule
    (:mod:`~contactlab.benchmarks.chung_ooi.attribution`): contactlab with all of the
    engine's rules is graded against it at every angle (rows "..., <engine>
    conventions"), and ``curves["attribution"]`` holds each
    :class:`~contactlab.benchmarks.chung_ooi.attribution.Attribution`.
    """
    radius, speed, mu = (case.inputs[k] for k in ("radius [m]", "speed [m/s]", "friction [-]"))
    body = grain(material, radius)
    normal = cl.laws.Hertz.from_material(body.material())
    rows, curves, others, lammps_runs = [], {}, {}, {}
    for history in HISTORIES:
        law = cl.laws.Mindlin.from_material(body.material(), mu, history=history)
        out = []
        for degrees in ANGLES:
            angle = math.radians(degrees)
            vn, vt = speed * math.cos(angle), speed * math.sin(angle)
            ours, theirs = impact(body, normal, law, speed, angle, 0.0, lammps)
            lammps_runs[history, degrees] = theirs
            for name, oblique in (reported or {}).items():
                if (name, degrees) not in others:
                    others[name, degrees] = rebound(oblique(body, normal, law, speed, angle))
            out.append(
                (
                    ours[1] / vt,
                    radius * ours[2] / vt,
                    _value(theirs, 1) / vt if theirs else math.nan,
                    radius * _value(theirs, 2) / vt if theirs else math.nan,
                )
            )
            e = min(ours[0] / vn, 1.0)  # elastic: 1 to ~1e-9
            rigid = analytic.ObliqueImpact(vn, vt, 0.0, radius, e, mu)
            if analytic.slides_throughout(rigid):
                theory = analytic.gross_sliding_rebound(rigid)[0]
                rows.append(
                    row(
                        case,
                        material,
                        f"vt' at {degrees} deg, {history} [m/s]",
                        ours[1],
                        theory,
                        lammps=_value(theirs, 1),
                        engines={
                            name: (others[name, degrees][1], False) for name in reported or {}
                        },
                    )
                )
        curves[history] = np.array(out)
    runs = {  # label -> (engine column, rules, rebound at each angle)
        name: (name, DEM_CONVENTIONS[name], [others[name, a] for a in ANGLES])
        for name in reported or {}
        if name in DEM_CONVENTIONS
    }
    if lammps is not None:
        for history, preset in _LAMMPS_RULES.items():
            label = preset.replace("_", " ", 1).replace("_", "/")
            runs[label] = (
                "lammps",
                DEM_CONVENTIONS[preset],
                [lammps_runs[history, a] for a in ANGLES],
            )
    mindlin = cl.laws.Mindlin.from_material(body.material(), mu)
    curves["attribution"] = []
    for label, (column, rules, rebounds) in runs.items():
        found = attribution.attribute(
            body, material.name, normal, mindlin, speed, ANGLES, label, rebounds, rules
        )
        curves["attribution"].append(found)
        rows += attribution.graded_rows(case, material, found, column)
    return rows, curves


def tangential_speed_test(case, material, lammps=None):
    """Test 5: normal speed fixed, vt = vn tan(theta); psi2 and R w'/(mu vn) graded.

    ``psi1 = vt / (mu vn)``, ``psi2 = slip' / (mu vn')`` (Maw et al.'s normalised incident
    and recoil angles of the contact point) and ``Omega = R w' / (mu vn)`` (Chung & Ooi
    plot ``-Omega``: their spin axis is the opposite one).
    """
    body, normal, (radius, vn, mu, _) = _drop(case, material)
    rows, curves = [], {}
    for history in HISTORIES:
        law = cl.laws.Mindlin.from_material(body.material(), mu, history=history)
        out = []
        for degrees in ANGLES:
            angle = math.radians(degrees)
            vt = vn * math.tan(angle)
            ours, theirs = impact(body, normal, law, vn / math.cos(angle), angle, 0.0, lammps)

            def normalised(result):
                if result is None:
                    return math.nan, math.nan
                vn_after, vt_after, spin_after = result
                psi2 = (vt_after - radius * spin_after) / (mu * vn_after)
                return psi2, radius * spin_after / (mu * vn)

            psi2, omega = normalised(ours)
            out.append((vt / (mu * vn), psi2, omega, *normalised(theirs)))
            realised = min(ours[0] / vn, 1.0)
            rigid = analytic.ObliqueImpact(vn, vt, 0.0, radius, realised, mu)
            if analytic.slides_throughout(rigid):
                vt_th, spin_th = analytic.gross_sliding_rebound(rigid)
                psi2_th = (vt_th - radius * spin_th) / (mu * realised * vn)
                lam_psi2, lam_omega = normalised(theirs) if theirs else (None, None)
                label = f"at psi1 = {vt / (mu * vn):.4g}, {history}"
                rows += [
                    row(case, material, f"psi2 {label} [-]", psi2, psi2_th, lammps=lam_psi2),
                    row(
                        case,
                        material,
                        f"R w'/(mu vn) {label} [-]",
                        omega,
                        radius * spin_th / (mu * vn),
                        lammps=lam_omega,
                    ),
                ]
        curves[history] = np.array(out)
    return rows, curves


def spin_test(case, material, lammps=None):
    """Test 6: a spinning sphere dropped on the plane (no centre tangential velocity).

    Graded: the realised restitution; the angular momentum about the contact point
    (exact for any contact force; worst of the angles); beta against gross sliding where
    that holds (:func:`closed_form_holds`), else against LAMMPS when it ran.
    """
    body, normal, (radius, vn, mu, e) = _drop(case, material)
    rows, curves = [], {}
    for history in HISTORIES:
        law = cl.laws.Mindlin.from_material(body.material(), mu, history=history)
        out, momenta = [], []
        for degrees in ANGLES:
            slip = vn * math.tan(math.radians(degrees))
            spin = -slip / radius
            ours, theirs = impact(body, normal, law, vn, 0.0, spin, lammps)

            def beta(result, slip=slip):
                return math.nan if result is None else -(result[1] - radius * result[2]) / slip

            realised = ours[0] / vn
            out.append((3.5 * mu * (1 + e) * vn / slip, beta(ours), beta(theirs)))
            before = contact_momentum(body, (vn, 0.0, spin))
            momenta.append((contact_momentum(body, ours), before))
            label = f"beta at tan = {slip / vn:.3g}, {history} [-]"
            if closed_form_holds(e) and analytic.slides_throughout(
                analytic.ObliqueImpact(vn, 0.0, spin, radius, realised, mu)
            ):
                theory = 3.5 * mu * (1 + realised) * vn / slip - 1.0
                lam = beta(theirs) if theirs else None
                rows.append(row(case, material, label, beta(ours), theory, lammps=lam))
            elif theirs is not None:
                rows.append(engine_row(case, material, label, beta(ours), beta(theirs), 1.0))
        label = f"I w + m R vt after, worst angle, {history} [kg*m**2/s]"
        rows.append(worst_momentum_row(case, material, label, momenta))
        curves[history] = np.array(out)
    rows.append(row(case, material, f"restitution for e = {e:g} [-]", realised, e))
    return rows, curves
