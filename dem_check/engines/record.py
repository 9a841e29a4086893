"""What the DEM engines' drop tests share: the release and plate geometry, the run plan,
the recorded columns and their reading as an :class:`EngineResult`.

LAMMPS (:mod:`dem_check.engines.lammps`) and Kratos (:mod:`dem_check.engines.kratos`) drop
the grain from a gap of a few steps onto a plane or onto a plate sphere of
:data:`PLATE_RADIUS_FACTOR` grain radii (:func:`drop_geometry`), run in chunks until
:data:`TAIL` after the contact and the sensor signal's first lobe (:func:`drop_plan`,
:func:`run_until_over`, :func:`impact_over`), record :data:`COLUMNS` per step (z up) and
read them in the model's axis (:func:`model_coordinates`, :func:`engine_result`). A
``deck`` below is the engine's scene, a :class:`DropCase` (the plate sphere's centre at
``z = -plate_radius`` at rest).
"""

import math
import warnings
from dataclasses import dataclass

import numpy as np

from contactlab.errors import ParameterError, WindowWarning
from contactlab.validation import check_number, check_positive
from dem_check.engines import steps as engine_steps
from dem_check.engines.intervals import contact_intervals
from dem_check.engines.result import EngineResult

__all__ = [
    "COLUMNS",
    "GAP_STEPS",
    "PLATE_RADIUS_FACTOR",
    "TAIL",
    "DropCase",
    "DropGeometry",
    "DropPlan",
    "drop_geometry",
    "drop_plan",
    "engine_result",
    "impact_over",
    "model_coordinates",
    "run_until_over",
    "sensor_signal",
    "step_limit",
    "warn_short_window",
]

PLATE_RADIUS_FACTOR = 10.0
"""Sensor plate radius over the grain radius: the law is mapped with the contact's ``R*``,
so the plate's curvature brings no error in the force (``docs/dem_check.md``)."""

GAP_STEPS = 3.5
"""Default release gap: the travel of 3.5 steps (the grain touches during step 4)."""

TAIL = 20e-6
"""Time simulated after the last contact and the end of the sensor signal's first lobe
[s], unless a duration is given."""

COLUMNS = ("step", "z2", "vz2", "fz2", "z1", "vz1")
"""Recorded per step: step number, grain z [m], z-velocity [m/s], z-force [N], plate z
[m], z-velocity [m/s] (plate columns 0 on a rigid sensor)."""


@dataclass(frozen=True)
class DropCase:
    """One drop test as every DEM engine's scene holds it; an engine's scene adds its input.

    Attributes
    ----------
    grain, sensor, law, velocity
        As for the engine's ``drop_test``.
    time_step : float
        [s].
    gap : float
        Grain-sensor distance at release [m].
    plate_radius : float
        Plate radius [m]; ``nan`` on a rigid sensor.
    """

    grain: object
    sensor: object
    law: object
    velocity: float
    time_step: float
    gap: float
    plate_radius: float

    @property
    def approach_time(self):
        """Time from release to touch [s]."""
        return self.gap / self.velocity


@dataclass(frozen=True)
class DropGeometry:
    """Release gap [m], plate radius [m] (``nan`` on a rigid sensor), and the contact's
    effective mass ``m*`` [kg] and radius ``R*`` [m] the law is mapped with."""

    gap: float
    plate_radius: float
    effective_mass: float
    effective_radius: float


def drop_geometry(grain, sensor, velocity, time_step, gap=None, plate_radius=None):
    """The release gap, the plate and the contact's ``m*``, ``R*`` of one drop test.

    Parameters
    ----------
    grain, sensor, velocity, time_step
        As for the engines' ``drop_test``; ``time_step`` already checked [s].
    gap : float, optional
        Release gap [m]; default :data:`GAP_STEPS` steps of travel.
    plate_radius : float, optional
        Plate radius [m]; default :data:`PLATE_RADIUS_FACTOR` grain radii. Ignored on a
        rigid sensor (``m* = m2``, ``R* = R2``).

    Returns
    -------
    DropGeometry

    Raises
    ------
    ParameterError
        For a gap or plate radius not > 0.
    """
    r2 = grain.radius
    if gap is None:
        gap = GAP_STEPS * velocity * time_step
    gap = check_number("gap", gap, low=0.0, unit="m")
    if sensor.is_rigid:
        return DropGeometry(gap, math.nan, grain.mass, r2)
    plate = PLATE_RADIUS_FACTOR * r2 if plate_radius is None else plate_radius
    plate = check_number("plate_radius", plate, low=0.0, unit="m")
    mass = grain.mass * sensor.mass / (grain.mass + sensor.mass)
    return DropGeometry(gap, plate, mass, r2 * plate / (r2 + plate))


@dataclass(frozen=True)
class DropPlan:
    """Checked inputs of a drop test: ``velocity`` [m/s], ``threshold`` [N], ``time_step``
    [s], ``after`` (longest time simulated after touch [s]) and ``stop`` (steps after the
    impact's end at which the run stops; ``None`` for a given duration)."""

    velocity: float
    threshold: float
    time_step: float
    after: float
    stop: int | None


def drop_plan(config, time_step, duration, threshold, default, min_steps):
    """Check a drop test's inputs and plan its run.

    ``config`` is the drop test's ImpactConfig (grain, sensor, law, ``velocity`` [m/s]);
    ``default(grain, sensor, law, velocity)`` gives the engine's default step [s];
    ``min_steps`` the fewest steps per contact and per sensor period
    (:func:`dem_check.engines.steps.check_time_step`). Without ``duration`` the run lasts
    until :data:`TAIL` after the impact, at most ten wall contact times and twenty sensor
    periods.

    Returns
    -------
    DropPlan

    Raises
    ------
    ParameterError
        For a bad velocity, threshold, time step or duration (each named).
    """
    grain, sensor, law = config.grain, config.sensor, config.law
    velocity = check_positive("velocity", config.velocity, "m/s")
    threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    dt = engine_steps.check_time_step(time_step, grain, sensor, law, velocity, min_steps, default)
    if duration is None:
        contact = engine_steps.wall_contact_time(grain, law, velocity)
        after = 10.0 * contact + 20.0 * sensor.period + TAIL
        return DropPlan(velocity, threshold, dt, after, math.ceil(TAIL / dt))
    after = check_number("duration", duration, low=0.0, unit="s")
    return DropPlan(velocity, threshold, dt, after, None)


def step_limit(deck, after, most, engine, start_states=False):
    """Steps from release to ``after`` past touch [s], refused beyond ``most``.

    Parameters
    ----------
    deck
        The engine's scene: ``approach_time`` and ``time_step`` [s].
    after : float
        Longest time simulated after touch [s] (:attr:`DropPlan.after`).
    most : int
        Most steps the engine's bench runs.
    engine : str
        The engine as named in the message (``"LAMMPS"``).
    start_states : bool, default False
        Whether the engine records each step's start state (one step more records the
        end).

    Returns
    -------
    int

    Raises
    ------
    ParameterError
        For more than ``most`` steps, naming ``duration`` and ``time_step``.
    """
    dt = deck.time_step
    steps = math.ceil((deck.approach_time + after) / dt) + int(start_states)
    if steps > most:
        raise ParameterError(
            f"duration = {after:.4g} s at time_step = {dt:.3g} s needs {steps} {engine} "
            f"steps; the bench runs at most {most}: shorten duration or lengthen time_step"
        )
    return steps


def warn_short_window(engine, end, stacklevel):
    """WindowWarning: the ``engine``'s run ended ``end`` [s] after touch, before the contact
    and the sensor signal's first lobe were over (``stacklevel`` as for
    :func:`warnings.warn`, counted from the caller)."""
    warnings.warn(
        f"the {engine} window ({end:.4g} s after touch) ended before the contact and the "
        "sensor signal's first lobe were over; give a longer duration",
        WindowWarning,
        stacklevel=stacklevel + 1,
    )


def model_coordinates(deck, columns):
    """``(x1, v1, x2, v2, S2)`` of recorded :data:`COLUMNS` in the model's axis (x down,
    into the sensor): ``x2 = R2 - z2``, ``x1 = -(z1 + Rp)`` (0 on a rigid sensor)."""
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


def impact_over(deck, columns, stop):
    """Whether ``stop`` steps have passed since the last contact and the first lobe's end."""
    force = columns[3]
    touching = np.flatnonzero(force > 0.0)
    if touching.size == 0:
        return False
    after = sensor_signal(deck, columns)[touching[0] :]
    rising = np.flatnonzero(after > 0.0)
    if rising.size == 0:
        return False
    falls = np.flatnonzero(after[rising[0] :] <= 0.0)
    if falls.size == 0:
        return False
    lobe_end = touching[0] + rising[0] + falls[0]
    return force.size - 1 >= max(touching[-1], lobe_end) + stop


def run_until_over(deck, limit, chunk, run, recorded, stop):
    """Step an engine in chunks until the impact is over or ``limit`` steps have run.

    Parameters
    ----------
    deck
        The engine's scene (module docstring).
    limit : int
        Most steps (:func:`step_limit`).
    chunk : int
        Steps between two looks for the end of the impact.
    run : callable
        ``run(count)`` steps the engine ``count`` steps further.
    recorded : callable
        ``recorded()`` returns the :data:`COLUMNS` recorded so far, ``(len(COLUMNS),
        steps)``.
    stop : int or None
        Steps to run after the last contact and the sensor signal's first lobe
        (:attr:`DropPlan.stop`, :func:`impact_over`); None runs all ``limit`` steps (a
        duration given).

    Returns
    -------
    columns : numpy.ndarray
        The recorded columns.
    complete : bool
        Whether the impact was seen to its end, or the duration given was run.
    """
    steps = 0
    while steps < limit:
        count = min(chunk, limit - steps)
        run(count)
        steps += count
        if stop is not None:
            columns = recorded()
            if impact_over(deck, columns, stop):
                return columns, True
    return recorded(), stop is None


def engine_result(method, label, deck, columns, threshold, complete, metadata):
    """The :class:`EngineResult` of an engine's recorded :data:`COLUMNS`.

    Parameters
    ----------
    method : str
        The engine (``"lammps"``, ``"kratos"``).
    label : str
        The engine as named in the warning of a window too short (``"LAMMPS"``).
    deck
        The engine's scene (module docstring).
    columns : numpy.ndarray
        ``(len(COLUMNS), steps)``.
    threshold : float
        Level [N] of the sensor signal's first lobe.
    complete : bool
        Whether the run reached the end of the impact.
    metadata : dict
        The engine's settings; ``"touch_time [s]"`` is added.

    Returns
    -------
    EngineResult

    Raises
    ------
    ParameterError
        If the grain never touched the sensor.
    """
    x1, v1, x2, v2, force = model_coordinates(deck, columns)
    times = columns[0] * deck.time_step
    intervals = contact_intervals(deck.law, times, x2 - x1, v2 - v1)
    if not intervals:
        raise ParameterError(
            f"the grain did not reach the sensor in {times[-1]:.4g} s; check velocity and gap"
        )
    touch = intervals[0][0]
    t = times - touch
    intervals = [(a - touch, b - touch) for a, b in intervals]
    if not complete or math.isnan(intervals[-1][1]):
        warn_short_window(label, t[-1], stacklevel=4)
    return EngineResult(
        method=method,
        grain=deck.grain,
        sensor=deck.sensor,
        law=deck.law,
        velocity=deck.velocity,
        t=t,
        signals=(x1, v1, x2, v2, force, sensor_signal(deck, columns)),
        intervals=intervals,
        metadata={**metadata, "touch_time [s]": touch},
        threshold=threshold,
    )
