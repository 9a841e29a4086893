"""Straw in the stream's deck: rigid clumps of spheres (LAMMPS ``fix rigid/small``).

A straw is a row of spheres of one class (its LAMMPS atom type) sharing a molecule ID
(the particle id plus one; ``fix property/atom mol``), integrated as one rigid body by
``fix rigid/small ... molecule`` instead of ``fix nve/sphere``. What the deck adds when
a case has straw (:func:`setup_lines`):

* ``comm_modify cutoff``: LAMMPS needs ghost atoms out to a body's extent;
* ``neigh_modify exclude molecule/intra straws``: a clump's own spheres do not touch
  each other (only straws have molecule IDs: grains and chaff keep molecule 0 and stay
  out of the ``straws`` group, whose exclusion alone is intra-molecular);
* the group ``free`` (the sensor, grains and chaff) that ``fix nve/sphere`` integrates;
* ``thermo_style custom step``: the default thermo temperature counts the rigid
  bodies' constrained degrees of freedom and refuses an empty box;
* per-atom velocities for the contact dump (:data:`VELOCITY_COLUMNS`): a straw
  sphere's row carries its **clump's centre-of-mass velocity** (``compute vcm/chunk``
  over molecules, spread back to the atoms), the velocity the truth needs for the
  clump's momentum; a sphere's row its own.

LAMMPS' rigid-body fixes fix their bodies when defined (``create_atoms`` cannot add to
a ``rigid/small`` body, and crashed creating atoms beside live bodies), so once a straw
is in the box every slot releases the bodies (:data:`UNFIX_RIGID`) before its sweep and
insertions and defines them again after (:data:`FIX_RIGID`): the bodies are rebuilt
from their atoms' positions and velocities, which is what ``fix rigid/small``'s default
``reinit yes`` already does at every ``run``'s set-up; a body's motion carries on to
rounding.
Deleting rebounded particles deletes whole molecules (``mol yes``).
"""

import numpy as np

__all__ = [
    "FIX_RIGID",
    "UNFIX_RIGID",
    "VELOCITY_COLUMNS",
    "free_types",
    "group_lines",
    "has_straw",
    "setup_lines",
    "sphere_centres",
    "straw_types",
    "velocity_lines",
]

FIX_RIGID = ("fix rigid straws rigid/small molecule", "straw: rigid bodies")
"""The straws' rigid bodies, (re)defined after each slot's insertions."""

UNFIX_RIGID = ("unfix rigid", "straw: bodies released for the slot's sweep and insertions")
"""Before each slot's sweep and insertions: LAMMPS 2025 crashed (a segmentation fault)
creating atoms while ``fix rigid/small`` held bodies."""

VELOCITY_COLUMNS = ("v_ux", "v_uy", "v_uz")
"""The contact dump's velocity columns in a case with straw (module docstring)."""


def has_straw(schedule):
    """Whether any class of ``schedule`` is a straw."""
    return any(offsets is not None for offsets in schedule.clumps)


def straw_types(schedule):
    """LAMMPS atom types of the straw classes (class plus one)."""
    return [k + 1 for k, offsets in enumerate(schedule.clumps) if offsets is not None]


def free_types(schedule):
    """Atom types ``fix nve/sphere`` integrates: single spheres and the sensor."""
    count = len(schedule.classes)
    return [k + 1 for k, offsets in enumerate(schedule.clumps) if offsets is None] + [count + 1]


def _type_list(types):
    return " ".join(str(t) for t in types)


def group_lines(schedule):
    """Lines (re)building the groups ``straws`` and ``free`` (LAMMPS' groups are static:
    atoms created later join only when asked)."""
    return [
        (f"group straws type {_type_list(straw_types(schedule))}", "groups"),
        (f"group free type {_type_list(free_types(schedule))}", "groups"),
    ]


def setup_lines(schedule, skin):
    """The deck's straw set-up (module docstring), after ``pair_style`` and before the
    walls; ``skin`` [m] is the neighbour skin."""
    reach = max(schedule.extent(k) for k in range(len(schedule.classes)))
    setup = "straw: rigid clumps"
    return [
        ("fix molid all property/atom mol ghost yes", setup),
        (f"comm_modify cutoff {2.0 * reach + 2.0 * skin!r}", setup),
        *group_lines(schedule),
        ("neigh_modify exclude molecule/intra straws", setup),
        ("thermo_style custom step", setup),
    ]


def velocity_lines():
    """Per-atom velocity variables for the contact dump (module docstring)."""
    setup = "straw: centre-of-mass velocities in the contact dump"
    lines = [
        ("compute bodies straws chunk/atom molecule nchunk every ids every compress yes", setup),
        ("compute body_v straws vcm/chunk bodies", setup),
        (
            "compute body_u straws chunk/spread/atom bodies c_body_v[1] c_body_v[2] c_body_v[3]",
            setup,
        ),
    ]
    for k, axis in enumerate("xyz"):
        lines.append((f"variable u{axis} atom v{axis}+(c_body_u[{k + 1}]-v{axis})*(mol>0)", setup))
    return lines


def sphere_centres(row, offsets):
    """Centres [m] of a straw's spheres: its schedule row's centre of mass plus the
    offsets along its axis."""
    centre = np.array([row["x [m]"], row["y [m]"], row["z [m]"]])
    axis = np.array([row["axis_x [-]"], row["axis_y [-]"], row["axis_z [-]"]])
    return [centre + o * axis for o in offsets]
