"""contactlab's laws as LAMMPS ``granular`` models: exact mappings, or a refusal saying why.

LAMMPS' GRANULAR package (``pair_style granular``, ``fix wall/gran granular``; LAMMPS 22
Jul 2025) computes the normal force of a contact of overlap ``d``, effective radius ``R*``
and effective mass ``m*`` as ``Fn = F_elastic + F_damping`` with ``d' = -v_n`` (positive
while approaching) and, with ``limit_damping``, ``Fn = max(Fn, 0)`` (source:
``granular_model.cpp``, ``gran_sub_mod_normal.cpp``, ``gran_sub_mod_damping.cpp``):

=====================  ===========================================================
sub-model              force
=====================  ===========================================================
``hooke k eta``        ``k d``
``hertz k eta``        ``k a d`` with the contact radius ``a = sqrt(R* d)``
``damping velocity``   ``eta d'``
``damping viscoelastic`` ``eta m* a d'``
``damping coeff_restitution``  ``sqrt(5) (-ln eta)/sqrt(pi^2 + ln^2 eta) sqrt(m* Fe/d) d'``
                       (``eta`` read as a restitution; ``Fe`` the elastic force)
=====================  ===========================================================

``m*`` is ``m1 m2 / (m1 + m2)`` between two particles and the particle's mass against a
wall; ``R*`` is ``R1 R2 / (R1 + R2)``, and the particle's radius against a plane wall.

So, with ``limit_damping`` making the contact one-sided as in contactlab (it ends when
the force reaches zero and never pulls), four laws map exactly for given ``m*`` and ``R*``:

* :class:`~contactlab.laws.LinearViscoelastic` ``(k, c)``: ``hooke k c``, ``damping
  velocity``;
* :class:`~contactlab.laws.Hertz` ``(kH)``: ``hertz kH/sqrt(R*) 0``, ``damping velocity``;
* :class:`~contactlab.laws.HertzDamped` ``(kH, eta)``: ``hertz kH/sqrt(R*) e_L``,
  ``damping coeff_restitution``, with ``e_L = exp(-pi s / sqrt(1 - s^2))``,
  ``s = eta / sqrt(5 m* kH)``: then the damping force is ``eta d**0.25 d'`` exactly. ``e_L``
  is only LAMMPS' input (the restitution its formula would give were the contact to end
  at zero overlap); the realised rebound is contactlab's (force-zero end). LAMMPS' own
  ``damping tsuji`` has the same force form, but maps its input through a sixth-degree
  polynomial fit (Marshall 2009, Eq. 53), which reaches only ``alpha < 1.80`` and has no
  closed inverse; ``coeff_restitution`` is inverted in closed form and reaches every
  ``alpha = eta/sqrt(m* kH) < sqrt(5)``. A stronger damping raises ParameterError;
* :class:`~contactlab.laws.KuwabaraKono` ``(kH, A)``: ``hertz kH/sqrt(R*) eta``,
  ``damping viscoelastic`` with ``eta = 1.5 A kH / (m* sqrt(R*))``, so the damping force
  is ``1.5 A kH d**0.5 d'``.

Floats are written with 17 significant digits, so LAMMPS reads the very doubles computed
here. The tangential model (required by LAMMPS) is ``linear_nohistory 0 0``: no
tangential force, as in contactlab's normal impact.

Every other law raises :class:`~contactlab.errors.ParameterError` naming it and saying
why (:data:`REFUSED`); nothing is approximated.
"""

import math
from dataclasses import dataclass

from contactlab.errors import ParameterError
from contactlab.laws.engine_support import refuse_unsupported
from contactlab.laws.hertz import Hertz, HertzDamped, HuntCrossley, KuwabaraKono
from contactlab.laws.hysteretic import WaltonBraun
from contactlab.laws.linear import LinearViscoelastic
from contactlab.laws.plastic import LinearPlastic, Thornton
from contactlab.laws.pulse import PlasticTrapezoid
from contactlab.validation import check_positive

__all__ = ["ENGINE_LAWS", "REFUSED", "TANGENTIAL", "GranularModel", "granular_model"]

ENGINE_LAWS = (LinearViscoelastic, Hertz, HertzDamped, KuwabaraKono)
"""Laws LAMMPS' granular models hold exactly (see the module docstring)."""

TANGENTIAL = "tangential linear_nohistory 0 0"
"""LAMMPS requires a tangential model: this one exerts no force."""

_DAMPING_FORMS = (
    "LAMMPS' damping forces scale as d**0 (velocity, mass_velocity), d**0.25 "
    "(tsuji, coeff_restitution on hertz) or d**0.5 (viscoelastic)"
)

REFUSED = {
    HuntCrossley: f"its damping k chi d**n d' scales as d**n; {_DAMPING_FORMS}",
    WaltonBraun: (
        "its unloading stiffness differs from its loading one (history); LAMMPS' normal "
        "models (hooke, hertz, hertz/material, dmt, jkr) are elastic in the current overlap "
        "and its plastic one (mdr) is a different law"
    ),
    LinearPlastic: (
        "its force is capped at a yield force with a history of the largest overlap; no "
        "LAMMPS normal model has a force cap"
    ),
    Thornton: (
        "its Hertz loading turns to a limiting contact pressure and unloads along a "
        "history-dependent Hertz curve; LAMMPS' mdr model is a different plastic law"
    ),
    PlasticTrapezoid: "it prescribes the force in time, not as a function of the overlap",
}
"""Laws LAMMPS cannot hold exactly: law class -> the reason (quoted in the ParameterError)."""


@dataclass(frozen=True)
class GranularModel:
    """A law as one LAMMPS granular model for a contact of given ``m*`` and ``R*``.

    Attributes
    ----------
    law : ContactLaw
        The contactlab law.
    normal : str
        LAMMPS normal sub-model (``"hooke"`` or ``"hertz"``).
    stiffness : float
        Its first coefficient: ``k`` [N/m] (hooke) or [N/m**2 = Pa] (hertz, ``F = k a d``).
    damping : str
        LAMMPS damping sub-model (``"velocity"``, ``"viscoelastic"``,
        ``"coeff_restitution"``).
    damping_coefficient : float
        The normal model's second coefficient as LAMMPS reads it for that damping: [N*s/m]
        (velocity), [1/(m*s)] (viscoelastic), a restitution [-] (coeff_restitution).
    effective_mass : float
        ``m*`` the mapping assumed [kg].
    effective_radius : float
        ``R*`` the mapping assumed [m].
    """

    law: object
    normal: str
    stiffness: float
    damping: str
    damping_coefficient: float
    effective_mass: float
    effective_radius: float

    def words(self, tangential=TANGENTIAL, number=repr):
        """The model as ``pair_coeff`` / ``fix wall/gran granular`` words (one-sided).

        ``tangential`` is the tangential sub-model's words (default: no tangential force);
        ``number`` writes a coefficient (default all 17 digits, so LAMMPS reads the very
        double; the DEM exporter writes 7).
        """
        return (
            f"{self.normal} {number(self.stiffness)} {number(self.damping_coefficient)} "
            f"damping {self.damping} {tangential} limit_damping"
        )

    @property
    def what(self):
        """The law and its parameters, for error messages."""
        return f"law {self.law!r} as {self.normal}/{self.damping}"


def _hertz_damped_restitution(law, mass):
    """LAMMPS' ``coeff_restitution`` input that gives the damping ``eta`` exactly."""
    alpha = law.damping / math.sqrt(mass * law.k_hertz)
    s = alpha / math.sqrt(5.0)
    if s >= 1.0:
        raise ParameterError(
            f"law HertzDamped: damping = {law.damping:.6g} N*s/m**1.25 is alpha = "
            f"eta/sqrt(m* kH) = {alpha:.6g} >= sqrt(5) for m* = {mass:.6g} kg; LAMMPS' "
            "coeff_restitution damping reaches alpha < sqrt(5) only (its tsuji damping "
            "alpha < 1.80): no LAMMPS input holds this law"
        )
    return math.exp(-math.pi * s / math.sqrt(1.0 - s * s))


def granular_model(law, effective_mass, effective_radius):
    """The LAMMPS granular model that realises ``law`` exactly for ``m*`` and ``R*``.

    Parameters
    ----------
    law : ContactLaw
        One of :data:`ENGINE_LAWS` (exact type; a subclass may change the force).
    effective_mass : float
        ``m*`` LAMMPS will use for the contact [kg] (the grain's mass on a wall).
    effective_radius : float
        ``R*`` LAMMPS will use for the contact [m] (the grain's radius on a plane wall).

    Returns
    -------
    GranularModel

    Raises
    ------
    ParameterError
        For a law LAMMPS cannot hold (naming it and why, :data:`REFUSED`), or a
        :class:`~contactlab.laws.HertzDamped` damping beyond LAMMPS' reach.
    """
    mass = check_positive("effective_mass", effective_mass, "kg")
    radius = check_positive("effective_radius", effective_radius, "m")
    refuse_unsupported(law, ENGINE_LAWS, REFUSED, "LAMMPS", "LAMMPS' granular models")
    kind = type(law)
    common = {"law": law, "effective_mass": mass, "effective_radius": radius}
    if kind is LinearViscoelastic:
        return GranularModel(
            normal="hooke",
            stiffness=law.stiffness,
            damping="velocity",
            damping_coefficient=law.damping,
            **common,
        )
    hertz = {"normal": "hertz", "stiffness": law.k_hertz / math.sqrt(radius), **common}
    if kind is Hertz:
        return GranularModel(damping="velocity", damping_coefficient=0.0, **hertz)
    if kind is HertzDamped:
        return GranularModel(
            damping="coeff_restitution",
            damping_coefficient=_hertz_damped_restitution(law, mass),
            **hertz,
        )
    coefficient = 1.5 * law.dissipation * law.k_hertz / (mass * math.sqrt(radius))
    return GranularModel(damping="viscoelastic", damping_coefficient=coefficient, **hertz)
