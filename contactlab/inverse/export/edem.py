"""EDEM input: the material and interaction values to enter in its creator."""

from contactlab.bodies import STEEL_DENSITY
from contactlab.inverse.export.contact import number, rayleigh_step, snippet

__all__ = ["write"]


EDEM_RAYLEIGH_FRACTION = 0.2
"""EDEM: 20 % of the Rayleigh time step (its auto time step; 10-40 % is its range)."""


def _hertz_step(c):
    return rayleigh_step(c, EDEM_RAYLEIGH_FRACTION, "EDEM's auto time step")


def _setting(entry):
    """A line of the creator's values: a ``(name, value)`` pair as ``name = value``; a
    section header or comment as it is."""
    if isinstance(entry, str):
        return entry
    name, value = entry
    return f"{name} = {value if isinstance(value, str) else number(value)}"


def _lines(c, step):
    if c.family == "linear":
        model = [
            ("Particle to Geometry normal model", "Linear Spring"),
            "[Interaction: grain - sensor plate]",
            ("Normal stiffness [N/m]", c.stiffness),
            ("Coefficient of Restitution", c.restitution),
            f"# dashpot c = {number(c.damping)} N*s/m = 2 sqrt(m k) (-ln e)/sqrt(pi^2 + ln^2 e)",
        ]
    else:
        model = [
            ("Particle to Geometry contact model", "Hertz-Mindlin (no slip)"),
            "[Bulk Material: grain]",
            ("Poisson's Ratio", c.poisson_ratio),
            ("Solids Density [kg/m3]", c.density),
            ("Shear Modulus [Pa]", c.shear_modulus),
            "[Equipment Material: sensor plate]",
            ("Poisson's Ratio", c.plate_poisson_ratio),
            ("Solids Density [kg/m3]", STEEL_DENSITY),
            ("Shear Modulus [Pa]", c.plate_shear_modulus),
            "[Interaction: grain - sensor plate]",
            ("Coefficient of Restitution", c.restitution),
        ]
    settings = [
        "[Physics]",
        *model,
        f"# Coefficient of Static Friction: {c.friction_note()}",
        ("Coefficient of Static Friction", c.friction),
        "[Simulator]",
        ("Fixed Time Step [s]", step),
    ]
    return [_setting(entry) for entry in settings]


def write(c):
    """EDEM lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    return snippet(c, "EDEM", "#", _hertz_step, _lines)
