"""The stream as a LAMMPS deck: box, particle classes, the moving plate and the sensor.

Why the plate is built this way (the exact-physics argument):

* The plate is a **region wall**, ``region plate block ... side out move NULL NULL v_zp``
  with ``fix wall/gran/region granular``: an exactly flat, finite plate (edges and
  corners included), against which LAMMPS' contact has ``m* =`` the particle's mass and
  ``R* =`` its radius, the values :func:`~contactlab.laws.lammps.granular_model`
  maps the law with, so every particle-plate contact realises the toolkit's law exactly,
  as in the single-impact bench. A sphere of large radius (the drop bench's plate) is
  not flat, and a rigid body of particles is bumpy; LAMMPS 2025 has no moving mesh wall
  in its GRANULAR package.
* The **sensor** is one extra atom (type ``K + 1``, no pair interaction, no gravity) of
  mass ``m1`` held by ``fix spring/self k1`` and ``fix viscous c1`` on the z axis, and
  pushed by ``fix addforce`` with minus the sum of the plate's contact forces on the
  particles (``compute reduce`` of the walls' per-atom forces, summed over all MPI
  ranks; one reduction gives the forces and the contact counts, one the sensor's
  position, and the sensor's velocity at the step's end is a third: the global
  reductions are a step's fixed cost under MPI). Its z displacement moves the region
  (``v_zp``). So the sensor is integrated by LAMMPS' own velocity Verlet, in lock-step
  with the particles and with no Python in the loop: at the force stage of each step
  both see the positions of that step, and the region's velocity ``(zp - zp_prev)/dt``
  equals the sensor's half-step velocity, the velocity the particles have at that stage
  (velocity Verlet), so the contact's damping sees the true relative velocity. The wall
  fixes are defined before ``addforce``, so the sensor is pushed by the contact forces
  of the same step.
* One wall fix per class (its group is the class's atom type), because the mapping
  depends on the class's ``m*`` and ``R*``. Particle-particle contacts use, for classes
  ``i <= j``, class ``i``'s mapped law (LAMMPS needs one model per type pair; these
  contacts are not what the sensor measures and no toolkit law describes them).
* Straw (rigid clumps of spheres) adds molecule IDs, a wider ghost cut-off, its own
  integration and centre-of-mass velocities in the dump: :mod:`dem_check.stream.straw`.

Sign: LAMMPS z is the plate's outward normal (up); ``x1 = z_rest - z_sensor`` (into the
sensor) and ``S1 = k1 x1 + c1 v1``; the contact force is ``sum fz`` of the particles.
"""

from contactlab.laws.lammps import TANGENTIAL, granular_model
from dem_check.engines.lammps.oblique import tangential_words
from dem_check.engines.lammps.scene import granular_setup
from dem_check.stream import straw

__all__ = [
    "CONTACTS",
    "RECORD",
    "create_line",
    "deck_lines",
    "group_lines",
    "insert_lines",
    "sweep_lines",
]

RECORD = "record"
"""ID of the ``fix vector`` holding, per step: step, contact force, x1, v1."""

CONTACTS = ("pid1", "step", "type", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz")
"""Columns of the contact dump: one row per particle touching the plate per step
(``pid1`` is the schedule's particle id plus one: 0 marks an atom just created)."""

_SENSOR_ID = 1
"""The sensor atom is created first."""


def _words(grain, law, tangential):
    model = granular_model(law, grain.mass, grain.radius)
    return model.words(
        TANGENTIAL if tangential is None else tangential_words(tangential, grain.radius)
    )


def _box(schedule, case):
    table, plate = schedule.table, case.plate
    rmax = max(schedule.extent(k) for k in range(len(schedule.classes)))
    half_x, half_y = plate.length / 2.0, plate.width / 2.0
    xs = [*table.get("x [m]", []), -half_x, half_x]
    ys = [*table.get("y [m]", []), -half_y, half_y]
    top = max([*table.get("z [m]", []), case.feed.release]) + 4.0 * rmax
    margin = 4.0 * rmax
    return (
        min(xs) - margin,
        max(xs) + margin,
        min(ys) - margin,
        max(ys) + margin,
        -plate.thickness - 8.0 * rmax,
        top,
    )


def deck_lines(case, schedule, dump_path):
    """``[(line, what), ...]``: the deck up to the first insertion (module docstring)."""
    sensor, plate = case.sensor, case.plate
    classes = schedule.classes
    count = len(classes)
    box = _box(schedule, case)
    z_rest = box[4] + 2.0 * max(c[1].radius for c in classes)
    setup = "the stream's LAMMPS box"
    lines = [
        *granular_setup("f f f", setup),
        ("region box block " + " ".join(repr(float(b)) for b in box), setup),
        (f"create_box {count + 1} box", setup),
        ("fix pid all property/atom i_pid ghost no", setup),
        (f"create_atoms {count + 1} single 0.0 0.0 {z_rest!r} units box", "the sensor atom"),
        (f"set atom {_SENSOR_ID} diameter {1e-4!r} mass {sensor.mass!r} i_pid -1", "sensor mass"),
        (f"group sensor type {count + 1}", setup),
        ("thermo_modify lost ignore", setup),
        ("pair_style granular", setup),
    ]
    rmax = max(c[1].radius for c in classes)
    clumps = straw.has_straw(schedule)
    if clumps:
        lines += straw.setup_lines(schedule, rmax)
    words = [_words(grain, law, tangential) for _, grain, law, tangential in classes]
    lines.append((f"pair_coeff * * {words[0]}", "the particles' laws"))
    for i in range(count):
        for j in range(i, count):
            lines.append((f"pair_coeff {i + 1} {j + 1} {words[i]}", f"class {i + 1}'s law"))
    for i in range(count + 1):
        lines.append((f"neigh_modify exclude type {i + 1} {count + 1}", setup))
    lines += [
        (f"neighbor {rmax!r} bin", setup),
        ("neigh_modify delay 0 every 1 check yes", setup),
        ("compute sensor_z sensor reduce sum z", setup),
        (f"variable zp equal c_sensor_z-{z_rest!r}", setup),
        (
            f"region plate block {-plate.length / 2!r} {plate.length / 2!r} "
            f"{-plate.width / 2!r} {plate.width / 2!r} {-plate.thickness!r} 0.0 side out "
            "move NULL NULL v_zp units box",
            "the plate",
        ),
    ]
    for i, (name, _, law, _) in enumerate(classes):
        lines += [
            (f"group c{i + 1} type {i + 1}", setup),
            (
                f"fix wall{i + 1} c{i + 1} wall/gran/region granular {words[i]} region plate "
                "contacts",
                f"the law of {name} class {i + 1} ({law!r}) on the plate",
            ),
        ]
    ids = range(1, count + 1)
    lines += [
        (
            "compute walls all reduce sum "
            + " ".join(f"f_wall{i}[4]" for i in ids)
            + " "
            + " ".join(f"f_wall{i}[1]" for i in ids),
            setup,
        ),
        ("variable force equal " + "+".join(f"c_walls[{i}]" for i in ids), setup),
        ("variable load equal -v_force", setup),
        ("variable ntouch equal " + "+".join(f"c_walls[{count + i}]" for i in ids), setup),
        (f"fix sensor_spring sensor spring/self {sensor.stiffness!r} z", "sensor stiffness k1"),
        (f"fix sensor_damper sensor viscous {sensor.damping!r}", "sensor damping c1"),
        ("fix sensor_load sensor addforce 0.0 0.0 v_load", setup),
        ("fix sensor_axis sensor setforce 0.0 0.0 NULL", setup),
        (f"group particles type 1:{count}", setup),
    ]
    g = schedule.gravity
    if any(g):
        magnitude = float((g @ g) ** 0.5)
        lines.append(
            (
                f"fix gravity particles gravity {magnitude!r} vector "
                + " ".join(repr(float(c / magnitude)) for c in g),
                "gravity",
            )
        )
    lines += [
        (f"fix integrate {'free' if clumps else 'all'} nve/sphere", setup),
        (f"timestep {schedule.time_step!r}", "time_step"),
        ("variable step equal step", setup),
        (f"variable x1 equal {z_rest!r}-c_sensor_z", setup),
        (f"variable v1 equal -vz[{_SENSOR_ID}]", setup),
        (f"fix {RECORD} all vector 1 v_step v_force v_x1 v_v1", setup),
        ("variable astep atom step", setup),
        ("variable touch atom " + "+".join(f"f_wall{i}[1]" for i in ids), setup),
        *[
            (f"variable w{axis} atom " + "+".join(f"f_wall{i}[{col}]" for i in ids), setup)
            for axis, col in (("x", 2), ("y", 3), ("z", 4))
        ],
        ("variable quiet equal v_ntouch<0.5", setup),
        *(straw.velocity_lines() if clumps else []),
        (
            f"dump contacts particles custom 1 {dump_path} i_pid v_astep type x y z "
            + " ".join(straw.VELOCITY_COLUMNS if clumps else ("vx", "vy", "vz"))
            + " v_wx v_wy v_wz",
            setup,
        ),
        ("dump_modify contacts thresh v_touch > 0.5 skip v_quiet format float %.17g", setup),
    ]
    return lines


def insert_lines(row, pid, tag, molecule=False):
    """Lines giving the atom of ``tag`` (just created) the schedule row's size, density,
    velocity and ``i_pid = pid + 1`` (and ``mol = pid + 1``: a straw's sphere)."""
    clump = f" mol {pid + 1}" if molecule else ""
    return [
        (
            f"set atom {tag} diameter {row['diameter [m]']!r} density "
            f"{row['density [kg/m^3]']!r} vx {row['vx [m/s]']!r} vy {row['vy [m/s]']!r} "
            f"vz {row['vz [m/s]']!r} i_pid {pid + 1}{clump}",
            f"particle {pid}",
        ),
    ]


def create_line(row, pid, at=None):
    """The line creating the atom of one schedule row (its type is its class plus one) at
    its position, or at ``at`` [m] (a straw's sphere)."""
    t = int(row["cls"]) + 1
    x, y, z = (row["x [m]"], row["y [m]"], row["z [m]"]) if at is None else map(float, at)
    return (f"create_atoms {t} single {x!r} {y!r} {z!r} units box", f"particle {pid}")


def group_lines(schedule):
    """Lines adding the new atoms to their class groups, to ``particles`` (and, with
    straw, to ``straws`` and ``free``): LAMMPS' groups are static, atoms created later
    join only when asked."""
    count = len(schedule.classes)
    lines = [(f"group c{t} type {t}", "groups") for t in range(1, count + 1)]
    lines.append((f"group particles type 1:{count}", "groups"))
    return lines + (straw.group_lines(schedule) if straw.has_straw(schedule) else [])


def sweep_lines(ceiling, molecules=False):
    """Lines deleting particles that rebounded above ``ceiling`` [m] (they would meet the
    insertions; IDs are kept: ``compress no``; ``molecules``: whole straws go)."""
    whole = " mol yes" if molecules else ""
    return [
        (f'variable gone atom "vz > 0 && z > {ceiling!r} && i_pid > 0"', "sweep"),
        ("group gone variable gone", "sweep"),
        (f"delete_atoms group gone compress no{whole}", "sweep"),
        ("group gone clear", "sweep"),
    ]
