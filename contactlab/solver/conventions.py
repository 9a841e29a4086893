"""The tangential conventions of the DEM codes, as named presets of this toolkit's options.

A DEM code's Hertz-Mindlin contact hard-wires three rules its law's name does not state
(``docs/dem-conventions.md``): the lever arm of the contact point (an option of
:func:`contactlab.simulate_oblique`), the tangential history rule and the tangential damping
(options of :class:`contactlab.laws.Mindlin`). :data:`DEM_CONVENTIONS` names each code's
choice; :meth:`Conventions.mindlin` and :attr:`Conventions.lever_arm` apply it::

    rules = DEM_CONVENTIONS["kratos"]
    law = rules.mindlin(Mindlin.from_material(Material(E, nu, R), mu))
    simulate_oblique(grain, sensor, normal, law, v, angle, lever_arm=rules.lever_arm)
"""

from dataclasses import dataclass

from contactlab.laws import COULOMB_CAPS, DAMPING_FORMS, HISTORY_FORMS, Mindlin
from contactlab.validation import check_choice

__all__ = ["DEM_CONVENTIONS", "LEVER_ARMS", "Conventions"]

LEVER_ARMS = ("radius", "contact")
"""Values of ``simulate_oblique(lever_arm=...)``: the radius ``R``, or the distance from
the centre to the contact point ``R - d`` at a wall."""


@dataclass(frozen=True)
class Conventions:
    """One DEM code's tangential rules.

    Attributes
    ----------
    lever_arm : {"radius", "contact"}
        Arm of the torque and of the contact-point slip: ``R`` or ``R - d``.
    history : {"total", "incremental", "incremental_rescaled"}
        :class:`~contactlab.laws.Mindlin`'s history rule.
    damping : {"none", "tied"}
        :class:`~contactlab.laws.Mindlin`'s tangential damping.
    coulomb_cap : {"total", "elastic"}, default "total"
        :class:`~contactlab.laws.Mindlin`'s Coulomb cap (it acts with a tangential damping
        only).
    """

    lever_arm: str
    history: str
    damping: str
    coulomb_cap: str = "total"

    def __post_init__(self):
        check_choice("lever_arm", self.lever_arm, LEVER_ARMS)
        check_choice("history", self.history, HISTORY_FORMS)
        check_choice("damping", self.damping, DAMPING_FORMS)
        check_choice("coulomb_cap", self.coulomb_cap, COULOMB_CAPS)

    def mindlin(self, law):
        """``law`` (a :class:`~contactlab.laws.Mindlin`) with these history, damping and
        Coulomb cap rules, its stiffness and friction kept."""
        return Mindlin(law.k_mindlin, law.friction, self.history, self.damping, self.coulomb_cap)


DEM_CONVENTIONS = {
    "contactlab": Conventions("radius", "total", "none"),
    "lammps_mindlin": Conventions("radius", "total", "none"),
    "lammps_mindlin_force": Conventions("radius", "incremental", "none"),
    "lammps_mindlin_rescale_force": Conventions("radius", "incremental_rescaled", "none"),
    "kratos": Conventions("contact", "incremental_rescaled", "tied", "elastic"),
}
"""Code -> its rules. LAMMPS (``pair granular``/``fix wall/gran granular``) at a wall: arm
``R`` (measured), the history named by its ``tangential`` keyword, ``xgamma_t = 0``
(no damping; a non-zero ``xgamma_t`` is a multiple of the normal damping coefficient, not
of ``gamma``). Kratos ``DEM_D_Hertz_viscous_Coulomb``: ``actual_arm_vector`` ``R - d``,
``minoring_factor`` rescaling, ``2 gamma sqrt(m* Kt)`` damping, the elastic force capped
(``CalculateTangentialForceWithNeighbour``). LAMMPS caps the total force
(``gran_sub_mod_tangential.cpp``). Sources:
``docs/dem-conventions.md``."""
