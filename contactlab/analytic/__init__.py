"""Closed-form results for one normal impact on a flat or a second body.

These are the reference values the solvers, metrics and calibration tools are tested
against: contact time, peak overlap and force, and coefficient of restitution of the
contact laws in :mod:`contactlab.laws`, plus a few helpers for sensors and time steps.
One module per family, as in :mod:`contactlab.laws`; everything is re-exported here.

Conventions
-----------
SI units throughout. The overlap ``d > 0`` in compression; the contact force is ``>= 0``.
``mass`` is the effective mass ``m* = 1/(1/m1 + 1/m2)`` (for a grain on an immovable flat:
the grain mass); radius and modulus are the effective ones likewise (:func:`effective_mass`,
:func:`effective_radius`, :func:`effective_modulus`). ``velocity`` is the normal impact speed.
Damped laws take a contact-end ``convention`` (:mod:`~contactlab.analytic.conventions`).

Functions take scalars and return floats; bad input raises
:class:`contactlab.errors.ParameterError` naming the parameter.
"""

from contactlab.analytic.conventions import CONVENTIONS
from contactlab.analytic.hertz import (
    HERTZ_TIME_FACTOR,
    KUWABARA_KONO_C1,
    KUWABARA_KONO_C2,
    KUWABARA_KONO_MAX_PARAMETER,
    hertz_contact_time,
    hertz_max_force,
    hertz_max_overlap,
    hunt_crossley_restitution,
    hunt_crossley_restitution_linearised,
    kuwabara_kono_parameter,
    kuwabara_kono_restitution,
    tsuji_damping_coefficient,
    tsuji_damping_factor,
    tsuji_restitution,
)
from contactlab.analytic.hysteretic import walton_braun_contact_time, walton_braun_restitution
from contactlab.analytic.linear import (
    damping_ratio,
    linear_contact_time,
    linear_damping_from_restitution,
    linear_restitution,
)
from contactlab.analytic.materials import (
    RIGID_FLAT,
    Material,
    contact_modulus_radius,
    effective_mass,
    effective_modulus,
    effective_radius,
    hertz_stiffness,
    rayleigh_time,
    youngs_from_shear,
)
from contactlab.analytic.pair import PairRebound, pair_rebound
from contactlab.analytic.plastic import (
    linear_plastic_contact_time,
    linear_plastic_restitution,
    linear_plastic_yield_velocity,
    thornton_restitution,
    thornton_yield_force,
    thornton_yield_overlap,
    thornton_yield_velocity,
)
from contactlab.analytic.pulse import plastic_trapezoid_amplitude
from contactlab.analytic.sensor import half_sine_residual_amplitude
from contactlab.analytic.tangential import (
    SOLID_SPHERE_INERTIA,
    ObliqueImpact,
    effective_shear_modulus,
    gross_sliding_rebound,
    mindlin_stiffness_coefficient,
    slides_throughout,
)

__all__ = [
    "CONVENTIONS",
    "HERTZ_TIME_FACTOR",
    "KUWABARA_KONO_C1",
    "KUWABARA_KONO_C2",
    "KUWABARA_KONO_MAX_PARAMETER",
    "RIGID_FLAT",
    "SOLID_SPHERE_INERTIA",
    "Material",
    "ObliqueImpact",
    "PairRebound",
    "contact_modulus_radius",
    "damping_ratio",
    "effective_mass",
    "effective_modulus",
    "effective_radius",
    "effective_shear_modulus",
    "gross_sliding_rebound",
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
    "mindlin_stiffness_coefficient",
    "pair_rebound",
    "plastic_trapezoid_amplitude",
    "rayleigh_time",
    "slides_throughout",
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
