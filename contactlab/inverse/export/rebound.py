"""Which rebound each DEM code realises from the exported inputs, stated in every header.

A fitted law is one-sided (:mod:`contactlab.laws.base`): its force never pulls and the
contact ends when the force reaches zero. A code that lets the damper pull ends the
contact at zero overlap instead, and the same inputs then rebound differently
(:func:`contactlab.analytic.linear_restitution`,
:func:`contactlab.analytic.tsuji_restitution`; e.g. 0.550 against 0.5 for a Tsuji
restitution input of 0.5). What each code does, from its source (``docs/dem_check.md``
holds the table and the LAMMPS measurements):

* LAMMPS: ``limit_damping`` clips the total normal force at zero (``granular_model.cpp``);
* LIGGGHTS: ``limitForce on`` sets a negative normal force to zero
  (``normal_model_hertz.h``, ``normal_model_hooke_stiffness.h``);
* YADE: ``Law2_ScGeom_ViscElPhys_Basic`` sets a negative ``kn d + cn d'`` to zero
  (``ViscoelasticPM.cpp``), ``Law2_ScGeom_MindlinPhys_Mindlin`` forbids attraction
  without adhesion (``HertzMindlin.cpp``);
* MercuryDPM: ``LinearViscoelasticInteraction`` and ``HertzianViscoelasticInteraction``
  apply ``k d - c v_n`` whenever the overlap is positive, tensile or not;
* EDEM: closed source; its theory guide gives the damping form but not whether the total
  force is clipped, so both rebounds are stated.
"""

from contactlab import analytic

__all__ = ["CONTACT_END", "realised_rebound", "rebound_line"]

CONTACT_END = {
    "LAMMPS": "force",
    "LIGGGHTS": "force",
    "YADE": "force",
    "MercuryDPM": "overlap",
    "EDEM": None,
}
"""Code -> where its contact ends with the exported inputs: ``"force"`` (never tensile,
the fitted law's convention), ``"overlap"`` (the damper may pull), ``None`` (not
documented)."""


def realised_rebound(contact, convention):
    """Rebound on a rigid plate of the exported inputs under a contact-end convention [-].

    Parameters
    ----------
    contact : ExportContact
        The exported contact (:mod:`contactlab.inverse.export.contact`).
    convention : {"force", "overlap"}
        ``"force"``: the fitted law's own rebound; ``"overlap"``: a code whose damper may
        pull (contact until zero overlap).

    Returns
    -------
    float
    """
    if contact.family == "linear":
        return analytic.linear_restitution(
            contact.stiffness, contact.damping, contact.mass, convention=convention
        )
    alpha = analytic.tsuji_damping_factor(contact.restitution)
    return analytic.tsuji_restitution(alpha, convention)


def rebound_line(code, contact):
    """The header sentence: which rebound the code realises from these inputs."""
    fitted = realised_rebound(contact, "force")
    end = CONTACT_END[code]
    if end == "force":
        return (
            f"realised rebound on a rigid plate: {fitted:.4f}, the fitted law's ({code} never "
            "lets the contact force pull: it ends when the force reaches zero)"
        )
    overlap = realised_rebound(contact, "overlap")
    if end == "overlap":
        return (
            f"realised rebound on a rigid plate: {overlap:.4f}, NOT the fitted law's "
            f"{fitted:.4f} ({code}'s damper pulls at the end of contact, which lasts until "
            "zero overlap)"
        )
    return (
        f"realised rebound on a rigid plate: {overlap:.4f} if {code} ends contact at zero "
        f"overlap (what its restitution mapping assumes), the fitted law's {fitted:.4f} if it "
        "never lets the force pull (not documented)"
    )
