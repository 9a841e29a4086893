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
* ``rebound_normal_speed [m/s]``: the velocity at the last contact step plus the
  half step of its force, the same way;
* ``peak_force [N]`` and ``impulse [N*s]`` (the sum of force times step, velocity
  Verlet's own momentum change) of the normal contact force over the first contact;
  ``recontacts`` and ``total_impulse [N*s]`` over all contacts.
"""

import numpy as np
import pandas as pd

__all__ = ["TRUTH_COLUMNS", "impacts_truth"]

TRUTH_COLUMNS = (
    "pid",
    "kind",
    "cls",
    "mass [kg]",
    "diameter [m]",
    "touch [s]",
    "separation [s]",
    "contact_time [s]",
    "normal_speed [m/s]",
    "tangential_speed [m/s]",
    "rebound_normal_speed [m/s]",
    "peak_force [N]",
    "impulse [N*s]",
    "recontacts",
    "total_impulse [N*s]",
)


def impacts_truth(contacts, schedule, steps):
    """The truth table (module docstring) of a contact dump, its schedule and the step
    series (``x1 [m]``, ``v1 [m/s]``: the plate's position and velocity)."""
    if contacts.empty:
        return pd.DataFrame(columns=TRUTH_COLUMNS)
    dt = schedule.time_step
    table = schedule.table
    rows = []
    x1, v1 = steps["x1 [m]"].to_numpy(), steps["v1 [m/s]"].to_numpy()
    pressing = contacts[contacts["fz"] > 0.0]
    for pid, group in pressing.groupby("pid", sort=True):
        steps = group["step"].to_numpy()
        breaks = np.flatnonzero(np.diff(steps) != 1) + 1
        starts = np.concatenate([[0], breaks])
        ends = np.concatenate([breaks, [steps.size]])
        first = group.iloc[starts[0] : ends[0]]
        mass = float(table.at[pid, "mass [kg]"])
        half = 0.5 * dt / mass
        head, tail = first.iloc[0], first.iloc[-1]
        vz0 = head["vz"] - half * head["fz"]
        vx0, vy0 = head["vx"] - half * head["fx"], head["vy"] - half * head["fy"]
        fz = first["fz"].to_numpy()
        n = int(head["step"])
        plate_z, plate_vz = -x1[n], -v1[n]
        overlap = 0.5 * float(table.at[pid, "diameter [m]"]) - (head["z"] - plate_z)
        approach = plate_vz - vz0
        rows.append(
            {
                "pid": int(pid),
                "kind": table.at[pid, "kind"],
                "cls": int(table.at[pid, "cls"]),
                "mass [kg]": mass,
                "diameter [m]": float(table.at[pid, "diameter [m]"]),
                "touch [s]": n * dt - overlap / approach,
                "separation [s]": n * dt - overlap / approach + len(first) * dt,
                "contact_time [s]": len(first) * dt,
                "normal_speed [m/s]": -vz0,
                "tangential_speed [m/s]": float(np.hypot(vx0, vy0)),
                "rebound_normal_speed [m/s]": tail["vz"] + half * tail["fz"],
                "peak_force [N]": float(fz.max()),
                "impulse [N*s]": float(fz.sum() * dt),
                "recontacts": int(starts.size - 1),
                "total_impulse [N*s]": float(group["fz"].sum() * dt),
            }
        )
    return pd.DataFrame(rows, columns=TRUTH_COLUMNS).sort_values("touch [s]").reset_index(drop=True)
