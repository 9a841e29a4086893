"""EDEM input: the material and interaction values to enter in its creator."""

from contactlab.bodies import STEEL_DENSITY
from contactlab.inverse.export.contact import linear_step, number

__all__ = ["write"]


EDEM_RAYLEIGH_FRACTION = 0.2
"""EDEM: 20 % of the Rayleigh time step (its auto time step; 10-40 % is its range)."""


def write(c):
    """EDEM lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    if c.family == "linear":
        step, why = linear_step(c)
        body = [
            "[Physics]",
            "Particle to Geometry normal model = Linear Spring",
            "[Interaction: grain - sensor plate]",
            f"Normal stiffness [N/m] = {number(c.stiffness)}",
            f"Coefficient of Restitution = {number(c.restitution)}",
            f"# dashpot c = {number(c.damping)} N*s/m = 2 sqrt(m k) (-ln e)/sqrt(pi^2 + ln^2 e)",
        ]
    else:
        step = EDEM_RAYLEIGH_FRACTION * c.rayleigh_time
        why = (
            f"{EDEM_RAYLEIGH_FRACTION:.0%} of the Rayleigh time step {number(c.rayleigh_time)} s "
            "(EDEM's auto time step)"
        )
        body = [
            "[Physics]",
            "Particle to Geometry contact model = Hertz-Mindlin (no slip)",
            "[Bulk Material: grain]",
            f"Poisson's Ratio = {number(c.poisson_ratio)}",
            f"Solids Density [kg/m3] = {number(c.density)}",
            f"Shear Modulus [Pa] = {number(c.shear_modulus)}",
            "[Equipment Material: sensor plate]",
            f"Poisson's Ratio = {number(c.plate_poisson_ratio)}",
            f"Solids Density [kg/m3] = {number(STEEL_DENSITY)}",
            f"Shear Modulus [Pa] = {number(c.plate_shear_modulus)}",
            "[Interaction: grain - sensor plate]",
            f"Coefficient of Restitution = {number(c.restitution)}",
        ]
    body += [
        f"# Coefficient of Static Friction: {c.friction_note()}",
        f"Coefficient of Static Friction = {number(c.friction)}",
        "[Simulator]",
        f"Fixed Time Step [s] = {number(step)}",
    ]
    return [*c.header("EDEM", "#", why, step), *body]
