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
``gamma``; :mod:`dem_check.engines.kratos.scene` sets ``DAMPING_GAMMA`` after
``Initialize``. Both bodies are given ``E = 2 E*`` and ``nu = 0`` (then ``E1 E2 / (E1 +
E2) = E*``); the Poisson ratio enters only the tangential stiffness, unused in a normal
impact (friction 0).

Every other law raises :class:`~contactlab.errors.ParameterError` naming it and saying
why (:data:`REFUSED`); nothing is approximated.

Each law states its own mapping beside its force (``_kratos_model(m*, R*, wall)``
returning a :class:`~contactlab.laws.kratos_form.KratosContact`) or its reason
(``kratos_refusal``), as it states its LAMMPS mapping (:mod:`contactlab.laws.lammps`);
this module reads them, so a new law adds neither a branch nor an entry here.
"""

from contactlab.laws import LAWS
from contactlab.laws.engine_support import engine_mapping, stated_support
from contactlab.laws.kratos_form import HERTZ_LAW, LINEAR_LAW, KratosContact, linear_kn_factor

__all__ = [
    "ENGINE_LAWS",
    "HERTZ_LAW",
    "LINEAR_LAW",
    "REFUSED",
    "KratosContact",
    "kratos_contact",
    "linear_kn_factor",
]

ENGINE_LAWS, REFUSED = stated_support(LAWS.values(), "_kratos_model", "kratos_refusal")
"""Laws Kratos' DEM contact laws hold exactly: those that state a ``_kratos_model``
(``ENGINE_LAWS``), and those Kratos cannot hold exactly: law class -> the reason each
states, quoted in the ParameterError (``REFUSED``)."""


def kratos_contact(law, effective_mass, effective_radius, wall):
    """The Kratos contact law that realises ``law`` exactly for ``m*`` and ``R*``.

    Parameters
    ----------
    law, effective_mass, effective_radius
        As for :func:`contactlab.laws.lammps.granular_model`: a law whose own class
        states a ``_kratos_model`` (:data:`ENGINE_LAWS`), and the ``m*`` [kg] and ``R*``
        [m] Kratos will use for the contact.
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
    return engine_mapping(
        law,
        "_kratos_model",
        (ENGINE_LAWS, REFUSED),
        "Kratos DEM",
        "Kratos' DEM contact laws",
        effective_mass,
        effective_radius,
        wall,
    )
