"""The drop bench as a LAMMPS deck: the grain, the sensor (a plane or a sprung plate), the run.

Geometry (``units si``, LAMMPS z up; the model's x axis points down, into the sensor):

* the **grain** is atom 1 (type 1), a sphere of the grain's diameter and mass, released
  ``gap`` above the sensor with velocity ``-v`` along z;
* :meth:`Sensor.rigid` is a plane, ``fix wall/gran granular ... zplane 0.0 NULL``: the
  grain-wall contact has ``m* = m2`` and ``R* = R2``;
* a **real sensor** is atom 2 (type 2), the plate: a sphere of radius
  :data:`PLATE_RADIUS_FACTOR` grain radii and mass ``m1``, its top at ``z = 0``, held by
  ``fix spring/self k1 z`` and damped by ``fix viscous c1``, with ``fix setforce 0 0
  NULL`` keeping it on the impact axis. Its displacement ``x1`` (down) and velocity give
  ``S1 = k1 x1 + c1 v1``. The grain-plate contact is ``pair_style granular`` with
  ``m* = m1 m2 / (m1 + m2)`` and ``R* = R2 Rp / (R2 + Rp)``; the law is mapped with these
  (:func:`~contactlab.laws.lammps.granular_model`), so the force against the
  overlap is the law's whatever the plate's radius: the radius brings no error in the
  force (the sphere's curvature enters only through ``R*``, which the mapping absorbs).
  What it brings is rounding: the overlap is ``R2 + Rp - r`` from centre distances of
  ``~ (1 + factor) R2``, so its absolute rounding is ``~1e-16 (1 + factor) R2`` (about
  3e-18 m for a 5 mm grain, 1e-12 of the paper's overlaps). Mapping with ``R* = R2``
  instead (a flat plate) would have made the Hertz stiffness ``sqrt(factor / (1 +
  factor))`` = 0.953 of the law's.

Both bodies integrate with ``fix nve/sphere`` (velocity Verlet). One fix ``vector``
records, every step, the step number, the grain's and the plate's z and z-velocity, and
the grain's z force (the contact force: nothing else acts on the grain).
"""

from dataclasses import dataclass

from contactlab.laws.lammps import granular_model
from dem_check.engines.record import COLUMNS, PLATE_RADIUS_FACTOR, DropCase, drop_geometry

__all__ = [
    "COLUMNS",
    "PLATE_RADIUS_FACTOR",
    "RECORD",
    "DropDeck",
    "drop_deck",
    "granular_setup",
]


RECORD = "record"
"""ID of the fix that records the steps."""


def granular_setup(boundary, what):
    """The first lines of a granular deck, ``[(line, what), ...]``: SI units, finite-size
    spheres, atoms found by ID, the ``boundary`` (e.g. ``"f f f"``) and ghost atoms'
    velocities (the granular pair styles read them)."""
    return [
        ("units si", what),
        ("atom_style sphere", what),
        ("atom_modify map array", what),
        (f"boundary {boundary}", what),
        ("comm_modify vel yes", what),
    ]


@dataclass(frozen=True)
class DropDeck(DropCase):
    """One drop test as LAMMPS input lines (build it with :func:`drop_deck`).

    Attributes
    ----------
    model : GranularModel
        The law as a LAMMPS granular model for this contact's ``m*`` and ``R*``.
    height : float
        Box height above the sensor [m]: the grain's largest possible travel.
    grain, sensor, law, velocity, time_step, gap, plate_radius
        As for :class:`~dem_check.engines.record.DropCase`.
    """

    model: object
    height: float

    def lines(self):
        """``[(line, what), ...]``: the deck, each line with what it sets (for errors)."""
        r2 = self.grain.radius
        rigid = self.sensor.is_rigid
        bottom = -(2.0 * self.plate_radius + r2) if not rigid else -r2
        side = 2.0 * (r2 if rigid else self.plate_radius)
        setup = "the LAMMPS box"
        lines = [
            *granular_setup("f f f", setup),
            (
                f"region box block {-side!r} {side!r} {-side!r} {side!r} {bottom!r} "
                f"{self.height!r}",
                "the box (grain radius, gap and travel)",
            ),
            (f"create_box {1 if rigid else 2} box", setup),
            (f"create_atoms 1 single 0.0 0.0 {r2 + self.gap!r}", "the grain's release gap"),
            (
                f"set atom 1 diameter {2.0 * r2!r} mass {self.grain.mass!r}",
                "the grain's diameter and mass",
            ),
            (f"velocity all set 0.0 0.0 {-self.velocity!r}", "velocity"),
            (f"neighbor {r2!r} nsq", setup),
            ("neigh_modify delay 0 every 1 check yes", setup),
            ("pair_style granular", setup),
            (f"pair_coeff * * {self.model.words()}", self.model.what),
        ]
        if rigid:
            lines.append(
                (
                    f"fix sensor all wall/gran granular {self.model.words()} zplane 0.0 NULL",
                    self.model.what,
                )
            )
        else:
            lines += self._plate_lines()
        lines += [
            ("fix integrate all nve/sphere", setup),
            (f"timestep {self.time_step!r}", "time_step"),
            ("variable step equal step", setup),
            ("variable z2 equal z[1]", setup),
            ("variable vz2 equal vz[1]", setup),
            ("variable fz2 equal fz[1]", setup),
            (f"variable z1 equal {'0.0' if rigid else 'z[2]'}", setup),
            (f"variable vz1 equal {'0.0' if rigid else 'vz[2]'}", setup),
            (f"fix {RECORD} all vector 1 " + " ".join(f"v_{c}" for c in COLUMNS), setup),
        ]
        return lines

    def _plate_lines(self):
        sensor, rp = self.sensor, self.plate_radius
        what = "the sensor plate (mass, stiffness, damping)"
        return [
            (f"create_atoms 2 single 0.0 0.0 {-rp!r}", "plate_radius"),
            (f"set atom 2 diameter {2.0 * rp!r} mass {sensor.mass!r}", what),
            ("group plate id 2", what),
            (f"fix plate_spring plate spring/self {sensor.stiffness!r} z", "sensor stiffness"),
            (f"fix plate_damper plate viscous {sensor.damping!r}", "sensor damping"),
            ("fix plate_axis plate setforce 0.0 0.0 NULL", what),
        ]


def drop_deck(grain, sensor, law, velocity, time_step, duration, gap=None, plate_radius=None):
    """The :class:`DropDeck` of one drop test.

    Parameters
    ----------
    grain, sensor, law, velocity, time_step
        As for :func:`~dem_check.engines.lammps.drop.drop_test`; ``time_step`` already
        checked [s].
    duration : float
        Longest time simulated after touch [s] (sizes the box).
    gap, plate_radius : float, optional
        Release gap and plate radius [m] (:func:`~dem_check.engines.record.drop_geometry`).

    Returns
    -------
    DropDeck

    Raises
    ------
    ParameterError
        For a law LAMMPS cannot hold, or a gap or plate radius not > 0.
    """
    geometry = drop_geometry(grain, sensor, velocity, time_step, gap, plate_radius)
    model = granular_model(law, geometry.effective_mass, geometry.effective_radius)
    r2, gap = grain.radius, geometry.gap
    # the grain never moves faster than at release (no gravity, dissipative contact)
    height = r2 + gap + velocity * (gap / velocity + duration) + 4.0 * r2
    return DropDeck(
        grain, sensor, law, velocity, time_step, gap, geometry.plate_radius, model, height
    )
