"""Kratos DEM input: the materials and contact-law part (``MaterialsDEM.json``).

Kratos' DEM application (``KratosDEMApplication`` 10.4.4) reads its materials from a JSON
file named in the project parameters (``solver_settings.material_import_settings``): the
materials with their Young's modulus, Poisson ratio and density, the material relations
with the contact law's name, restitution and friction, and which model part gets which
material. This writer gives that file for the grain (``SpheresPart``) and the sensor
plate as a rigid wall (``RigidFacePart``), with the fitted law exactly where Kratos can
hold it. Sources in ``applications/DEMApplication/`` of github.com/KratosMultiphysics/Kratos
(formulas in :mod:`contactlab.laws.kratos`):

* Hertz family ``(E*, e)``: ``DEM_D_Hertz_viscous_Coulomb``. At a wall Kratos mixes
  ``1/E* = (1 - nu**2)/E + (1 - nu_p**2)/E_p`` and takes ``R* = R``, ``m* = m``
  (``InitializeContactWithFEM``), so grain and plate get the same ``E, nu, E_p, nu_p`` as
  for the other codes, and the force is ``(4/3) E* sqrt(R) d**1.5 = kH d**1.5``. Its
  damping is ``2 gamma sqrt(m* Kn) d'`` with ``Kn = 1.5 kH sqrt(d)``: the fitted Tsuji
  damping ``alpha sqrt(m kH) d**0.25 d'`` is ``gamma = alpha / (2 sqrt(1.5))``,
  independent of the grain. Kratos computes ``gamma`` from ``COEFFICIENT_OF_RESTITUTION``
  with Thornton's 10-term polynomial (``sphere_strategy.py``, ``GammaForHertzThornton``),
  so the file holds the restitution whose polynomial value is that ``gamma``
  (:func:`kratos_hertz_restitution`, solved to machine precision): the fitted law is
  realised exactly, and the number written is close to (within the polynomial's misfit,
  up to 2.5e-4 at e = 0.2), not equal to, the fitted law's own rebound.
* linear ``(k, c)``: ``DEM_D_Linear_viscous_Coulomb``, whose wall stiffness is ``Kn = pi
  0.31225 E* R`` (``InitializeContactWithFEM``): the grain's ``E`` is chosen for ``Kn =
  k`` with the grain radius of the fit (Poisson ratio 0; it enters only the tangential
  stiffness). Kratos finds ``gamma = c / (2 sqrt(m k))`` from the restitution by
  bisection to 1e-4 (``RootByBisection`` on ``coeff_of_rest_diff``, the linear
  oscillator's rebound with the contact ending at zero force, the fitted law's
  convention): the file holds that exact rebound, and Kratos realises ``gamma`` within
  6e-5 (the bisection's last interval).

Kratos clips the normal force at zero (``CalculateForcesWithFEM``): the contact never
pulls, so the realised rebound is the fitted law's. Friction, rolling friction and the
grain-grain relation are not measured by a grain-plate impact (NOT FITTED): the relation
between grains repeats the grain-plate one, the friction is the one given or 0.5.

Only numbers and fixed keys are written (``json.dumps``); no text from the fit reaches the
file. The time step and the fitted rebound, which belong to the project parameters, are
under the key ``contactlab_export`` (Kratos ignores keys it does not read).
"""

import json
import math

from scipy.optimize import brentq

from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.inverse.export.contact import STEEL_POISSON_RATIO, STEEL_YOUNGS_MODULUS
from contactlab.inverse.export.rebound import realised_rebound
from contactlab.laws.kratos_form import linear_kn_factor

__all__ = [
    "KRATOS_STEPS_PER_CONTACT",
    "kratos_hertz_restitution",
    "material_relation",
    "thornton_gamma",
    "write",
]

KRATOS_STEPS_PER_CONTACT = 200
"""Time step = contact time / 200: symplectic Euler evaluates the damping at the step's
start velocity (first order); at 200 steps the realised rebound errs ~0.1 %."""

_THORNTON = (
    -6.918798,
    -16.41105,
    146.8049,
    -796.4559,
    2928.711,
    -7206.864,
    11494.29,
    -11342.18,
    6276.757,
    -1489.915,
)
"""Coefficients h1 ... h10 of ``GammaForHertzThornton`` (Kratos ``sphere_strategy.py``)."""

_RESTITUTION_RANGE = (0.001, 0.999)
"""Kratos clamps the restitution below 0.001 and returns ``gamma = 0`` above 0.999."""


def thornton_gamma(restitution):
    """Kratos' ``GammaForHertzThornton(e)``: its Hertz damping ratio for a restitution.

    ``alpha = e (h1 + e (h2 + ... + e h10))``, ``gamma = sqrt(1 / (1 - (1 + e)**2
    exp(alpha)) - 1)``; 0 above ``e = 0.999``.
    """
    e = max(restitution, _RESTITUTION_RANGE[0])
    if e > _RESTITUTION_RANGE[1]:
        return 0.0
    alpha = 0.0
    for h in reversed(_THORNTON):
        alpha = (alpha + h) * e
    return math.sqrt(1.0 / (1.0 - (1.0 + e) ** 2 * math.exp(alpha)) - 1.0)


def kratos_hertz_restitution(gamma):
    """The ``COEFFICIENT_OF_RESTITUTION`` for which Kratos sets ``DAMPING_GAMMA = gamma``.

    Parameters
    ----------
    gamma : float
        Damping ratio of ``DEM_D_Hertz_viscous_Coulomb`` [-].

    Returns
    -------
    float
        ``e`` with ``thornton_gamma(e) == gamma`` (the polynomial falls monotonically
        from 14.2 at ``e = 0.001`` to 0.0047 at 0.999); 1.0 for ``gamma = 0``.

    Raises
    ------
    ParameterError
        For a damping beyond what Kratos' polynomial reaches.
    """
    if gamma == 0.0:
        return 1.0
    low, high = _RESTITUTION_RANGE
    if not thornton_gamma(high) <= gamma <= thornton_gamma(low):
        raise ParameterError(
            f"fitted damping gamma = {gamma:.6g} is outside what Kratos' "
            f"GammaForHertzThornton reaches ({thornton_gamma(high):.4g} to "
            f"{thornton_gamma(low):.4g}) from a restitution of {low} to {high}"
        )
    return brentq(lambda e: thornton_gamma(e) - gamma, low, high, xtol=1e-15, rtol=1e-15)


def material_relation(names, ids, law_name, restitution, friction):
    """One ``material_relations`` entry of a ``MaterialsDEM.json``: the two materials' names
    and ids, Kratos' law name, the restitution and the friction [-] (no rolling friction,
    Kratos' default rolling model named so it does not warn)."""
    return {
        "material_names_list": list(names),
        "material_ids_list": list(ids),
        "Variables": {
            "COEFFICIENT_OF_RESTITUTION": restitution,
            "STATIC_FRICTION": friction,
            "DYNAMIC_FRICTION": friction,
            "FRICTION_DECAY": 500.0,
            "ROLLING_FRICTION": 0.0,
            "ROLLING_FRICTION_WITH_WALLS": 0.0,
            "DEM_ROLLING_FRICTION_MODEL_NAME": "DEMRollingFrictionModelBounded",
            "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME": law_name,
        },
    }


def _linear_materials(c):
    """Grain and plate Young's moduli and Poisson ratios for Kratos' linear law."""
    e_star = c.stiffness / (linear_kn_factor(wall=True) * c.radius)
    plate_e, plate_nu = STEEL_YOUNGS_MODULUS, STEEL_POISSON_RATIO  # a linear fit has none
    compliance = 1.0 / e_star - (1.0 - plate_nu**2) / plate_e
    if compliance <= 0.0:
        raise ParameterError(
            f"fitted stiffness k = {c.stiffness:.4g} N/m needs E* = {e_star:.4g} Pa in "
            "Kratos' linear law, stiffer than the plate allows"
        )
    gamma = c.damping / (2.0 * math.sqrt(c.mass * c.stiffness))
    if gamma >= 1.0 / math.sqrt(2.0):
        raise ParameterError(
            f"fitted damping ratio {gamma:.4g} >= 1/sqrt(2): the linear contact then ends "
            "at zero force with no rebound formula Kratos inverts"
        )
    return 1.0 / compliance, 0.0, plate_e, plate_nu, realised_rebound(c, "force")


def write(c):
    """The ``MaterialsDEM.json`` text for an
    :class:`~contactlab.inverse.export.contact.ExportContact`, as lines."""
    step = c.contact_time / KRATOS_STEPS_PER_CONTACT
    if c.family == "linear":
        law_name = "DEM_D_Linear_viscous_Coulomb"
        young, nu, plate_e, plate_nu, restitution = _linear_materials(c)
    else:
        law_name = "DEM_D_Hertz_viscous_Coulomb"
        alpha = analytic.tsuji_damping_factor(c.restitution)
        restitution = kratos_hertz_restitution(alpha / (2.0 * math.sqrt(1.5)))
        young, nu = c.youngs_modulus, c.poisson_ratio
        plate_e, plate_nu = c.plate_youngs_modulus, c.plate_poisson_ratio
    friction = float(c.friction)
    document = {
        "materials": [
            {
                "material_name": "grain",
                "material_id": 1,
                "Variables": {
                    "PARTICLE_DENSITY": float(c.density),
                    "YOUNG_MODULUS": float(young),
                    "POISSON_RATIO": float(nu),
                },
            },
            {
                "material_name": "plate",
                "material_id": 2,
                "Variables": {
                    "YOUNG_MODULUS": float(plate_e),
                    "POISSON_RATIO": float(plate_nu),
                    "COMPUTE_WEAR": False,
                },
            },
        ],
        "material_relations": [
            material_relation(("grain", "grain"), (1, 1), law_name, restitution, friction),
            material_relation(("grain", "plate"), (1, 2), law_name, restitution, friction),
        ],
        "material_assignation_table": [["SpheresPart", "grain"], ["RigidFacePart", "plate"]],
        "contactlab_export": {
            "MaxTimeStep [s]": step,
            "steps_per_contact": KRATOS_STEPS_PER_CONTACT,
            "contact_time [s]": float(c.contact_time),
            "grain_radius [m]": float(c.radius),
            "impact_velocity [m/s]": float(c.velocity),
            "fitted_rebound [-]": realised_rebound(c, "force"),
            "friction_fitted": bool(c.friction_fitted),
            "grain_grain_relation_fitted": False,
        },
    }
    return json.dumps(document, indent=2, allow_nan=False).split("\n")
