"""Running a stream in LAMMPS: insertion slots, sweeps, and what is read back.

:func:`simulate_stream` draws the particles (:func:`~dem_check.stream.feed.schedule`),
builds the deck (:mod:`dem_check.stream.deck`) and runs it slot by slot: each slot
inserts its particles (``run ... pre yes``: new atoms need LAMMPS' set-up), deletes
rebounders above the insertion zone, and runs ``slot_steps`` steps; with straw in the
box it first releases the rigid bodies and defines them again after its insertions
(:mod:`dem_check.stream.straw`). The sensor moves
inside LAMMPS, so there is no Python in the step loop. Under ``mpiexec`` every rank runs
the same Python (LAMMPS splits the box between them); the series are global and the
contact dump is written once.
"""

import math
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from dem_check.engines.lammps.session import LammpsSession
from dem_check.stream.deck import (
    CONTACTS,
    RECORD,
    create_line,
    deck_lines,
    group_lines,
    insert_lines,
    sweep_lines,
)
from dem_check.stream.feed import schedule as draw_schedule
from dem_check.stream.straw import FIX_RIGID, UNFIX_RIGID, has_straw, sphere_centres

__all__ = ["RawStream", "simulate_stream", "world"]


class RawStream:
    """What one stream run gives back before analysis.

    Attributes
    ----------
    case, schedule
        The case and its drawn particles.
    steps : pandas.DataFrame
        Per step: ``t [s]``, ``contact_force [N]`` (sum over the plate), ``x1 [m]``,
        ``v1 [m/s]`` (plate displacement and velocity into the sensor) and
        ``sensor_force [N]`` (``S1 = k1 x1 + c1 v1``).
    contacts : pandas.DataFrame
        The contact dump (:data:`~dem_check.stream.deck.CONTACTS`, ``pid`` the schedule's).
    script : str
        The LAMMPS input lines run (a deck reproducing the run, inserts included).
    rank, ranks : int
        This process's MPI rank and the number of processes.
    """

    def __init__(self, case, schedule, steps, contacts, script, rank, ranks):
        self.case, self.schedule, self.steps = case, schedule, steps
        self.contacts, self.script, self.rank, self.ranks = contacts, script, rank, ranks


def world(session):
    """``(rank, size)`` of the LAMMPS instance's MPI world."""
    lmp = session.lmp
    return int(lmp.extract_setting("world_rank")), int(lmp.extract_setting("world_size"))


def _read_contacts(path):
    if not Path(path).exists():
        return pd.DataFrame(columns=CONTACTS)
    frame = pd.read_csv(
        path,
        sep=" ",
        header=None,
        names=CONTACTS,
        comment="I",
        skipinitialspace=True,
        engine="c",
        index_col=False,
    )
    frame = frame.dropna().astype({"pid1": int, "step": int, "type": int})
    frame.insert(0, "pid", frame.pop("pid1") - 1)
    return frame.sort_values(["pid", "step"], kind="stable").reset_index(drop=True)


def _insert(session, rows, schedule):
    """Create the slot's particles (a straw: each of its spheres); each new atom has the
    largest ID (LAMMPS gives a created atom the largest ID plus one, across all ranks)."""
    for pid, row in rows.iterrows():
        offsets = schedule.clumps[int(row["cls"])]
        centres = [None] if offsets is None else sphere_centres(row, offsets)
        for at in centres:
            session.command(*create_line(row, pid, at))
            tag = int(session.lmp.extract_global("map_tag_max"))
            for line, what in insert_lines(row, pid, tag, molecule=offsets is not None):
                session.command(line, what)
    for line, what in group_lines(schedule):
        session.command(line, what)


def simulate_stream(case, *, progress=False, workdir=None):
    """Run ``case`` in LAMMPS (module docstring).

    Parameters
    ----------
    case : StreamCase
    progress : bool, default False
        A progress bar over the insertion slots (tqdm on stderr, rank 0 only).
    workdir : path, optional
        Folder for the contact dump (default a temporary folder).

    Returns
    -------
    RawStream
    """
    schedule = draw_schedule(case)
    table = schedule.table
    total = schedule.lead + case.duration + 2.0 * schedule.slot_steps * schedule.time_step
    slots = math.ceil(total / (schedule.slot_steps * schedule.time_step))
    by_slot = {s: rows for s, rows in table.groupby("slot")} if len(table) else {}
    ceiling = 0.5 * case.feed.release
    clumps = has_straw(schedule)
    rigid = False  # whether fix rigid is defined
    with tempfile.TemporaryDirectory() as tmp, LammpsSession(context="stream") as session:
        dump = Path(workdir or tmp) / "contacts.dump"
        for line, what in deck_lines(case, schedule, dump):
            session.command(line, what)
        rank, size = world(session)
        bar = None
        if progress and rank == 0:
            from tqdm import tqdm

            bar = tqdm(total=slots, unit="slot", desc="stream")
        for s in range(slots):
            rows = by_slot.get(s)
            if rigid:  # LAMMPS crashes when atoms are added to or taken from live bodies
                session.command(*UNFIX_RIGID)
            for line, what in sweep_lines(ceiling, molecules=clumps):
                session.command(line, what)
            if rows is not None:
                _insert(session, rows, schedule)
            if clumps and (rigid or (rows is not None and (rows["spheres"] > 1).any())):
                session.command(*FIX_RIGID)
                rigid = True
            session.command(f"run {schedule.slot_steps} pre yes post no")
            if bar is not None:
                bar.update()
        if bar is not None:
            bar.close()
        step, force, x1, v1 = session.fix_vector_columns(RECORD, 4)
        session.command("undump contacts")  # flushes the file
        contacts = _read_contacts(dump)
        script = session.script
    step, first = np.unique(step.astype(np.int64), return_index=True)
    if not np.array_equal(step, np.arange(step.size)):  # the truth indexes steps by number
        raise RuntimeError("LAMMPS' step record is not every step from 0; report this")
    sensor = case.sensor
    x1, v1 = x1[first], v1[first]
    steps = pd.DataFrame(
        {
            "t [s]": step * schedule.time_step,
            "contact_force [N]": force[first],
            "sensor_force [N]": sensor.stiffness * x1 + sensor.damping * v1,
            "x1 [m]": x1,
            "v1 [m/s]": v1,
        }
    )
    return RawStream(case, schedule, steps, contacts, script, rank, size)
