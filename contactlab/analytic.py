"""Closed-form results for one normal impact on a flat or a second body.

These are the reference values the solvers, metrics and calibration tools are tested
against: contact time, peak overlap and force, and coefficient of restitution of the
contact laws in :mod:`contactlab.laws`, plus a few helpers for sensors and time steps.

Conventions
-----------
SI units throughout. The overlap ``d > 0`` in compression; the contact force is ``>= 0``.
``mass`` is the effective mass ``m* = 1/(1/m1 + 1/m2)`` (for a grain on an immovable flat:
the grain mass); radius and modulus are the effective ones likewise (:func:`effective_mass`,
:func:`effective_radius`, :func:`effective_modulus`). ``velocity`` is the normal impact speed.

Damped laws need a rule for when contact ends; ``convention`` selects it:

``"overlap"``
    Contact ends when the overlap returns to zero. The damper may pull (tensile force)
    near the end. This is the textbook result and the one most DEM mappings assume.
``"force"``
    Contact ends when the force returns to zero; the force is never tensile. This is what
    a one-sided contact does and what :func:`contactlab.simulate_impact` computes. It gives
    a shorter contact and a larger restitution than ``"overlap"``.

Functions take scalars and return floats; bad input raises
:class:`contactlab.errors.ParameterError` naming the parameter.
"""

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import beta, gamma

from contactlab.errors import ParameterError
from contactlab.validation import check_choice, check_number

__all__ = [
    "CONVENTIONS",
    "HERTZ_TIME_FACTOR",
    "KUWABARA_KONO_C1",
    "KUWABARA_KONO_C2",
    "KUWABARA_KONO_MAX_PARAMETER",
    "damping_ratio",
    "effective_mass",
    "effective_modulus",
    "effective_radius",
    "half_sine_residual_amplitude",
    "hertz_contact_time",
    "hertz_max_force",
    "hertz_max_overlap",
    "hertz_stiffness",
    "hunt_crossley_restitution",
    "hunt_crossley_restitution_linearised",
    "kuwabara_kono_parameter",
    "kuwabara_kono_restitution",
    "linear_contact_time",
    "linear_damping_from_restitution",
    "linear_plastic_contact_time",
    "linear_plastic_restitution",
    "linear_plastic_yield_velocity",
    "linear_restitution",
    "plastic_trapezoid_amplitude",
    "rayleigh_time",
    "thornton_restitution",
    "thornton_yield_force",
    "thornton_yield_overlap",
    "thornton_yield_velocity",
    "tsuji_damping_coefficient",
    "tsuji_damping_factor",
    "tsuji_restitution",
    "walton_braun_contact_time",
    "walton_braun_restitution",
    "youngs_from_shear",
]

#: Contact-end conventions accepted by the ``convention`` arguments.
CONVENTIONS = ("overlap", "force")

#: Hertz contact time in units of d_max / v: 2 * integral_0^1 du / sqrt(1 - u^(5/2)).
HERTZ_TIME_FACTOR = 2.0 * math.sqrt(math.pi) * gamma(7 / 5) / gamma(9 / 10)

#: First two coefficients of the Kuwabara-Kono restitution series (Ramirez et al. 1999).
KUWABARA_KONO_C1 = 0.8 * 1.25**0.6 * beta(3 / 5, 3 / 2)
KUWABARA_KONO_C2 = 0.6 * KUWABARA_KONO_C1**2

#: Largest Kuwabara-Kono parameter accepted: the two-term series has its minimum there.
KUWABARA_KONO_MAX_PARAMETER = KUWABARA_KONO_C1 / (2.0 * KUWABARA_KONO_C2)


# --- input checks shared by the functions below -------------------------------------------


def _positive(name, value, unit):
    return check_number(name, value, low=0.0, unit=unit)


def _non_negative(name, value, unit):
    return check_number(name, value, low=0.0, low_open=False, unit=unit)


def _poisson(name, value):
    return check_number(name, value, low=-1.0, high=0.5, unit="-")


def _restitution(value):
    return check_number("restitution", value, low=0.0, high=1.0, unit="-")


def _convention(value):
    return check_choice("convention", value, CONVENTIONS)


# --- material helpers -----------------------------------------------------------------------


def effective_mass(mass, other_mass=math.inf):
    """Effective (reduced) mass of a two-body contact.

    Parameters
    ----------
    mass : float
        Mass of the first body [kg].
    other_mass : float, default inf
        Mass of the second body [kg]; ``inf`` for an immovable wall.

    Returns
    -------
    float
        Effective mass m* [kg].

    Notes
    -----
    m* = 1 / (1/m1 + 1/m2); m* = m1 against an immovable wall.
    """
    m1 = _positive("mass", mass, "kg")
    m2 = check_number("other_mass", other_mass, low=0.0, unit="kg", allow_inf=True)
    return 1.0 / (1.0 / m1 + 1.0 / m2)


def effective_radius(radius, other_radius=math.inf):
    """Effective radius of curvature of a contact between two convex bodies.

    Parameters
    ----------
    radius : float
        Radius of the first body [m].
    other_radius : float, default inf
        Radius of the second body [m]; ``inf`` for a flat.

    Returns
    -------
    float
        Effective radius R* [m].

    Notes
    -----
    R* = 1 / (1/R1 + 1/R2); R* = R1 against a flat.
    """
    r1 = _positive("radius", radius, "m")
    r2 = check_number("other_radius", other_radius, low=0.0, unit="m", allow_inf=True)
    return 1.0 / (1.0 / r1 + 1.0 / r2)


def effective_modulus(
    youngs_modulus, poisson_ratio, other_youngs_modulus=math.inf, other_poisson_ratio=0.0
):
    """Effective (contact) modulus of two elastic bodies.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus of the first body [Pa].
    poisson_ratio : float
        Poisson's ratio of the first body, in (-1, 0.5] [-].
    other_youngs_modulus : float, default inf
        Young's modulus of the second body [Pa]; ``inf`` for a rigid flat.
    other_poisson_ratio : float, default 0.0
        Poisson's ratio of the second body [-]; irrelevant for a rigid body.

    Returns
    -------
    float
        Effective modulus E* [Pa].

    Notes
    -----
    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, so E* = E1/(1 - nu1^2) against a rigid flat
    (Johnson 1985, Sec. 4.2).

    References
    ----------
    .. [1] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985.
       DOI: 10.1017/CBO9781139171731
    """
    e1 = _positive("youngs_modulus", youngs_modulus, "Pa")
    nu1 = _poisson("poisson_ratio", poisson_ratio)
    e2 = check_number(
        "other_youngs_modulus", other_youngs_modulus, low=0.0, unit="Pa", allow_inf=True
    )
    nu2 = _poisson("other_poisson_ratio", other_poisson_ratio)
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


def hertz_stiffness(effective_modulus, effective_radius):
    """Hertz contact stiffness kH in F = kH d^(3/2).

    Parameters
    ----------
    effective_modulus : float
        Effective modulus E* [Pa].
    effective_radius : float
        Effective radius R* [m].

    Returns
    -------
    float
        kH [N/m^1.5].

    Notes
    -----
    kH = (4/3) E* sqrt(R*).

    References
    ----------
    .. [1] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, Eq. (4.22).
    """
    e = _positive("effective_modulus", effective_modulus, "Pa")
    r = _positive("effective_radius", effective_radius, "m")
    return 4.0 / 3.0 * e * math.sqrt(r)


def youngs_from_shear(shear_modulus, poisson_ratio):
    """Young's modulus of an isotropic material from its shear modulus.

    Parameters
    ----------
    shear_modulus : float
        Shear (Kirchhoff) modulus G [Pa].
    poisson_ratio : float
        Poisson's ratio, in (-1, 0.5] [-].

    Returns
    -------
    float
        Young's modulus E = 2 G (1 + nu) [Pa].
    """
    g = _positive("shear_modulus", shear_modulus, "Pa")
    nu = _poisson("poisson_ratio", poisson_ratio)
    return 2.0 * g * (1.0 + nu)


# --- Hertz elastic --------------------------------------------------------------------------


def hertz_max_overlap(k_hertz, mass, velocity):
    """Largest overlap of an elastic Hertz impact.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5] (:func:`hertz_stiffness`).
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        d_max [m].

    Notes
    -----
    Energy balance m v^2 / 2 = (2/5) kH d_max^(5/2) gives
    d_max = (5 m v^2 / (4 kH))^(2/5) = (15 m v^2 / (16 E* sqrt(R*)))^(2/5).

    References
    ----------
    .. [1] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, Sec. 11.1.
    """
    k = _positive("k_hertz", k_hertz, "N/m^1.5")
    m = _positive("mass", mass, "kg")
    v = _positive("velocity", velocity, "m/s")
    return (1.25 * m * v**2 / k) ** 0.4


def hertz_max_force(k_hertz, mass, velocity):
    """Peak force of an elastic Hertz impact.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        F_max = kH d_max^(3/2) [N], with d_max from :func:`hertz_max_overlap`.
    """
    return k_hertz * hertz_max_overlap(k_hertz, mass, velocity) ** 1.5


def hertz_contact_time(k_hertz, mass, velocity):
    """Duration of an elastic Hertz impact.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        Contact time t_c [s].

    Notes
    -----
    With u = d/d_max the speed is v sqrt(1 - u^(5/2)), so

    t_c = 2 (d_max/v) integral_0^1 du / sqrt(1 - u^(5/2))
        = 2 sqrt(pi) Gamma(7/5) / Gamma(9/10) * d_max / v = 2.943275 d_max / v
        = 2.868266 (m*^2 / (R* E*^2 v))^(1/5).

    The grain of the reference paper (E = 2 * 9 MPa * 1.2, nu = 0.2, 765 kg/m^3, rigid
    flat, v = 2 m/s) gives 180.6 us for a 5.0 mm diameter and 90.3 us for 2.5 mm.

    References
    ----------
    .. [1] H. Hertz, "Ueber die Beruehrung fester elastischer Koerper", J. reine angew.
       Math. 92, 156-171 (1882). DOI: 10.1515/crll.1882.92.156
    .. [2] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, Eq. (11.24).
    """
    d_max = hertz_max_overlap(k_hertz, mass, velocity)
    return HERTZ_TIME_FACTOR * d_max / velocity


# --- linear spring-dashpot ------------------------------------------------------------------


def _linear_overlap_convention(zeta):
    """Return (w0 * t_c, ln e) when contact ends at zero overlap."""
    if zeta >= 1.0:
        return math.inf, -math.inf
    root = math.sqrt((1.0 - zeta) * (1.0 + zeta))
    return math.pi / root, -math.pi * zeta / root


def _linear_force_convention(zeta):
    """Return (w0 * t_c, ln e) when contact ends at zero force (x'' = 0).

    Underdamped: angle = arccos(zeta), root = sqrt(1 - zeta^2); overdamped: the analytic
    continuation angle = arccosh(zeta), root = sqrt(zeta^2 - 1). Then w0 t_c = 2 angle / root
    and ln e = -2 angle zeta / root in both regimes; both tend to 2 and -2 at zeta = 1.
    """
    if zeta == 1.0:
        return 2.0, -2.0
    if zeta < 1.0:
        angle = math.acos(zeta)
        root = math.sqrt((1.0 - zeta) * (1.0 + zeta))
    else:
        angle = math.acosh(zeta)
        root = math.sqrt(zeta - 1.0) * math.sqrt(zeta + 1.0)
    return 2.0 * angle / root, -2.0 * angle * zeta / root


_LINEAR_SOLUTIONS = {"overlap": _linear_overlap_convention, "force": _linear_force_convention}


def _damping_ratio_from_restitution(restitution, convention):
    """Damping ratio that realises ``restitution`` in (0, 1] under ``convention``."""
    if restitution == 1.0:
        return 0.0
    log_e = math.log(restitution)
    if convention == "overlap":
        return -log_e / math.hypot(math.pi, log_e)
    # ln e(zeta) falls strictly from 0 and e(zeta) < 1/zeta^2 for zeta > 1: the bracket holds.
    upper = 1.0 / math.sqrt(restitution)
    return brentq(
        lambda zeta: _linear_force_convention(zeta)[1] - log_e,
        0.0,
        upper,
        xtol=1e-300,
        rtol=4 * np.finfo(float).eps,
    )


def _linear_zeta(stiffness, damping, mass):
    k = _positive("stiffness", stiffness, "N/m")
    c = _non_negative("damping", damping, "N*s/m")
    m = _positive("mass", mass, "kg")
    return c / (2.0 * math.sqrt(k * m))


def damping_ratio(stiffness, damping, mass):
    """Damping ratio of a linear spring-dashpot contact.

    Parameters
    ----------
    stiffness : float
        Spring stiffness k [N/m].
    damping : float
        Dashpot coefficient c [N*s/m].
    mass : float
        Effective mass m* [kg].

    Returns
    -------
    float
        zeta = c / (2 sqrt(k m*)) [-].
    """
    return _linear_zeta(stiffness, damping, mass)


def linear_contact_time(stiffness, damping, mass, convention="overlap"):
    """Contact time of a linear spring-dashpot impact, F = k d + c d'.

    Parameters
    ----------
    stiffness : float
        Spring stiffness k [N/m].
    damping : float
        Dashpot coefficient c [N*s/m].
    mass : float
        Effective mass m* [kg].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends (see the module docstring).

    Returns
    -------
    float
        Contact time t_c [s]; ``inf`` under ``"overlap"`` for zeta >= 1 (the overlap decays
        but never returns to zero).

    Notes
    -----
    With w0 = sqrt(k/m*) and zeta = c / (2 sqrt(k m*)):

    - ``"overlap"``: t_c = pi / (w0 sqrt(1 - zeta^2)).
    - ``"force"``: k d + c d' = 0 is d'' = 0. For zeta < 1, t_c = (pi - phi) / (w0 sqrt(1 -
      zeta^2)) with phi = atan2(2 zeta sqrt(1 - zeta^2), 1 - 2 zeta^2) = 2 arcsin(zeta),
      i.e. t_c = 2 arccos(zeta) / (w0 sqrt(1 - zeta^2)), valid for every zeta < 1
      (Schwager & Poeschel 2007 state it for zeta < 1/sqrt(2)). zeta = 1: t_c = 2 / w0.
      zeta > 1, with roots l1 > l2 of s^2 + 2 zeta w0 s + w0^2:
      t_c = ln(l2^2 / l1^2) / (l1 - l2) = 2 arccosh(zeta) / (w0 sqrt(zeta^2 - 1)).

    References
    ----------
    .. [1] T. Schwager, T. Poeschel, "Coefficient of restitution and linear-dashpot model
       revisited", Granular Matter 9, 465-469 (2007). DOI: 10.1007/s10035-007-0065-z
    """
    zeta = _linear_zeta(stiffness, damping, mass)
    scaled_time, _ = _LINEAR_SOLUTIONS[_convention(convention)](zeta)
    return scaled_time / math.sqrt(stiffness / mass)


def linear_restitution(stiffness, damping, mass, convention="overlap"):
    """Coefficient of restitution of a linear spring-dashpot impact, F = k d + c d'.

    Parameters
    ----------
    stiffness : float
        Spring stiffness k [N/m].
    damping : float
        Dashpot coefficient c [N*s/m].
    mass : float
        Effective mass m* [kg].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends (see the module docstring).

    Returns
    -------
    float
        Rebound speed / impact speed [-], independent of the impact speed.

    Notes
    -----
    - ``"overlap"``: e = exp(-pi zeta / sqrt(1 - zeta^2)); 0 for zeta >= 1.
    - ``"force"``: e = |d'(t_c)| / v with t_c from :func:`linear_contact_time`. For
      zeta < 1, e = exp(-zeta (pi - phi) / sqrt(1 - zeta^2)) = exp(-2 zeta arccos(zeta) /
      sqrt(1 - zeta^2)) (Schwager & Poeschel 2007); zeta = 1: e = exp(-2); zeta > 1:
      e = exp(-2 zeta arccosh(zeta) / sqrt(zeta^2 - 1)) = q^(-(q + 1)/(q - 1)) with
      q = l2/l1. e falls strictly with zeta and tends to 0 only as zeta -> inf (like
      1/(4 zeta^2)), so every e in (0, 1] is reached; it is never below the ``"overlap"``
      value.

    References
    ----------
    .. [1] T. Schwager, T. Poeschel, "Coefficient of restitution and linear-dashpot model
       revisited", Granular Matter 9, 465-469 (2007). DOI: 10.1007/s10035-007-0065-z
    """
    zeta = _linear_zeta(stiffness, damping, mass)
    _, log_e = _LINEAR_SOLUTIONS[_convention(convention)](zeta)
    return math.exp(log_e)


def linear_damping_from_restitution(stiffness, restitution, mass, convention="overlap"):
    """Dashpot coefficient that gives a linear spring-dashpot contact a chosen restitution.

    Parameters
    ----------
    stiffness : float
        Spring stiffness k [N/m].
    restitution : float
        Target coefficient of restitution, in (0, 1] [-]; 1 gives c = 0.
    mass : float
        Effective mass m* [kg].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends (see the module docstring).

    Returns
    -------
    float
        Dashpot coefficient c = 2 zeta sqrt(k m*) [N*s/m].

    Notes
    -----
    ``"overlap"``: zeta = -ln e / sqrt(pi^2 + ln^2 e) (the mapping DEM codes use).
    ``"force"``: :func:`linear_restitution` inverted with Brent's method; it is strictly
    monotone in zeta and covers (0, 1] (e -> 0 only as zeta -> inf), so every restitution
    in (0, 1] is realisable. For a given e the ``"force"`` damping is larger.

    References
    ----------
    .. [1] T. Schwager, T. Poeschel, "Coefficient of restitution and linear-dashpot model
       revisited", Granular Matter 9, 465-469 (2007). DOI: 10.1007/s10035-007-0065-z
    """
    k = _positive("stiffness", stiffness, "N/m")
    e = _restitution(restitution)
    m = _positive("mass", mass, "kg")
    zeta = _damping_ratio_from_restitution(e, _convention(convention))
    return 2.0 * zeta * math.sqrt(k * m)


# --- Hertz with Tsuji / EDEM / LIGGGHTS damping ---------------------------------------------


def tsuji_damping_factor(restitution, convention="overlap"):
    """Damping factor alpha of the Tsuji/EDEM/LIGGGHTS damped Hertz law for a restitution.

    The law is F = kH d^(3/2) + alpha sqrt(m* kH) d^(1/4) d'.

    Parameters
    ----------
    restitution : float
        Target coefficient of restitution, in (0, 1] [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends. ``"overlap"`` returns the factor the DEM codes use.

    Returns
    -------
    float
        alpha [-].

    Notes
    -----
    ``"overlap"``: alpha = sqrt(5) (-ln e) / sqrt(pi^2 + ln^2 e), the EDEM/LIGGGHTS formula
    (LIGGGHTS writes gamma_n = 2 sqrt(5/6) beta sqrt(S_n m*) with S_n = 2 E* sqrt(R* d)).
    It realises e *exactly*, at every speed, when contact ends at zero overlap: with
    w = u^(5/4) and d(sigma) = u^(1/4) d(tau) the scaled law (see :func:`tsuji_restitution`)
    becomes the linear oscillator w'' + alpha w' + (5/4) w = 0, whose damping ratio is
    alpha / sqrt(5) (Antypov & Elliott 2011). The one-sided force of that oscillator is
    the law's force divided by u^(1/4), so ``"force"`` maps onto the linear ``"force"``
    result too: alpha = sqrt(5) zeta_force(e), from :func:`linear_damping_from_restitution`.

    References
    ----------
    .. [1] Y. Tsuji, T. Tanaka, T. Ishida, "Lagrangian numerical simulation of plug flow of
       cohesionless particles in a horizontal pipe", Powder Technol. 71, 239-250 (1992).
       DOI: 10.1016/0032-5910(92)88030-L
    .. [2] D. Antypov, J. A. Elliott, "On an analytical solution for the damped Hertzian
       spring", EPL 94, 50004 (2011). DOI: 10.1209/0295-5075/94/50004
    """
    e = _restitution(restitution)
    return math.sqrt(5.0) * _damping_ratio_from_restitution(e, _convention(convention))


def tsuji_damping_coefficient(k_hertz, mass, restitution, convention="overlap"):
    """Damping coefficient eta of F = kH d^(3/2) + eta d^(1/4) d' for a restitution.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    mass : float
        Effective mass m* [kg].
    restitution : float
        Target coefficient of restitution, in (0, 1] [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends; see :func:`tsuji_damping_factor`.

    Returns
    -------
    float
        eta = alpha sqrt(m* kH) [N*s/m^1.25].
    """
    k = _positive("k_hertz", k_hertz, "N/m^1.5")
    m = _positive("mass", mass, "kg")
    return tsuji_damping_factor(restitution, convention) * math.sqrt(m * k)


def tsuji_restitution(alpha, convention="overlap"):
    """Restitution realised by the Tsuji/EDEM damped Hertz law for a damping factor alpha.

    Parameters
    ----------
    alpha : float
        Damping factor in F = kH d^(3/2) + alpha sqrt(m* kH) d^(1/4) d' [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends (see the module docstring).

    Returns
    -------
    float
        Coefficient of restitution [-]; 0 under ``"overlap"`` for alpha >= sqrt(5) (the
        overlap never returns to zero).

    Notes
    -----
    Scaling d = L u, t = (L/v) tau with L^(5/2) = m* v^2 / kH turns the law into
    u'' = -(u^(3/2) + alpha u^(1/4) u'), u(0) = 0, u'(0) = 1, so e depends on alpha only:
    not on kH, m* or v. With w = u^(5/4) and d(sigma) = u^(1/4) d(tau) this is exactly the
    linear oscillator w'' + alpha w' + (5/4) w = 0 (u' = (4/5) dw/dsigma), so e is the
    linear spring-dashpot result (:func:`linear_restitution`) at zeta = alpha / sqrt(5),
    under the same convention. This is exact; no integration is needed. The test suite
    checks it against direct integration of m x'' = -(kH x^1.5 + eta x^0.25 x')
    (DOP853, rtol 1e-11). Realised e for alpha from :func:`tsuji_damping_factor`
    (``"overlap"`` mapping):

    ========  ==========  ===========  ========
    target e  alpha       "overlap"    "force"
    ========  ==========  ===========  ========
    0.3       0.800193    0.3          0.397140
    0.5       0.481769    0.5          0.550283
    0.7       0.252247    0.7          0.718201
    0.9       0.0749495   0.9          0.902026
    ========  ==========  ===========  ========

    So the EDEM mapping assumes contact ends at zero overlap; with a one-sided (``"force"``)
    contact the grain rebounds faster than asked (Thornton et al. 2013 report the same
    dependence on alpha only).

    References
    ----------
    .. [1] D. Antypov, J. A. Elliott, "On an analytical solution for the damped Hertzian
       spring", EPL 94, 50004 (2011). DOI: 10.1209/0295-5075/94/50004
    .. [2] C. Thornton, S. J. Cummins, P. W. Cleary, "An investigation of the comparative
       behaviour of alternative contact force models during inelastic collisions",
       Powder Technol. 233, 30-46 (2013). DOI: 10.1016/j.powtec.2012.08.012
    """
    a = _non_negative("alpha", alpha, "-")
    _, log_e = _LINEAR_SOLUTIONS[_convention(convention)](a / math.sqrt(5.0))
    return math.exp(log_e)


# --- Kuwabara-Kono viscoelastic Hertz -------------------------------------------------------


def kuwabara_kono_parameter(k_hertz, dissipation, mass, velocity):
    """Dimensionless dissipation of F = kH (d^(3/2) + (3/2) A d^(1/2) d').

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    dissipation : float
        Dissipative constant A [s].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        x = (3/2) A (kH/m*)^(2/5) v^(1/5) [-].

    Notes
    -----
    Scaling d = L u, t = (L/v) tau with L^(5/2) = m* v^2 / kH gives
    u'' = -(u^(3/2) + x u^(1/2) u'): the restitution depends on x alone.
    """
    k = _positive("k_hertz", k_hertz, "N/m^1.5")
    a = _non_negative("dissipation", dissipation, "s")
    m = _positive("mass", mass, "kg")
    v = _positive("velocity", velocity, "m/s")
    return 1.5 * a * (k / m) ** 0.4 * v**0.2


def kuwabara_kono_restitution(k_hertz, dissipation, mass, velocity):
    """Restitution of the Kuwabara-Kono viscoelastic Hertz law (small-dissipation series).

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    dissipation : float
        Dissipative constant A [s].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        e = 1 - C1 x + C2 x^2 [-], x from :func:`kuwabara_kono_parameter`.

    Raises
    ------
    ParameterError
        If x > C1 / (2 C2) = 0.7225, where the two-term series turns upwards.

    Notes
    -----
    C1 = sqrt(pi) Gamma(3/5) / (2^(1/5) 5^(2/5) Gamma(21/10)) = 1.1534489 (first-order
    dissipated energy along the elastic Hertz path) and C2 = (3/5) C1^2 = 0.7982666; the
    published values are 1.15344 and 0.79826.

    The series is the expansion of the ``"overlap"`` convention. Against direct integration
    (DOP853, rtol 1e-12) its error is about +0.52 x^3 (the next term):

    =====  ==============  =================
    x      e - "overlap"   e - "force"
    =====  ==============  =================
    0.01   +5.2e-7         -2.1e-6
    0.05   +6.3e-5         -7.4e-5
    0.1    +4.9e-4         -2.2e-4
    0.2    +3.7e-3         +2.8e-4
    0.5    +4.9e-2         +2.8e-2
    =====  ==============  =================

    Under ``"force"`` the realised e is larger by about 0.26 x^(5/2) (for small x), an
    error of lower order than the series' own; the smaller ``"force"`` errors near
    x = 0.1-0.2 are a cancellation, not a better match.

    References
    ----------
    .. [1] G. Kuwabara, K. Kono, "Restitution coefficient in a collision between two
       spheres", Jpn. J. Appl. Phys. 26, 1230-1233 (1987). DOI: 10.1143/JJAP.26.1230
    .. [2] T. Schwager, T. Poeschel, "Coefficient of normal restitution of viscous particles
       and cooling rate of granular gases", Phys. Rev. E 57, 650-654 (1998).
       DOI: 10.1103/PhysRevE.57.650
    .. [3] R. Ramirez, T. Poeschel, N. V. Brilliantov, T. Schwager, "Coefficient of
       restitution of colliding viscoelastic spheres", Phys. Rev. E 60, 4465-4472 (1999).
       DOI: 10.1103/PhysRevE.60.4465
    """
    x = kuwabara_kono_parameter(k_hertz, dissipation, mass, velocity)
    if x > KUWABARA_KONO_MAX_PARAMETER:
        raise ParameterError(
            f"dissipation gives the Kuwabara-Kono parameter x = {x:g}, outside the range of "
            f"the series x <= {KUWABARA_KONO_MAX_PARAMETER:.4f}; integrate the law instead"
        )
    return 1.0 - KUWABARA_KONO_C1 * x + KUWABARA_KONO_C2 * x**2


# --- Hunt-Crossley --------------------------------------------------------------------------


def _x_minus_log1p(w):
    """w - ln(1 + w) for w > -1, free of the cancellation the direct form has at small |w|."""
    if abs(w) > 0.25:
        return w - math.log1p(w)
    return math.fsum((-w) ** k / k for k in range(2, 40))


def hunt_crossley_restitution(damping, velocity):
    """Exact restitution of the Hunt-Crossley law F = k d^n (1 + (3/2) chi d').

    Parameters
    ----------
    damping : float
        Hunt-Crossley damping chi [s/m].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        Coefficient of restitution [-]; independent of k, n and the mass.

    Notes
    -----
    With lam = (3/2) chi, m v dv/dx = -k x^n (1 + lam v) separates; the first integral
    G(v) = v/lam - ln(1 + lam v)/lam^2 gives G(v_in) = G(-v_out) exactly, i.e. with
    y = lam v_in and z = lam v_out: y - ln(1 + y) = -z - ln(1 - z), solved by Brent's
    method for s = -ln(1 - z) (so that z -> 1 stays resolved). Since lam |d'| <= z < 1
    throughout, the force is positive until d = 0: both contact-end conventions give this
    result. For y >~ 40, z = 1 to double
    precision and e = 1/y. For small y, e = 1 - chi v + O((chi v)^2)
    (:func:`hunt_crossley_restitution_linearised`).

    References
    ----------
    .. [1] K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping
       in vibroimpact", J. Appl. Mech. 42, 440-445 (1975). DOI: 10.1115/1.3423596
    """
    chi = _non_negative("damping", damping, "s/m")
    v = _positive("velocity", velocity, "m/s")
    y = 1.5 * chi * v
    if y == 0.0:
        return 1.0
    target = _x_minus_log1p(y)

    def excess(s):
        z = -math.expm1(-s)  # z = 1 - exp(-s); then -z - ln(1 - z) = s - z
        return (s - z if z > 0.25 else _x_minus_log1p(-z)) - target

    s = brentq(excess, 0.0, target + 1.0, xtol=1e-300)
    return -math.expm1(-s) / y


def hunt_crossley_restitution_linearised(damping, velocity):
    """Small-damping restitution of the Hunt-Crossley law, e = 1 - chi v.

    Parameters
    ----------
    damping : float
        Hunt-Crossley damping chi [s/m].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        1 - chi v [-].

    Raises
    ------
    ParameterError
        If chi v >= 1 (the linearised value would not be positive).

    Notes
    -----
    First-order expansion of :func:`hunt_crossley_restitution`: z = y (1 - 2y/3 + ...) with
    y = (3/2) chi v, hence e = 1 - chi v. This is Hunt & Crossley's lambda = (3/2) alpha
    relation with alpha = chi (the factor 3/2 in the law is chosen for it).

    References
    ----------
    .. [1] K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping
       in vibroimpact", J. Appl. Mech. 42, 440-445 (1975). DOI: 10.1115/1.3423596
    """
    chi = _non_negative("damping", damping, "s/m")
    v = _positive("velocity", velocity, "m/s")
    if chi * v >= 1.0:
        raise ParameterError(
            f"damping * velocity must be < 1 for the linearised restitution; got {chi * v!r}"
        )
    return 1.0 - chi * v


# --- Walton-Braun hysteretic linear ---------------------------------------------------------


def _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness):
    k1 = _positive("loading_stiffness", loading_stiffness, "N/m")
    k2 = check_number(
        "unloading_stiffness", unloading_stiffness, low=k1, low_open=False, unit="N/m"
    )
    return k1, k2


def walton_braun_restitution(loading_stiffness, unloading_stiffness):
    """Restitution of the Walton-Braun hysteretic linear law.

    Parameters
    ----------
    loading_stiffness : float
        Loading stiffness k1 [N/m].
    unloading_stiffness : float
        Unloading stiffness k2 >= k1 [N/m].

    Returns
    -------
    float
        e = sqrt(k1 / k2) [-].

    Notes
    -----
    Loading F = k1 d up to d_max = v sqrt(m/k1); unloading F = k2 (d - d0), released
    energy (k1 d_max)^2 / (2 k2).

    References
    ----------
    .. [1] O. R. Walton, R. L. Braun, "Viscosity, granular-temperature, and stress
       calculations for shearing assemblies of inelastic, frictional disks", J. Rheol. 30,
       949-980 (1986). DOI: 10.1122/1.549893
    """
    k1, k2 = _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness)
    return math.sqrt(k1 / k2)


def walton_braun_contact_time(loading_stiffness, unloading_stiffness, mass):
    """Contact time of the Walton-Braun hysteretic linear law.

    Parameters
    ----------
    loading_stiffness : float
        Loading stiffness k1 [N/m].
    unloading_stiffness : float
        Unloading stiffness k2 >= k1 [N/m].
    mass : float
        Effective mass m* [kg].

    Returns
    -------
    float
        t_c = (pi/2) (sqrt(m/k1) + sqrt(m/k2)) [s]: a quarter period on each branch.

    References
    ----------
    .. [1] O. R. Walton, R. L. Braun, J. Rheol. 30, 949-980 (1986). DOI: 10.1122/1.549893
    """
    k1, k2 = _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness)
    m = _positive("mass", mass, "kg")
    return 0.5 * math.pi * (math.sqrt(m / k1) + math.sqrt(m / k2))


# --- linear spring with a force cap ---------------------------------------------------------


def linear_plastic_yield_velocity(stiffness, yield_force, mass):
    """Impact speed at which a linear spring with a force cap starts to yield.

    Parameters
    ----------
    stiffness : float
        Elastic stiffness k [N/m].
    yield_force : float
        Force cap Fy [N].
    mass : float
        Effective mass m* [kg].

    Returns
    -------
    float
        v_y = Fy / sqrt(k m*) [m/s].
    """
    k = _positive("stiffness", stiffness, "N/m")
    fy = _positive("yield_force", yield_force, "N")
    m = _positive("mass", mass, "kg")
    return fy / math.sqrt(k * m)


def linear_plastic_restitution(stiffness, yield_force, mass, velocity):
    """Restitution of a linear elastic-perfectly-plastic contact.

    Parameters
    ----------
    stiffness : float
        Elastic stiffness k [N/m] (loading and unloading).
    yield_force : float
        Force cap Fy [N].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        e = min(1, v_y / v) [-]; unloading from Fy releases Fy^2 / (2k) = m v_y^2 / 2.
    """
    v_y = linear_plastic_yield_velocity(stiffness, yield_force, mass)
    v = _positive("velocity", velocity, "m/s")
    return min(1.0, v_y / v)


def linear_plastic_contact_time(stiffness, yield_force, mass, velocity):
    """Contact time of a linear elastic-perfectly-plastic contact.

    Parameters
    ----------
    stiffness : float
        Elastic stiffness k [N/m].
    yield_force : float
        Force cap Fy [N].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        t_c [s].

    Notes
    -----
    t_c = [arcsin(min(1, v_y/v)) + sqrt(max(0, v^2 - v_y^2)) / v_y + pi/2] / w0,
    w0 = sqrt(k/m*): elastic loading until k d = Fy, deceleration at constant Fy until at
    rest, then a quarter period of elastic unloading. pi / w0 for v <= v_y.
    """
    v_y = linear_plastic_yield_velocity(stiffness, yield_force, mass)
    v = _positive("velocity", velocity, "m/s")
    w0 = math.sqrt(stiffness / mass)
    plastic = math.sqrt(max(0.0, v**2 - v_y**2)) / v_y
    return (math.asin(min(1.0, v_y / v)) + plastic + 0.5 * math.pi) / w0


# --- Thornton elastic-perfectly-plastic Hertz -----------------------------------------------


def _thornton_material(effective_modulus, effective_radius, yield_pressure):
    e = _positive("effective_modulus", effective_modulus, "Pa")
    r = _positive("effective_radius", effective_radius, "m")
    p = _positive("yield_pressure", yield_pressure, "Pa")
    return e, r, p


def thornton_yield_overlap(effective_modulus, effective_radius, yield_pressure):
    """Overlap at which the Hertz peak pressure reaches the limiting pressure (Thornton 1997).

    Parameters
    ----------
    effective_modulus : float
        Effective modulus E* [Pa].
    effective_radius : float
        Effective radius R* [m].
    yield_pressure : float
        Limiting contact pressure p_y [Pa].

    Returns
    -------
    float
        d_y = pi^2 R* p_y^2 / (4 E*^2) [m].

    References
    ----------
    .. [1] C. Thornton, "Coefficient of restitution for collinear collisions of
       elastic-perfectly plastic spheres", J. Appl. Mech. 64, 383-386 (1997).
       DOI: 10.1115/1.2787319
    """
    e, r, p = _thornton_material(effective_modulus, effective_radius, yield_pressure)
    return math.pi**2 * r * p**2 / (4.0 * e**2)


def thornton_yield_force(effective_modulus, effective_radius, yield_pressure):
    """Force at the yield overlap of Thornton's model.

    Parameters
    ----------
    effective_modulus : float
        Effective modulus E* [Pa].
    effective_radius : float
        Effective radius R* [m].
    yield_pressure : float
        Limiting contact pressure p_y [Pa].

    Returns
    -------
    float
        F_y = pi^3 R*^2 p_y^3 / (6 E*^2) = kH d_y^(3/2) [N].

    References
    ----------
    .. [1] C. Thornton, J. Appl. Mech. 64, 383-386 (1997). DOI: 10.1115/1.2787319
    """
    e, r, p = _thornton_material(effective_modulus, effective_radius, yield_pressure)
    return math.pi**3 * r**2 * p**3 / (6.0 * e**2)


def thornton_yield_velocity(effective_modulus, effective_radius, yield_pressure, mass):
    """Impact speed at which Thornton's elastic-perfectly-plastic contact starts to yield.

    Parameters
    ----------
    effective_modulus : float
        Effective modulus E* [Pa].
    effective_radius : float
        Effective radius R* [m].
    yield_pressure : float
        Limiting contact pressure p_y [Pa].
    mass : float
        Effective mass m* [kg].

    Returns
    -------
    float
        v_y = sqrt((16/15) E* sqrt(R*) d_y^(5/2) / m*) [m/s] (Hertz energy at d_y).

    References
    ----------
    .. [1] C. Thornton, J. Appl. Mech. 64, 383-386 (1997). DOI: 10.1115/1.2787319
    """
    d_y = thornton_yield_overlap(effective_modulus, effective_radius, yield_pressure)
    m = _positive("mass", mass, "kg")
    return math.sqrt(16.0 / 15.0 * effective_modulus * math.sqrt(effective_radius) * d_y**2.5 / m)


def thornton_restitution(effective_modulus, effective_radius, yield_pressure, mass, velocity):
    """Restitution of Thornton's elastic-perfectly-plastic Hertz contact.

    Parameters
    ----------
    effective_modulus : float
        Effective modulus E* [Pa].
    effective_radius : float
        Effective radius R* [m].
    yield_pressure : float
        Limiting contact pressure p_y [Pa].
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        Coefficient of restitution [-]; 1 for v <= v_y.

    Notes
    -----
    With r = v_y / v < 1:
    e = sqrt(6 sqrt(3) / 5) sqrt(1 - r^2/6) [r / (r + 2 sqrt(6/5 - r^2/5))]^(1/4).
    The model: Hertz to d_y, then F = F_y + pi p_y R* (d - d_y); Hertz unloading with the
    enlarged radius that keeps the contact radius sqrt(R* d_max).

    References
    ----------
    .. [1] C. Thornton, "Coefficient of restitution for collinear collisions of
       elastic-perfectly plastic spheres", J. Appl. Mech. 64, 383-386 (1997).
       DOI: 10.1115/1.2787319
    """
    v_y = thornton_yield_velocity(effective_modulus, effective_radius, yield_pressure, mass)
    v = _positive("velocity", velocity, "m/s")
    if v <= v_y:
        return 1.0
    r = v_y / v
    bracket = r / (r + 2.0 * math.sqrt(1.2 - 0.2 * r**2))
    return math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * math.sqrt(1.0 - r**2 / 6.0) * bracket**0.25


# --- time-step guide ------------------------------------------------------------------------


def rayleigh_time(radius, density, shear_modulus, poisson_ratio):
    """Rayleigh time: the DEM codes' time-step guide for Hertz contacts.

    Parameters
    ----------
    radius : float
        Particle radius R [m].
    density : float
        Particle density rho [kg/m^3].
    shear_modulus : float
        Shear modulus G [Pa].
    poisson_ratio : float
        Poisson's ratio, in (-1, 0.5] [-].

    Returns
    -------
    float
        T_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766) [s].

    Notes
    -----
    The time a Rayleigh surface wave takes to cross half the particle's circumference;
    0.1631 nu + 0.8766 is a linear fit of the Rayleigh-wave to shear-wave speed ratio,
    within 0.3 % for 0 <= nu <= 0.5. Codes take a fraction (typically 0.1-0.3) as time step.

    References
    ----------
    .. [1] Y. Li, Y. Xu, C. Thornton, "A comparison of discrete element simulations and
       experiments for 'sandpiles' composed of spherical particles", Powder Technol. 160,
       219-228 (2005). DOI: 10.1016/j.powtec.2005.09.002
    """
    r = _positive("radius", radius, "m")
    rho = _positive("density", density, "kg/m^3")
    g = _positive("shear_modulus", shear_modulus, "Pa")
    nu = _poisson("poisson_ratio", poisson_ratio)
    return math.pi * r * math.sqrt(rho / g) / (0.1631 * nu + 0.8766)


# --- prescribed plastic pulse (the paper's Eqs. 7-8) ----------------------------------------


def plastic_trapezoid_amplitude(mass, velocity, contact_time, ramp_time):
    """Plateau force of the paper's perfectly plastic trapezoidal pulse.

    Parameters
    ----------
    mass : float
        Grain mass [kg].
    velocity : float
        Impact speed v [m/s].
    contact_time : float
        Total pulse duration t_k [s].
    ramp_time : float
        Duration of each linear rise and fall, in [0, t_k / 2] [s]; 0 is the rectangle of
        Eq. (7), t_k / 2 a triangle.

    Returns
    -------
    float
        F = m v / (t_k - t_r) [N], so that the impulse equals m v (restitution 0).

    References
    ----------
    .. [1] W. Keska, J. Marcinkiewicz, L. Gierz, Z. Staszak, J. Selech, K. Koszela,
       "Simulation verification of the contact parameter influence on the forces' course of
       cereal grain impact against a stiff surface", Appl. Sci. 11, 466 (2021), Eqs. (7)-(8).
       DOI: 10.3390/app11020466
    """
    m = _positive("mass", mass, "kg")
    v = _positive("velocity", velocity, "m/s")
    t_k = _positive("contact_time", contact_time, "s")
    t_r = check_number("ramp_time", ramp_time, low=0.0, high=0.5 * t_k, low_open=False, unit="s")
    return m * v / (t_k - t_r)


# --- sensor response ------------------------------------------------------------------------


def half_sine_residual_amplitude(pulse_duration, period):
    """Residual vibration of an undamped oscillator after a half-sine force pulse.

    Parameters
    ----------
    pulse_duration : float
        Duration tau of the pulse F0 sin(pi t / tau), 0 <= t <= tau [s].
    period : float
        Natural period T of the oscillator [s].

    Returns
    -------
    float
        Amplitude of the free vibration after the pulse divided by the static deflection
        F0 / k under the peak force [-] (the residual shock response spectrum).

    Notes
    -----
    With r = tau / T, Duhamel's integral gives

    A_res / (F0/k) = 4 r |cos(pi r)| / |1 - 4 r^2| = 2 pi r / (1 + 2 r) |sinc((1 - 2r)/2)|,

    sinc(x) = sin(pi x) / (pi x); the second form is used (no 0/0 at r = 1/2, where the
    value is pi/2). Zeros at r = 3/2, 5/2, ...; for r -> 0 it tends to 4 r, the response
    to the impulse 2 F0 tau / pi.

    References
    ----------
    .. [1] A. G. Piersol, T. L. Paez (eds.), *Harris' Shock and Vibration Handbook*,
       6th ed., McGraw-Hill, 2010: transient response to pulse functions.
    """
    tau = _positive("pulse_duration", pulse_duration, "s")
    t = _positive("period", period, "s")
    r = tau / t
    return 2.0 * math.pi * r / (1.0 + 2.0 * r) * abs(float(np.sinc(0.5 - r)))
