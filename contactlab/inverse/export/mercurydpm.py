"""MercuryDPM input: a C++ species set-up."""

from contactlab.inverse.export.contact import LINEAR_STEPS_PER_CONTACT, number, snippet

__all__ = ["write"]


def _hertz_step(c):
    step = c.contact_time / LINEAR_STEPS_PER_CONTACT
    return step, (
        f"Hertz contact time at the impact velocity / {LINEAR_STEPS_PER_CONTACT} "
        "(MercuryDPM's getCollisionTime / 50 habit)"
    )


def _lines(c, step):
    if c.family == "linear":
        species = [
            "// normal force k d + c d' (LinearViscoelasticSpecies)",
            "auto species = speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());",
            f"species->setDensity({number(c.density)}); // [kg/m^3]",
            f"species->setStiffness({number(c.stiffness)}); // [N/m]",
            f"species->setDissipation({number(c.damping)}); // [N*s/m]",
        ]
    else:
        species = [
            "// normal force 4/3 E* sqrt(R d) d + alpha sqrt(m* kn) d' with alpha from e",
            "// (HertzianViscoelasticNormalSpecies); the species' modulus is the contact's E*:",
            "// this value is for grain-plate contacts (grain-grain: E/(2(1-nu^2)))",
            "auto species = speciesHandler.copyAndAddObject(HertzianViscoelasticMindlinSpecies());",
            f"species->setDensity({number(c.density)}); // [kg/m^3]",
            "species->setElasticModulusAndRestitutionCoefficient("
            f"{number(c.effective_modulus)}, {number(c.restitution)}); // E* [Pa], e [-]",
        ]
    return [
        *species,
        f"// sliding friction: {c.friction_note()} (set it on a friction species)",
        f"setTimeStep({number(step)}); // [s]",
    ]


def write(c):
    """MercuryDPM lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    return snippet(c, "MercuryDPM", "//", _hertz_step, _lines)
