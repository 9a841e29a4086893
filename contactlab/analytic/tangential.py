"""Closed forms of the tangential side of an impact: shear moduli and gross sliding.

Conventions
-----------
A sphere of mass ``m``, radius ``R`` and moment of inertia ``I = kappa m R**2`` (``kappa =
2/5`` for a solid sphere) meets a flat. ``normal_velocity`` is the approach speed along the
normal (> 0), ``tangential_velocity`` the velocity of the centre along the flat, ``spin``
the angular velocity about the axis normal to the plane of incidence, signed so that the
contact point slips at ``s = vt - R spin`` (a ball rolling forward has ``spin = vt / R``).

References
----------
Maw N., Barber J.R., Fawcett J.N. (1976) The oblique impact of elastic spheres. Wear 38,
101-114. DOI 10.1016/0043-1648(76)90201-8
Johnson K.L. (1985) Contact Mechanics, Cambridge University Press, Sec. 7.2 and 11.4.
Chung Y.C., Ooi J.Y. (2011) Granular Matter 13, 643-656. DOI 10.1007/s10035-011-0277-0
"""

import math
from typing import NamedTuple

from contactlab.analytic.materials import check_elastic_pair
from contactlab.entry_checks import check_instance
from contactlab.errors import ParameterError
from contactlab.validation import check_inertia_factor, check_number

__all__ = [
    "SOLID_SPHERE_INERTIA",
    "ObliqueImpact",
    "effective_shear_modulus",
    "gross_sliding_rebound",
    "mindlin_stiffness_coefficient",
    "slides_throughout",
]

SOLID_SPHERE_INERTIA = 0.4
"""``I / (m R**2)`` of a homogeneous solid sphere [-]."""


def effective_shear_modulus(
    youngs_modulus, poisson_ratio, other_youngs_modulus=math.inf, other_poisson_ratio=0.0
):
    """Effective shear modulus ``G*`` of two elastic bodies in contact [Pa].

    Parameters
    ----------
    youngs_modulus, poisson_ratio, other_youngs_modulus, other_poisson_ratio : float
        The two bodies' Young's moduli [Pa] and Poisson ratios [-], as for
        :func:`~contactlab.analytic.effective_modulus` (default: a rigid flat).

    Returns
    -------
    float
        ``G*`` with ``1/G* = (2 - nu1)/G1 + (2 - nu2)/G2`` and ``G = E / (2 (1 + nu))``;
        against a rigid flat ``G* = G1 / (2 - nu1)``.

    Notes
    -----
    The Mindlin tangential stiffness of a Hertz contact of radius ``a`` is ``8 G* a``
    (Mindlin 1949; Johnson 1985, Eq. 7.42). LAMMPS' ``mindlin`` with material properties
    uses the same mixing, with both bodies of the grain's material at a wall.

    References
    ----------
    Mindlin R.D. (1949) J. Appl. Mech. 16, 259-268.
    """
    e1, nu1, e2, nu2 = check_elastic_pair(
        youngs_modulus, poisson_ratio, other_youngs_modulus, other_poisson_ratio
    )
    compliance = 2.0 * (2.0 - nu1) * (1.0 + nu1) / e1 + 2.0 * (2.0 - nu2) * (1.0 + nu2) / e2
    return 1.0 / compliance


def mindlin_stiffness_coefficient(effective_shear_modulus, effective_radius):
    """``k_mindlin = 8 G* sqrt(R*)`` [N/m**1.5], so that ``kt = k_mindlin sqrt(d)`` [N/m].

    Parameters
    ----------
    effective_shear_modulus : float
        ``G*`` [Pa] (:func:`effective_shear_modulus`).
    effective_radius : float
        ``R*`` [m].
    """
    g = check_number("effective_shear_modulus", effective_shear_modulus, low=0.0, unit="Pa")
    r = check_number("effective_radius", effective_radius, low=0.0, unit="m")
    return 8.0 * g * math.sqrt(r)


class _ObliqueFields(NamedTuple):
    normal_velocity: float
    tangential_velocity: float
    spin: float
    radius: float
    restitution: float
    friction: float
    inertia_factor: float


class ObliqueImpact(_ObliqueFields):
    """A sphere's oblique impact on a flat in rigid-body terms, as
    :func:`slides_throughout` and :func:`gross_sliding_rebound` read it (each value
    checked here).

    Parameters
    ----------
    normal_velocity : float
        Normal approach speed ``vn`` [m/s], > 0.
    tangential_velocity : float
        Tangential velocity of the centre ``vt`` [m/s].
    spin : float
        Angular velocity [rad/s], signed as in the module docstring.
    radius : float
        Sphere radius ``R`` [m].
    restitution : float
        Normal coefficient of restitution ``e`` in [0, 1] [-].
    friction : float
        Coulomb friction coefficient ``mu`` >= 0 [-].
    inertia_factor : float, default 0.4
        ``kappa = I / (m R**2)`` [-].
    """

    __slots__ = ()

    def __new__(
        cls,
        normal_velocity,
        tangential_velocity,
        spin,
        radius,
        restitution,
        friction,
        inertia_factor=SOLID_SPHERE_INERTIA,
    ):
        return super().__new__(
            cls,
            check_number("normal_velocity", normal_velocity, low=0.0, unit="m/s"),
            check_number("tangential_velocity", tangential_velocity, unit="m/s"),
            check_number("spin", spin, unit="rad/s"),
            check_number("radius", radius, low=0.0, unit="m"),
            check_number("restitution", restitution, low=0.0, high=1.0, low_open=False),
            check_number("friction", friction, low=0.0, low_open=False),
            check_inertia_factor("inertia_factor", inertia_factor),
        )


def _slip_and_reach(impact):
    """The initial slip ``vt - R spin`` [m/s] and how far Coulomb friction moves it over
    the impact, ``(1 + 1/kappa) mu (1 + e) vn`` [m/s]."""
    vn, vt, w, r, e, mu, kappa = check_instance("impact", impact, ObliqueImpact)
    return vt - r * w, (1.0 + 1.0 / kappa) * mu * (1.0 + e) * vn


def slides_throughout(impact):
    """Whether the contact point slides in one direction for the whole impact [bool].

    Rigid-body Coulomb theory: the tangential impulse is ``mu`` times the normal one
    ``(1 + e) m vn`` and changes the slip by ``(1 + 1/kappa) mu (1 + e) vn``; the contact
    slides throughout when that does not exhaust the initial slip ``|vt - R spin|``.
    A compliant contact (Mindlin) slides throughout under the same condition, except near
    it, where its stick phases start earlier (Maw et al. 1976).

    Parameters
    ----------
    impact : ObliqueImpact
        The impact's speeds, spin, radius, restitution, friction and inertia factor.
    """
    slip, reach = _slip_and_reach(impact)
    return abs(slip) >= reach


def gross_sliding_rebound(impact):
    """Tangential velocity [m/s] and spin [rad/s] after an impact in gross sliding.

    The tangential impulse is ``-mu (1 + e) m vn sign(s)``, with ``s = vt - R spin`` the
    initial slip, so ``vt' = vt - mu (1 + e) vn sign(s)`` and
    ``spin' = spin + mu (1 + e) vn sign(s) / (kappa R)``. Exact for any normal law and any
    tangential law capped by Coulomb friction, provided the contact slides throughout
    (:func:`slides_throughout`, checked here).

    Parameters
    ----------
    impact : ObliqueImpact
        The impact's speeds, spin, radius, restitution, friction and inertia factor.

    Returns
    -------
    (float, float)
        ``(vt', spin')`` [m/s, rad/s].

    Raises
    ------
    ParameterError
        If the contact does not slide throughout (the closed form does not apply).

    References
    ----------
    Maw N., Barber J.R., Fawcett J.N. (1976) Wear 38, 101-114 (gross slip regime).
    Chung Y.C., Ooi J.Y. (2011) Granular Matter 13, 643-656 (tests 4-8, sliding branches).
    """
    slip, reach = _slip_and_reach(impact)
    if abs(slip) < reach:
        raise ParameterError(
            f"the contact does not slide throughout: |vt - R spin| = {abs(slip):.6g} m/s "
            f"< (1 + 1/kappa) mu (1 + e) vn = {reach:.6g} m/s"
        )
    vn, vt, w, r, e, mu, kappa = impact
    change = mu * (1.0 + e) * vn * math.copysign(1.0, slip)
    return vt - change, w + change / (kappa * r)
