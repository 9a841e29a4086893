"""Reading LAMMPS' recorded steps as an :class:`~dem_check.engines.result.EngineResult`.

The recorded columns (:data:`~dem_check.engines.record.COLUMNS`) become the model's
coordinates: ``x2 = R2 - z2`` (grain, down from its touching position), ``x1 = -(z1 +
Rp)`` (plate, down from rest; 0 on a rigid sensor), so the overlap is ``x2 - x1`` and the
contact force S2 is the grain's z force (:mod:`dem_check.engines.record`, shared with
Kratos). Contacts are located inside the steps by
:func:`dem_check.engines.intervals.contact_intervals`.
"""

from dem_check.engines.lammps.scene import COLUMNS, RECORD
from dem_check.engines.record import engine_result

__all__ = ["read_steps", "recorded_columns"]


def recorded_columns(session):
    """The recorded steps as a ``(len(COLUMNS), steps + 1)`` array (row 0: the release)."""
    return session.fix_vector_columns(RECORD, len(COLUMNS))


def read_steps(deck, columns, threshold, complete, wall, version):
    """The :class:`EngineResult` of the recorded columns of a :class:`DropDeck`."""
    model = deck.model
    metadata = {
        "engine": f"LAMMPS {version} (GRANULAR)",
        "time_step [s]": deck.time_step,
        "numerical_damping [N*s/m]": 0.0,
        "steps": int(columns[0][-1]),
        "granular_model": model.words(),
        "effective_mass [kg]": model.effective_mass,
        "effective_radius [m]": model.effective_radius,
        "plate_radius [m]": deck.plate_radius,
        "gap [m]": deck.gap,
        "wall_time [s]": wall,
    }
    return engine_result("lammps", "LAMMPS", deck, columns, threshold, complete, metadata)
