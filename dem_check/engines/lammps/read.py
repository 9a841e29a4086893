"""Reading LAMMPS' recorded steps as an :class:`~dem_check.engines.result.EngineResult`.

The recorded columns (:data:`~dem_check.engines.lammps.scene.COLUMNS`) become the model's
coordinates: ``x2 = R2 - z2`` (grain, down from its touching position), ``x1 = -(z1 +
Rp)`` (plate, down from rest; 0 on a rigid sensor), so the overlap is ``x2 - x1`` and the
contact force S2 is the grain's z force.

Contacts are located inside the steps by
:func:`dem_check.engines.intervals.contact_intervals` (shared with the other engines).
"""

import math
import warnings

import numpy as np

from contactlab.errors import ParameterError, WindowWarning
from dem_check.engines.intervals import contact_intervals
from dem_check.engines.lammps.scene import COLUMNS, RECORD
from dem_check.engines.result import EngineResult

__all__ = [
    "contact_intervals",
    "model_coordinates",
    "read_steps",
    "recorded_columns",
    "sensor_signal",
]


def recorded_columns(session):
    """The recorded steps as a ``(len(COLUMNS), steps + 1)`` array (row 0: the release)."""
    return session.fix_vector_columns(RECORD, len(COLUMNS))


def model_coordinates(deck, columns):
    """``(x1, v1, x2, v2, S2)`` in the model's axis (x down, into the sensor).

    ``deck`` needs ``grain``, ``sensor`` and ``plate_radius`` (the plate sphere's centre
    at ``z = -plate_radius`` at rest); ``columns`` are :data:`COLUMNS` (z up). The Kratos
    engine records the same columns (:mod:`dem_check.engines.kratos.drop`).
    """
    _, z2, vz2, fz2, z1, vz1 = columns
    plate = 0.0 if deck.sensor.is_rigid else deck.plate_radius
    x1 = np.zeros_like(z1) if deck.sensor.is_rigid else -(z1 + plate)
    return x1, -vz1, deck.grain.radius - z2, -vz2, fz2


def sensor_signal(deck, columns):
    """S1 [N] per recorded step: ``k1 x1 + c1 v1``, or S2 on a rigid sensor."""
    x1, v1, _, _, force = model_coordinates(deck, columns)
    if deck.sensor.is_rigid:
        return force.copy()
    return deck.sensor.stiffness * x1 + deck.sensor.damping * v1


def read_steps(deck, columns, threshold, complete, wall, version):
    """The :class:`EngineResult` of the recorded columns of a :class:`DropDeck`."""
    x1, v1, x2, v2, force = model_coordinates(deck, columns)
    steps = columns[0] * deck.time_step
    intervals = contact_intervals(deck.law, steps, x2 - x1, v2 - v1)
    if not intervals:
        raise ParameterError(
            f"the grain did not reach the sensor in {steps[-1]:.4g} s; check velocity and gap"
        )
    touch = intervals[0][0]
    t = steps - touch
    intervals = [(a - touch, b - touch) for a, b in intervals]
    if not complete or math.isnan(intervals[-1][1]):
        warnings.warn(
            f"the LAMMPS window ({t[-1]:.4g} s after touch) ended before the contact and the "
            "sensor signal's first lobe were over; give a longer duration",
            WindowWarning,
            stacklevel=3,
        )
    model = deck.model
    metadata = {
        "engine": f"LAMMPS {version} (GRANULAR)",
        "time_step [s]": deck.time_step,
        "numerical_damping [N*s/m]": 0.0,
        "steps": int(columns[0][-1]),
        "touch_time [s]": touch,
        "granular_model": model.words(),
        "effective_mass [kg]": model.effective_mass,
        "effective_radius [m]": model.effective_radius,
        "plate_radius [m]": deck.plate_radius,
        "gap [m]": deck.gap,
        "wall_time [s]": wall,
    }
    return EngineResult(
        method="lammps",
        grain=deck.grain,
        sensor=deck.sensor,
        law=deck.law,
        velocity=deck.velocity,
        t=t,
        signals=(x1, v1, x2, v2, force, sensor_signal(deck, columns)),
        intervals=intervals,
        metadata=metadata,
        threshold=threshold,
    )
