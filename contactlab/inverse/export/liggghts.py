"""LIGGGHTS input: ``pair_style gran`` with hooke/stiffness or hertz."""

from contactlab.inverse.export.contact import number, rayleigh_step, snippet, type_pair

__all__ = ["write"]


LIGGGHTS_RAYLEIGH_FRACTION = 0.1
"""LIGGGHTS Hertz: 10 % of the Rayleigh time (``fix check/timestep/gran`` example)."""


def _hertz_step(c):
    return rayleigh_step(c, LIGGGHTS_RAYLEIGH_FRACTION, "fix check/timestep/gran")


def _lines(c, step):
    if c.family == "linear":
        model = [
            "# hooke/stiffness with absolute damping: F = kn d + gamman_abs d' (limitForce:",
            "# never tensile, as the fitted one-sided law)",
            "pair_style gran model hooke/stiffness tangential history absolute_damping on "
            "limitForce on",
            "pair_coeff * *",
            f"fix m1 all property/global kn peratomtypepair 2 {type_pair(c.stiffness)}",
            f"fix m2 all property/global gamman_abs peratomtypepair 2 {type_pair(c.damping)}",
            "# NOT FITTED (placeholders): tangential stiffness kt = 2/7 kn, no tangential damping",
            f"fix m3 all property/global kt peratomtypepair 2 {type_pair(2.0 / 7.0 * c.stiffness)}",
            f"fix m4 all property/global gammat_abs peratomtypepair 2 {type_pair(0.0)}",
        ]
    else:
        model = [
            "# Hertz with Tsuji damping from the restitution (limitForce: never tensile)",
            "pair_style gran model hertz tangential history limitForce on",
            "pair_coeff * *",
            "fix m1 all property/global youngsModulus peratomtype "
            f"{number(c.youngs_modulus)} {number(c.plate_youngs_modulus)}",
            "fix m2 all property/global poissonsRatio peratomtype "
            f"{number(c.poisson_ratio)} {number(c.plate_poisson_ratio)}",
            "# restitution measured for grain-plate; used for grain-grain too",
            f"fix m3 all property/global coefficientRestitution peratomtypepair 2 "
            f"{type_pair(c.restitution)}",
            "# warns when the step exceeds the guidance (needs youngsModulus: Hertz only)",
            f"fix ts_check all check/timestep/gran 1000 {LIGGGHTS_RAYLEIGH_FRACTION:g} "
            f"{LIGGGHTS_RAYLEIGH_FRACTION:g}",
        ]
    return [
        "# atom type 1 = grain, atom type 2 = sensor plate (wall mesh); units si",
        *model,
        f"# coefficientFriction: {c.friction_note()}",
        f"fix m5 all property/global coefficientFriction peratomtypepair 2 {type_pair(c.friction)}",
        f"timestep {number(step)}",
    ]


def write(c):
    """LIGGGHTS lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    return snippet(c, "LIGGGHTS", "#", _hertz_step, _lines)
