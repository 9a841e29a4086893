"""Elastic-perfectly-plastic impacts: linear spring with a force cap, Thornton's Hertz."""

import math

from contactlab.validation import (
    check_positive,
)

__all__ = [
    "linear_plastic_contact_time",
    "linear_plastic_restitution",
    "linear_plastic_yield_velocity",
    "thornton_restitution",
    "thornton_yield_force",
    "thornton_yield_overlap",
    "thornton_yield_velocity",
]


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
    k = check_positive("stiffness", stiffness, "N/m")
    fy = check_positive("yield_force", yield_force, "N")
    m = check_positive("mass", mass, "kg")
    km = k * m
    return fy / (math.sqrt(km) if km > 0.0 else math.sqrt(k) * math.sqrt(m))  # km underflows


def linear_plastic_restitution(stiffness, yield_force, mass, velocity):
    """Restitution of a linear elastic-perfectly-plastic contact.

    Parameters
    ----------
    stiffness, yield_force, mass : float
        k [N/m] (loading and unloading), Fy [N], m* [kg], as for
        :func:`linear_plastic_yield_velocity`.
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        e = min(1, v_y / v) [-]; unloading from Fy releases Fy^2 / (2k) = m v_y^2 / 2.
    """
    v_y = linear_plastic_yield_velocity(stiffness, yield_force, mass)
    v = check_positive("velocity", velocity, "m/s")
    return min(1.0, v_y / v)


def linear_plastic_contact_time(stiffness, yield_force, mass, velocity):
    """Contact time t_c [s] of a linear elastic-perfectly-plastic contact.

    Parameters
    ----------
    stiffness, yield_force, mass, velocity : float
        k [N/m], Fy [N], m* [kg] and v [m/s], as for :func:`linear_plastic_restitution`.

    Notes
    -----
    t_c = [arcsin(min(1, v_y/v)) + sqrt(max(0, v^2 - v_y^2)) / v_y + pi/2] / w0,
    w0 = sqrt(k/m*): elastic loading until k d = Fy, deceleration at constant Fy until at
    rest, then a quarter period of elastic unloading. pi / w0 for v <= v_y.
    """
    v_y = linear_plastic_yield_velocity(stiffness, yield_force, mass)
    v = check_positive("velocity", velocity, "m/s")
    w0 = math.sqrt(stiffness / mass)
    plastic = math.sqrt(max(0.0, v**2 - v_y**2)) / v_y
    return (math.asin(min(1.0, v_y / v)) + plastic + 0.5 * math.pi) / w0


# --- Thornton elastic-perfectly-plastic Hertz -----------------------------------------------


def _thornton_material(effective_modulus, effective_radius, yield_pressure):
    e = check_positive("effective_modulus", effective_modulus, "Pa")
    r = check_positive("effective_radius", effective_radius, "m")
    p = check_positive("yield_pressure", yield_pressure, "Pa")
    return e, r, p


def thornton_yield_overlap(effective_modulus, effective_radius, yield_pressure):
    """Overlap at which the Hertz peak pressure reaches the limiting pressure (Thornton 1997).

    Parameters
    ----------
    effective_modulus, effective_radius : float
        E* [Pa] and R* [m] of the contact (:func:`~contactlab.analytic.hertz_stiffness`).
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
    """Force at the yield overlap of Thornton's model:
    F_y = pi^3 R*^2 p_y^3 / (6 E*^2) = kH d_y^(3/2) [N].

    Parameters
    ----------
    effective_modulus, effective_radius, yield_pressure : float
        E* [Pa], R* [m] and p_y [Pa], as for :func:`thornton_yield_overlap`.

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
    effective_modulus, effective_radius, yield_pressure : float
        E* [Pa], R* [m] and p_y [Pa], as for :func:`thornton_yield_overlap`.
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
    m = check_positive("mass", mass, "kg")
    return math.sqrt(16.0 / 15.0 * effective_modulus * math.sqrt(effective_radius) * d_y**2.5 / m)


def thornton_restitution(effective_modulus, effective_radius, yield_pressure, mass, velocity):
    """Restitution of Thornton's elastic-perfectly-plastic Hertz contact.

    Parameters
    ----------
    effective_modulus, effective_radius, yield_pressure, mass : float
        E* [Pa], R* [m], p_y [Pa] and m* [kg], as for :func:`thornton_yield_velocity`.
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
    v = check_positive("velocity", velocity, "m/s")
    if v <= v_y:
        return 1.0
    r = v_y / v
    bracket = r / (r + 2.0 * math.sqrt(1.2 - 0.2 * r**2))
    return math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * math.sqrt(1.0 - r**2 / 6.0) * bracket**0.25
