"""LAMMPS input: ``pair_style granular`` for grain-grain, ``fix wall/gran`` for the sensor.

The snippet is meant for ``include`` in a user's deck after ``units si``, ``atom_style
sphere``, the box and the atoms (the grain is atom type 1) and ``comm_modify vel yes``. It
sets the grain-grain pair model, the sensor plate as the plane ``z = 0`` (grain above,
moving towards -z) and the time step; it creates no atoms, sets no velocity, integrates
nothing and does not run.

The grain-plate contact is the fitted law exactly, in the words of the one law -> LAMMPS
mapping, :func:`contactlab.laws.lammps.granular_model` (which the LAMMPS engine of
:mod:`dem_check.engines.lammps` runs too; LAMMPS 22 Jul 2025, GRANULAR package). A plane
wall has ``R* = R`` and ``m* = m`` of the grain, and LAMMPS takes a wall's coefficients
as given (no mixing), so:

* linear ``(k, c)``: ``hooke k c damping velocity``;
* Hertz ``(E*)``: ``hertz (4/3) E* 0 damping velocity``;
* damped Hertz ``(E*, e)``: ``hertz (4/3) E* e damping coeff_restitution`` (``F = k a d``
  with ``a = sqrt(R d)`` is ``(4/3) E* sqrt(R) d**1.5 = kH d**1.5``, and the damping is
  ``sqrt(5) beta sqrt(m* Fe/d) d'`` with ``beta = -ln e/sqrt(pi^2 + ln^2 e)``: the fit's
  Tsuji damping, independent of the grain size, so the mapping's input is the fit's
  ``e``);
* ``limit_damping``: the force never pulls, as in the fitted law, so the realised rebound
  is the fitted law's (not ``e``).

Grain-grain contacts are not measured by a grain-plate impact (NOT FITTED): the snippet
writes Hertz with the grain's own modulus (``hertz/material E e nu``, which LAMMPS mixes
to ``E* = E/(2(1-nu^2))``) and the same ``e`` (same Tsuji damping factor, so the same
one-sided rebound), or the linear law's ``k, c`` as they are. Tangential models are
placeholders (NOT FITTED): Mindlin with ``8 G*`` of grain and plate (Hertz) or
``kt = 2/7 k`` (linear), and the friction given or 0.5.
"""

from contactlab.inverse.export.contact import number
from contactlab.laws.lammps import granular_model

__all__ = ["LAMMPS_STEPS_PER_CONTACT", "write"]

LAMMPS_STEPS_PER_CONTACT = 200
"""Time step = contact time / 200: velocity Verlet evaluates the damping at the half-step
velocity (first order); at 200 steps per contact the realised rebound errs by at most
0.16 % and the peak force by 0.3 % (measured in LAMMPS over release phases,
``docs/dem_check.md``)."""


def _mindlin_stiffness(c):
    """``8 G*`` [Pa] of grain and plate, ``1/G* = (2-nu1)/G1 + (2-nu2)/G2`` (Mindlin)."""
    compliance = (2.0 - c.poisson_ratio) / c.shear_modulus
    compliance += (2.0 - c.plate_poisson_ratio) / c.plate_shear_modulus
    return 8.0 / compliance


def write(c):
    """LAMMPS lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    step = c.contact_time / LAMMPS_STEPS_PER_CONTACT
    why = f"contact time / {LAMMPS_STEPS_PER_CONTACT} (first-order damping: < 0.2 % in rebound)"
    mu = number(c.friction)
    model = granular_model(c.contact_law, c.mass, c.radius)  # a plane wall: m* = m, R* = R
    if c.family == "linear":
        tangential = f"tangential linear_history {number(2.0 / 7.0 * c.stiffness)} 0.0 {mu}"
        pair = wall = model.words(tangential, number)
        notes = [
            "# grain-grain: NOT FITTED, the fitted k and c taken as they are",
            f"# tangential: NOT FITTED (kt = 2/7 k, no tangential damping); friction: "
            f"{c.friction_note()}",
        ]
    else:
        wall = model.words(f"tangential mindlin {number(_mindlin_stiffness(c))} 1.0 {mu}", number)
        pair = (
            f"hertz/material {number(c.youngs_modulus)} {number(model.damping_coefficient)} "
            f"{number(c.poisson_ratio)} damping {model.damping} "
            f"tangential mindlin NULL 1.0 {mu} limit_damping"
        )
        notes = [
            "# grain-grain: NOT FITTED, Hertz of the grain's own E and nu (E* = E/(2(1-nu^2)))",
            "# and the same damping input (same Tsuji damping factor, same rebound)",
            "# hertz k = (4/3) E*: F = k sqrt(R d) d = kH d**1.5 on the plane (R = grain radius)",
            f"# tangential: NOT FITTED (Mindlin, 8 G* of grain and plate); friction: "
            f"{c.friction_note()}",
        ]
    body = [
        "# include after: units si, atom_style sphere, the box and the atoms (grain = atom",
        "# type 1), comm_modify vel yes. Then add fix nve/sphere, a velocity and run.",
        "# limit_damping: the contact force never pulls, as in the fitted law",
        *notes,
        "pair_style granular",
        f"pair_coeff * * {pair}",
        "# sensor plate: the plane z = 0, grain above it moving towards -z",
        f"fix sensor_plate all wall/gran granular {wall} zplane 0.0 NULL",
        f"timestep {number(step)}",
    ]
    return [*c.header("LAMMPS", "#", why, step), *body]
