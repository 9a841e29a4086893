"""The ground truth of a stream: one row per particle that touched the plate.

From the contact dump (one row per particle touching the plate per step) a particle's
**contacts** are runs of consecutive steps with a positive normal force (contactlab's
contact: it ends when the force reaches zero; with ``limit_damping`` LAMMPS keeps an
overlap a few steps longer at zero force); the first is its impact, later ones are
re-contacts (a bounce back onto the plate, rolling on and off). Per impact:

* ``touch [s]``: when the overlap began, ``t_n - d_n / v`` from the first step in
  contact ``n``, its overlap ``d_n`` (radius minus the centre's height over the plate,
  whose position is the sensor's) and the approach speed ``v`` of the free flight
  (second order in the step, so signals can be aligned to it); ``contact_time [s]``:
  steps in contact times the step (as
  :class:`~dem_check.engines.lammps.realise.RealisedImpact` counts);
  ``separation [s]``: touch plus contact time;
* ``normal_speed`` and ``tangential_speed [m/s]`` at touch: the velocity the particle had
  on the last free step. LAMMPS writes ``v(n) = v(n - 1/2) + dt f(n) / (2 m)`` at the
  first contact step, and ``v(n - 1/2)`` (the velocity Verlet half step) is the free
  flight's, so the dump's velocity is corrected by the half step of contact force;
* ``rebound_normal_speed`` and ``rebound_tangential_speed [m/s]``: the velocity at the
  last contact step plus the half step of its force, the same way;
* ``peak_force [N]`` and ``impulse [N*s]`` (the sum of force times step, velocity
  Verlet's own momentum change) of the normal contact force over the contact.

A straw (a rigid clump of spheres, :mod:`dem_check.stream.straw`) is one particle: per
step its spheres' plate forces are summed, its velocity is its centre of mass's (the
dump's straw columns), its overlap that of its lowest sphere, and its mass the clump's;
so its ``impulse`` is the clump's momentum change, and its touch is interpolated with
the centre of mass's approach speed (exact for a clump that does not spin).

Every contact is a row (``contact`` 0 the impact, 1, 2 ... re-contacts; ``recontacts``
their number for the particle): a re-contact makes its own signal, which a detector
should find.
"""

import numpy as np
import pandas as pd

__all__ = ["TRUTH_COLUMNS", "impacts_truth"]

TRUTH_COLUMNS = (
    "pid",
    "kind",
    "cls",
    "contact",
    "mass [kg]",
    "diameter [m]",
    "touch [s]",
    "separation [s]",
    "contact_time [s]",
    "normal_speed [m/s]",
    "tangential_speed [m/s]",
    "rebound_normal_speed [m/s]",
    "rebound_tangential_speed [m/s]",
    "peak_force [N]",
    "impulse [N*s]",
    "recontacts",
)


def _segment(segment, pid, contact, dt, table, plate):
    """The truth row of one contact (consecutive steps with a positive force)."""
    mass = float(table.at[pid, "mass [kg]"])
    half = 0.5 * dt / mass
    head, tail = segment.iloc[0], segment.iloc[-1]
    vz0 = head["vz"] - half * head["fz"]
    vx0, vy0 = head["vx"] - half * head["fx"], head["vy"] - half * head["fy"]
    fz = segment["fz"].to_numpy()
    n = int(head["step"])
    x1, v1 = plate
    overlap = 0.5 * float(table.at[pid, "diameter [m]"]) - (head["z"] + x1[n])
    approach = -v1[n] - vz0
    # a re-contact may start from a standing overlap (the plate pushing back): no
    # interpolation is then possible, and the touch is the step's start
    before = min(max(overlap / approach, 0.0), dt) if approach > 0.0 else dt
    touch = n * dt - before
    return {
        "pid": int(pid),
        "kind": table.at[pid, "kind"],
        "cls": int(table.at[pid, "cls"]),
        "contact": contact,
        "mass [kg]": mass,
        "diameter [m]": float(table.at[pid, "diameter [m]"]),
        "touch [s]": touch,
        "separation [s]": touch + len(segment) * dt,
        "contact_time [s]": len(segment) * dt,
        "normal_speed [m/s]": -vz0,
        "tangential_speed [m/s]": float(np.hypot(vx0, vy0)),
        "rebound_normal_speed [m/s]": tail["vz"] + half * tail["fz"],
        "rebound_tangential_speed [m/s]": float(
            np.hypot(tail["vx"] + half * tail["fx"], tail["vy"] + half * tail["fy"])
        ),
        "peak_force [N]": float(fz.max()),
        "impulse [N*s]": float(fz.sum() * dt),
    }


def impacts_truth(contacts, schedule, steps):
    """The truth table (module docstring) of a contact dump, its schedule and the step
    series (``x1 [m]``, ``v1 [m/s]``: the plate's position and velocity): one row per
    contact, ``contact`` 0 for a particle's impact and 1, 2 ... for its re-contacts
    (``recontacts`` counts them on every row of the particle)."""
    if contacts.empty:
        return pd.DataFrame(columns=TRUTH_COLUMNS)
    dt, table = schedule.time_step, schedule.table
    plate = steps["x1 [m]"].to_numpy(), steps["v1 [m/s]"].to_numpy()
    rows = []
    contacts = _clumps_as_one(contacts, table)
    pressing = contacts[contacts["fz"] > 0.0]
    for pid, group in pressing.groupby("pid", sort=True):
        numbers = group["step"].to_numpy()
        breaks = np.flatnonzero(np.diff(numbers) != 1) + 1
        edges = np.concatenate([[0], breaks, [numbers.size]])
        for k in range(edges.size - 1):
            row = _segment(group.iloc[edges[k] : edges[k + 1]], pid, k, dt, table, plate)
            row["recontacts"] = int(edges.size - 2)
            rows.append(row)
    return pd.DataFrame(rows, columns=TRUTH_COLUMNS).sort_values("touch [s]").reset_index(drop=True)


def _clumps_as_one(contacts, table):
    """The dump with each straw's rows of a step made one: forces summed, the lowest
    sphere's height, the centre of mass's velocity (every sphere's row carries it)."""
    if "spheres" not in table or not (table["spheres"] > 1).any():
        return contacts
    clump = contacts["pid"].map(table["spheres"]).to_numpy() > 1
    merged = (
        contacts[clump]
        .groupby(["pid", "step"], sort=True)
        .agg(
            type=("type", "first"),
            x=("x", "first"),
            y=("y", "first"),
            z=("z", "min"),
            vx=("vx", "first"),
            vy=("vy", "first"),
            vz=("vz", "first"),
            fx=("fx", "sum"),
            fy=("fy", "sum"),
            fz=("fz", "sum"),
        )
        .reset_index()
    )
    frame = pd.concat([contacts[~clump], merged[list(contacts.columns)]], ignore_index=True)
    return frame.sort_values(["pid", "step"], kind="stable").reset_index(drop=True)
