"""Run an exported LAMMPS snippet as a user's deck would, and read what it realises.

:func:`realise_snippet` writes the smallest deck the snippet's header asks for (``units
si``, ``atom_style sphere``, a box, the grain as atom type 1, ``comm_modify vel yes``),
``include``\\ s the snippet (``contactlab export-dem --to lammps``), adds ``fix
nve/sphere`` and the grain's velocity towards the plate, and runs: what comes out is what
a user's simulation of a grain dropped on the sensor plate gets from the export.
"""

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from contactlab.validation import check_positive
from dem_check.engines.lammps.session import LammpsSession

__all__ = ["RealisedImpact", "realise_snippet"]

_GAP = 1e-6
"""Release gap between grain and plate [m] (the grain touches within a few steps)."""


@dataclass(frozen=True)
class RealisedImpact:
    """A grain's impact on the plate of an exported snippet, step by step.

    Attributes
    ----------
    time_step : float
        The snippet's time step [s].
    force : numpy.ndarray
        The plate's force on the grain along +z, per step [N].
    velocity : numpy.ndarray
        The grain's z-velocity per step [m/s].
    impact_speed : float
        [m/s].
    """

    time_step: float
    force: np.ndarray
    velocity: np.ndarray
    impact_speed: float

    @property
    def restitution(self):
        """Final rebound speed over impact speed [-]."""
        return float(self.velocity[-1]) / self.impact_speed

    @property
    def contact_time(self):
        """Steps with a positive force times the step [s] (resolution: one step)."""
        return self.time_step * int(np.count_nonzero(self.force > 0.0))

    @property
    def peak_force(self):
        """Largest force of the steps [N]."""
        return float(self.force.max())

    @property
    def min_force(self):
        """Smallest force of the steps [N]: negative if the contact pulled."""
        return float(self.force.min())


def realise_snippet(snippet_path, grain, velocity, contact_time):
    """Drop the grain on the snippet's plate in LAMMPS and record the impact.

    Parameters
    ----------
    snippet_path : str or pathlib.Path
        A file written by ``contactlab export-dem --to lammps``.
    grain : Grain
        The grain (atom type 1: its diameter and density).
    velocity : float
        Impact speed towards the plate [m/s].
    contact_time : float
        Expected contact time [s]; the run lasts the approach and three contact times.

    Returns
    -------
    RealisedImpact

    Raises
    ------
    LammpsError
        If LAMMPS refuses the snippet; the message names the line.
    """
    velocity = check_positive("velocity", velocity, "m/s")
    contact_time = check_positive("contact_time", contact_time, "s")
    r = grain.radius
    travel = velocity * (_GAP / velocity + 3.0 * contact_time)
    deck = [
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "boundary f f f",
        f"region box block {-4 * r!r} {4 * r!r} {-4 * r!r} {4 * r!r} {-r!r} {2 * r + travel!r}",
        "create_box 1 box",
        f"create_atoms 1 single 0.0 0.0 {r + _GAP!r}",
        f"set atom 1 diameter {2 * r!r} density {grain.density!r}",
        "comm_modify vel yes",
        f"include {Path(snippet_path).resolve()}",
        "fix integrate all nve/sphere",
        f"velocity all set 0.0 0.0 {-velocity!r}",
        "variable vz equal vz[1]",
        "variable fz equal fz[1]",
        "fix record all vector 1 v_vz v_fz",
    ]
    with LammpsSession(context="the exported LAMMPS snippet") as session:
        for line in deck:
            session.command(line)
        dt = session.lmp.extract_global("dt")
        steps = math.ceil((_GAP / velocity + 3.0 * contact_time) / dt)
        session.command(f"run {steps}")
        velocity_z, force_z = session.fix_vector_columns("record", 2)
    return RealisedImpact(dt, force_z, velocity_z, velocity)
