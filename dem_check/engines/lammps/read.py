"""Reading LAMMPS' recorded steps as an :class:`~dem_check.engines.result.EngineResult`.

The recorded columns (:data:`~dem_check.engines.lammps.scene.COLUMNS`) become the model's
coordinates: ``x2 = R2 - z2`` (grain, down from its touching position), ``x1 = -(z1 +
Rp)`` (plate, down from rest; 0 on a rigid sensor), so the overlap is ``x2 - x1`` and the
contact force S2 is the grain's z force.

Contact starts where the overlap turns positive and ends where the law's force formula
(``law.branch("load").force``, unclipped) turns negative, as in
:func:`contactlab.simulate_impact`. Both are located inside the step where they happen:
the overlap is interpolated by the cubic Hermite polynomial of its values and rates at
the step's ends (error O(dt**4)) and the root found by Brent's method, so the contact
time carries no error of the step grid (linear interpolation of ``d**1.5`` would err by
up to a tenth of a step).
"""

import math
import warnings

import numpy as np
from scipy.optimize import brentq

from contactlab.errors import ParameterError, WindowWarning
from dem_check.engines.lammps.scene import COLUMNS, RECORD
from dem_check.engines.result import EngineResult

__all__ = ["contact_intervals", "read_steps", "recorded_columns", "sensor_signal"]


def recorded_columns(session):
    """The recorded steps as a ``(len(COLUMNS), steps + 1)`` array (row 0: the release)."""
    return session.fix_vector_columns(RECORD, len(COLUMNS))


def _model_coordinates(deck, columns):
    """``(x1, v1, x2, v2, S2)`` in the model's axis (x down, into the sensor)."""
    _, z2, vz2, fz2, z1, vz1 = columns
    plate = 0.0 if deck.sensor.is_rigid else deck.plate_radius
    x1 = np.zeros_like(z1) if deck.sensor.is_rigid else -(z1 + plate)
    return x1, -vz1, deck.grain.radius - z2, -vz2, fz2


def sensor_signal(deck, columns):
    """S1 [N] per recorded step: ``k1 x1 + c1 v1``, or S2 on a rigid sensor."""
    x1, v1, _, _, force = _model_coordinates(deck, columns)
    if deck.sensor.is_rigid:
        return force.copy()
    return deck.sensor.stiffness * x1 + deck.sensor.damping * v1


def _hermite(d0, d1, r0, r1, h):
    """Overlap and its rate at fraction ``s`` of a step of length ``h`` (cubic Hermite)."""

    def at(s):
        s2, s3 = s * s, s * s * s
        d = (
            (2 * s3 - 3 * s2 + 1) * d0
            + (s3 - 2 * s2 + s) * h * r0
            + (-2 * s3 + 3 * s2) * d1
            + (s3 - s2) * h * r1
        )
        r = (6 * s2 - 6 * s) * d0 / h + (3 * s2 - 4 * s + 1) * r0
        r += (-6 * s2 + 6 * s) * d1 / h + (3 * s2 - 2 * s) * r1
        return d, r

    return at


def _root_in_step(at, formula):
    """Fraction of the step where ``formula(d, d')`` (or, for ``None``, ``d``) is zero."""

    def test(s):
        overlap, rate = at(s)
        return overlap if formula is None else float(formula(overlap, rate))

    return brentq(test, 0.0, 1.0, xtol=1e-14)


def contact_intervals(law, t, overlap, rate):
    """Contacts as ``[(start, end), ...]`` [s] located inside the steps.

    Parameters
    ----------
    law : ContactLaw
        Its unclipped force formula marks the end of contact.
    t, overlap, rate : numpy.ndarray
        Time [s], overlap [m] and overlap rate [m/s] per step.

    Returns
    -------
    list of tuple
        One ``(start, end)`` per contact; ``end`` is ``nan`` for a contact still open.
    """
    formula = law.branch("load").force
    raw = formula(overlap, rate)
    touching = (overlap > 0.0) & (raw > 0.0)
    if touching[0]:
        raise ParameterError("the grain touches the sensor at release; give a positive gap")
    edges = np.flatnonzero(touching[1:] != touching[:-1]) + 1
    times = []
    for i in edges:
        h = t[i] - t[i - 1]
        at = _hermite(overlap[i - 1], overlap[i], rate[i - 1], rate[i], h)
        # what changes sign across the step: the force formula at the end of a contact,
        # the overlap at its start
        ends = touching[i - 1] and raw[i] <= 0.0
        times.append(t[i - 1] + h * _root_in_step(at, formula if ends else None))
    if touching[-1]:
        times.append(math.nan)
    return [(float(a), float(b)) for a, b in zip(times[::2], times[1::2], strict=True)]


def read_steps(deck, columns, threshold, complete, wall, version):
    """The :class:`EngineResult` of the recorded columns of a :class:`DropDeck`."""
    x1, v1, x2, v2, force = _model_coordinates(deck, columns)
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
