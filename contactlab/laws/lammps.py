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

Each law states its own mapping beside its force (``lammps_model(m*, R*)`` returning a
:class:`~contactlab.laws.granular.GranularModel`) or its reason (``lammps_refusal``);
this module reads them, so a new law adds neither a branch nor an entry here.
"""

from contactlab.laws import LAWS
from contactlab.laws.engine_support import engine_mapping, stated_support
from contactlab.laws.granular import TANGENTIAL, GranularModel

__all__ = ["ENGINE_LAWS", "REFUSED", "TANGENTIAL", "GranularModel", "granular_model"]

ENGINE_LAWS, REFUSED = stated_support(LAWS.values(), "_lammps_model", "lammps_refusal")
"""Laws LAMMPS' granular models hold exactly: those that state a ``_lammps_model``
(``ENGINE_LAWS``), and those LAMMPS cannot hold exactly: law class -> the reason each
states, quoted in the ParameterError (``REFUSED``)."""


def granular_model(law, effective_mass, effective_radius):
    """The LAMMPS granular model that realises ``law`` exactly for ``m*`` and ``R*``.

    Parameters
    ----------
    law : ContactLaw
        A law whose own class states a ``lammps_model`` (:data:`ENGINE_LAWS`; a subclass
        may change the force, so it does not inherit its parent's mapping).
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
    return engine_mapping(
        law,
        "_lammps_model",
        (ENGINE_LAWS, REFUSED),
        "LAMMPS",
        "LAMMPS' granular models",
        effective_mass,
        effective_radius,
    )
