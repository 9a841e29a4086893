"""contactlab's laws as Kratos DEM contact laws: exact mappings, or a refusal saying why.

Kratos' DEM application (``KratosDEMApplication`` 10.4.4) computes a sphere's normal
contact force from the two bodies' Young's moduli ``E1, E2`` and Poisson ratios ``nu1,
nu2`` (``E* = E1 E2 / (E2 (1 - nu1**2) + E1 (1 - nu2**2))``), the effective radius ``R*``
and mass ``m*`` (a particle's own against a rigid wall), and a damping ratio ``gamma``
(the material relation's ``DAMPING_GAMMA``). Sources, in
``applications/DEMApplication/custom_constitutive/`` of github.com/KratosMultiphysics/Kratos:

============================  =========================================================
law name                      normal force (``d'`` the approach rate)
============================  =========================================================
``DEM_D_Hertz_viscous_Coulomb``  ``Kn = 2 E* sqrt(R* d)``, ``F = 2/3 Kn d + 2 gamma
                              sqrt(m* Kn) d'`` (``DEM_D_Hertz_viscous_Coulomb_CL.cpp``:
                              ``InitializeContact``/``InitializeContactWithFEM``,
                              ``CalculateNormalForce``, ``CalculateViscoDampingForce``;
                              ``gamma`` from the contact's sub-properties)
``DEM_D_Linear_viscous_Coulomb``  ``F = Kn d + 2 gamma sqrt(m* Kn) d'`` with ``Kn = pi
                              0.31225 E* R`` against a wall and ``Kn = 1.432 pi 0.31225
                              E* R*`` between spheres (``DEM_D_Linear_viscous_Coulomb_CL.cpp``,
                              ``InitializeContactWithFEM`` and ``InitializeContact``;
                              ``gamma`` the particles' ``DAMPING_GAMMA``, averaged)
============================  =========================================================

Both laws clip the sum at zero (``if (normal_contact_force < 0.0)``, in
``CalculateForces``): the contact never pulls, as in contactlab, where it ends when the
force reaches zero. So, for given ``m*`` and ``R*``, three laws map exactly:

* :class:`~contactlab.laws.Hertz` ``(kH)``: Hertz law, ``E* = 3 kH / (4 sqrt(R*))``,
  ``gamma = 0``;
* :class:`~contactlab.laws.HertzDamped` ``(kH, eta)``: the same ``E*`` and ``gamma = eta /
  (2 sqrt(1.5 m* kH))``, since ``2 gamma sqrt(m* Kn) = 2 gamma sqrt(1.5 m* kH) d**0.25``;
* :class:`~contactlab.laws.LinearViscoelastic` ``(k, c)``: linear law, ``E*`` from the
  ``Kn`` formula above and ``gamma = c / (2 sqrt(m* k))``.

``gamma`` is written into the material relations *after* Kratos has initialised them:
Kratos' own ``sphere_strategy.ModifySubProperties`` derives it from a
``COEFFICIENT_OF_RESTITUTION`` through a 10-term polynomial fit (``GammaForHertzThornton``,
Hertz) or a bisection to 1e-4 (``RootByBisection``, linear), neither exact, and both
refer to a contact ending at zero overlap. :func:`kratos_contact` computes the exact
``gamma``; :mod:`~dem_check.engines.kratos.scene` sets ``DAMPING_GAMMA`` after
``Initialize``. Both bodies are given ``E = 2 E*`` and ``nu = 0`` (then ``E1 E2 / (E1 +
E2) = E*``); the Poisson ratio enters only the tangential stiffness, unused in a normal
impact (friction 0).

Every other law raises :class:`~contactlab.errors.ParameterError` naming it and saying
why (:data:`REFUSED`); nothing is approximated.
"""

import math
from dataclasses import dataclass

from contactlab.laws import (
    Hertz,
    HertzDamped,
    HuntCrossley,
    KuwabaraKono,
    LinearPlastic,
    LinearViscoelastic,
    PlasticTrapezoid,
    Thornton,
    WaltonBraun,
    damping_ratio,
)
from contactlab.laws.engine_support import EngineContact, refuse_unsupported
from contactlab.validation import check_positive

__all__ = [
    "ENGINE_LAWS",
    "HERTZ_LAW",
    "LINEAR_LAW",
    "REFUSED",
    "KratosContact",
    "hertz_gamma",
    "kratos_contact",
    "linear_kn_factor",
]

ENGINE_LAWS = (LinearViscoelastic, Hertz, HertzDamped)
"""Laws Kratos' DEM contact laws hold exactly (see the module docstring)."""

HERTZ_LAW = "DEM_D_Hertz_viscous_Coulomb"
"""Kratos' Hertz law with viscous damping and Coulomb friction."""

LINEAR_LAW = "DEM_D_Linear_viscous_Coulomb"
"""Kratos' linear law with viscous damping and Coulomb friction."""

_LINEAR_RADIUS_FACTOR = 0.31225
"""``Kn = pi * 0.31225 * E* * R`` (``DEM_D_Linear_viscous_Coulomb_CL.cpp``,
``modified_radius``)."""

_LINEAR_SPHERE_FACTOR = 1.432
"""Extra factor ``beta`` of the linear stiffness between two spheres (not at a wall)."""

_DAMPING_FORMS = (
    "Kratos' viscous damping is 2 gamma sqrt(m* Kn) d', which scales as d**0 (linear) or "
    "d**0.25 (Hertz)"
)

REFUSED = {
    KuwabaraKono: f"its damping 1.5 A kH d**0.5 d' scales as d**0.5; {_DAMPING_FORMS}",
    HuntCrossley: f"its damping k chi d**n d' scales as d**n; {_DAMPING_FORMS}",
    WaltonBraun: (
        "its unloading stiffness differs from its loading one (history); Kratos' "
        "DEM_D_Hertz/Linear laws are elastic in the current overlap"
    ),
    LinearPlastic: "its force is capped at a yield force; Kratos' elastic laws have no cap",
    Thornton: (
        "its Hertz loading turns to a limiting contact pressure; Kratos' plastic laws "
        "(DEM_D_Conical_damage, ...) are different laws"
    ),
    PlasticTrapezoid: "it prescribes the force in time, not as a function of the overlap",
}
"""Laws Kratos cannot hold exactly: law class -> the reason (quoted in the ParameterError)."""


def linear_kn_factor(wall):
    """``Kn / (E* R*)`` of Kratos' linear law: ``pi 0.31225`` at a wall, ``1.432`` times
    that between two spheres."""
    factor = math.pi * _LINEAR_RADIUS_FACTOR
    return factor if wall else _LINEAR_SPHERE_FACTOR * factor


def hertz_gamma(law, effective_mass):
    """``DAMPING_GAMMA`` that gives a :class:`~contactlab.laws.HertzDamped` damping exactly.

    ``2 gamma sqrt(m* Kn) d' = eta d**0.25 d'`` with ``Kn = 1.5 kH d**0.5``
    (:func:`contactlab.laws.damping_ratio`).
    """
    return damping_ratio(law, effective_mass)


@dataclass(frozen=True, kw_only=True)
class KratosContact(EngineContact):
    """A law as a Kratos DEM contact law for a contact of given ``m*`` and ``R*``.

    Attributes
    ----------
    name : str
        Kratos' law name (:data:`HERTZ_LAW` or :data:`LINEAR_LAW`).
    young : float
        Young's modulus of both bodies [Pa] (``2 E*``, Poisson ratio 0).
    gamma : float
        ``DAMPING_GAMMA`` [-].

    and ``law``, ``effective_mass``, ``effective_radius`` of
    :class:`~contactlab.laws.engine_support.EngineContact`.
    """

    name: str
    young: float
    gamma: float

    @property
    def what(self):
        """The law and its parameters, for messages."""
        return (
            f"law {self.law!r} as {self.name} (E = {self.young:.6g} Pa, gamma = {self.gamma:.6g})"
        )


def kratos_contact(law, effective_mass, effective_radius, wall):
    """The Kratos contact law that realises ``law`` exactly for ``m*`` and ``R*``.

    Parameters
    ----------
    law : ContactLaw
        One of :data:`ENGINE_LAWS` (exact type; a subclass may change the force).
    effective_mass : float
        ``m*`` Kratos will use for the contact [kg] (the grain's mass at a wall).
    effective_radius : float
        ``R*`` Kratos will use for the contact [m] (the grain's radius at a wall).
    wall : bool
        Whether the contact is with a rigid wall (Kratos' DEM-FEM contact) or between two
        spheres; the linear law's stiffness differs (:func:`linear_kn_factor`).

    Returns
    -------
    KratosContact

    Raises
    ------
    ParameterError
        For a law Kratos cannot hold, naming it and why (:data:`REFUSED`).
    """
    mass = check_positive("effective_mass", effective_mass, "kg")
    radius = check_positive("effective_radius", effective_radius, "m")
    refuse_unsupported(law, ENGINE_LAWS, REFUSED, "Kratos DEM", "Kratos' DEM contact laws")
    kind = type(law)
    common = {"law": law, "effective_mass": mass, "effective_radius": radius}
    if kind is LinearViscoelastic:
        e_star = law.stiffness / (linear_kn_factor(wall) * radius)
        gamma = damping_ratio(law, mass)
        return KratosContact(name=LINEAR_LAW, young=2.0 * e_star, gamma=gamma, **common)
    e_star = 3.0 * law.k_hertz / (4.0 * math.sqrt(radius))
    gamma = hertz_gamma(law, mass) if kind is HertzDamped else 0.0
    return KratosContact(name=HERTZ_LAW, young=2.0 * e_star, gamma=gamma, **common)
