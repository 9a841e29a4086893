"""Linear spring-dashpot impacts: contact time, restitution and damping in both conventions."""

import math

import numpy as np
from scipy.optimize import brentq

from contactlab.analytic.conventions import check_convention, check_restitution
from contactlab.validation import (
    check_non_negative,
    check_positive,
)

__all__ = [
    "damping_ratio",
    "linear_contact_time",
    "linear_damping_from_restitution",
    "linear_restitution",
]


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
    k = check_positive("stiffness", stiffness, "N/m")
    c = check_non_negative("damping", damping, "N*s/m")
    m = check_positive("mass", mass, "kg")
    return c / (2.0 * math.sqrt(k * m))


def damping_ratio(stiffness, damping, mass):
    """Damping ratio zeta = c / (2 sqrt(k m*)) [-] of a linear spring-dashpot contact of
    stiffness k [N/m], damping c [N*s/m] and effective mass m* [kg]."""
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
    scaled_time, _ = _linear_solution(stiffness, damping, mass, convention)
    return scaled_time / math.sqrt(stiffness / mass)


def _linear_solution(stiffness, damping, mass, convention):
    """``(w0 t_c, ln e)`` of a linear spring-dashpot impact under ``convention``."""
    zeta = _linear_zeta(stiffness, damping, mass)
    return _LINEAR_SOLUTIONS[check_convention(convention)](zeta)


def linear_restitution(stiffness, damping, mass, convention="overlap"):
    """Coefficient of restitution of a linear spring-dashpot impact, F = k d + c d'.

    Parameters
    ----------
    stiffness, damping, mass : float
        k [N/m], c [N*s/m] and m* [kg], as for :func:`linear_contact_time`.
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
      value. Reference: Schwager & Poeschel (2007), as for :func:`linear_contact_time`.
    """
    _, log_e = _linear_solution(stiffness, damping, mass, convention)
    return math.exp(log_e)


def linear_damping_from_restitution(stiffness, restitution, mass, convention="overlap"):
    """Dashpot coefficient that gives a linear spring-dashpot contact a chosen restitution.

    Parameters
    ----------
    stiffness, restitution, mass : float
        Spring stiffness k [N/m], the target restitution in (0, 1] [-] (1 gives c = 0) and
        the effective mass m* [kg].
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
    k = check_positive("stiffness", stiffness, "N/m")
    e = check_restitution(restitution)
    m = check_positive("mass", mass, "kg")
    zeta = _damping_ratio_from_restitution(e, check_convention(convention))
    return 2.0 * zeta * math.sqrt(k * m)
