"""Effective mass, radius and modulus of two bodies; Hertz stiffness; the Rayleigh time step."""

import math
from typing import NamedTuple

from contactlab.entry_checks import check_instance
from contactlab.validation import (
    check_number,
    check_poisson_ratio,
    check_positive,
)

__all__ = [
    "RIGID_FLAT",
    "Material",
    "check_elastic_pair",
    "contact_modulus_radius",
    "effective_mass",
    "effective_modulus",
    "effective_radius",
    "hertz_stiffness",
    "rayleigh_time",
    "youngs_from_shear",
]


class _MaterialFields(NamedTuple):
    youngs_modulus: float
    poisson_ratio: float
    radius: float


class Material(_MaterialFields):
    """A body's elastic data and radius of curvature, as the laws' ``from_material`` take
    them (:meth:`contactlab.Grain.material` gives a grain's); the defaults are a rigid
    flat (:data:`RIGID_FLAT`).

    Parameters
    ----------
    youngs_modulus : float, default inf
        Young's modulus [Pa], > 0; ``inf`` is rigid.
    poisson_ratio : float, default 0.0
        Poisson ratio [-] in (-1, 0.5].
    radius : float, default inf
        Radius of curvature [m], > 0; ``inf`` is a flat.
    """

    __slots__ = ()

    def __new__(cls, youngs_modulus=math.inf, poisson_ratio=0.0, radius=math.inf):
        return super().__new__(
            cls,
            check_number("youngs_modulus", youngs_modulus, low=0.0, unit="Pa", allow_inf=True),
            check_poisson_ratio("poisson_ratio", poisson_ratio),
            check_number("radius", radius, low=0.0, unit="m", allow_inf=True),
        )


RIGID_FLAT = Material()
"""The second body a grain meets unless another is given: rigid and flat."""


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
    return _in_series("mass", mass, "other_mass", other_mass, "kg")


def _in_series(name, value, other_name, other, unit):
    """``1 / (1/value + 1/other)``: ``value`` > 0, ``other`` > 0 or ``inf`` (checked)."""
    first = check_positive(name, value, unit)
    second = check_number(other_name, other, low=0.0, unit=unit, allow_inf=True)
    return 1.0 / (1.0 / first + 1.0 / second)


def effective_radius(radius, other_radius=math.inf):
    """Effective radius of curvature R* = 1 / (1/R1 + 1/R2) [m] of two convex bodies in
    contact (R* = R1 against a flat), the radii checked as :func:`effective_mass` checks
    masses.

    Parameters
    ----------
    radius, other_radius : float
        Radii of curvature of the two bodies [m]; ``other_radius = inf`` (default) is a flat.
    """
    return _in_series("radius", radius, "other_radius", other_radius, "m")


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
    e1, nu1, e2, nu2 = check_elastic_pair(
        youngs_modulus, poisson_ratio, other_youngs_modulus, other_poisson_ratio
    )
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


def check_elastic_pair(youngs_modulus, poisson_ratio, other_youngs_modulus, other_poisson_ratio):
    """Check the elastic data of two bodies in contact; return them as floats.

    ``youngs_modulus`` [Pa] > 0, ``other_youngs_modulus`` [Pa] > 0 or ``inf`` (a rigid
    body), Poisson ratios in (-1, 0.5] [-]; a bad value raises ParameterError naming it.
    """
    e1 = check_positive("youngs_modulus", youngs_modulus, "Pa")
    nu1 = check_poisson_ratio("poisson_ratio", poisson_ratio)
    e2 = check_number(
        "other_youngs_modulus", other_youngs_modulus, low=0.0, unit="Pa", allow_inf=True
    )
    nu2 = check_poisson_ratio("other_poisson_ratio", other_poisson_ratio)
    return e1, nu1, e2, nu2


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
    e = check_positive("effective_modulus", effective_modulus, "Pa")
    r = check_positive("effective_radius", effective_radius, "m")
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
    g = check_positive("shear_modulus", shear_modulus, "Pa")
    nu = check_poisson_ratio("poisson_ratio", poisson_ratio)
    return 2.0 * g * (1.0 + nu)


def contact_modulus_radius(material, other=RIGID_FLAT):
    """Effective modulus [Pa] and radius [m] of a grain against a second body.

    Parameters
    ----------
    material : Material
        The grain's ``(youngs_modulus [Pa], poisson_ratio [-], radius [m])``.
    other : Material, default RIGID_FLAT
        The second body's; ``inf`` modulus and radius make it a rigid flat.

    Returns
    -------
    tuple of float
        ``(E*, R*)`` with ``1/E* = (1-nu1**2)/E1 + (1-nu2**2)/E2`` and
        ``1/R* = 1/R1 + 1/R2``.
    """
    grain = check_instance("material", material, Material, "Grain.material")
    other = check_instance("other", other, Material)
    return (
        effective_modulus(*grain[:2], *other[:2]),
        effective_radius(grain.radius, other.radius),
    )


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
    r = check_positive("radius", radius, "m")
    rho = check_positive("density", density, "kg/m^3")
    g = check_positive("shear_modulus", shear_modulus, "Pa")
    nu = check_poisson_ratio("poisson_ratio", poisson_ratio)
    return math.pi * r * math.sqrt(rho / g) / (0.1631 * nu + 0.8766)
