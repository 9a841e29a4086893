"""Time steps of the DEM engines' drop tests, from the contact and the sensor period.

An engine steps a contact of duration ``t_c`` (the law's impact on an immovable wall at
the release speed, :func:`contactlab.solver.wall_impact`; a Hertz contact's duration
depends on it) and a sensor of period ``T1``. Its default step resolves both
(:func:`default_time_step`), and a given step must leave at least ``min_steps`` steps
per contact and per sensor period (:func:`check_time_step`). LAMMPS
(:mod:`dem_check.engines.lammps.drop`) and Kratos (:mod:`dem_check.engines.kratos.drop`)
step their drop tests with the counts defined here (:data:`DROP_STEP_NAMES`, which both
modules re-export); pybullet (:mod:`dem_check.engines.bullet.limits`) has its own counts
and checks its step with :func:`check_steps` against its own contact time.
"""

from contactlab.solver import wall_impact
from contactlab.validation import check_number

__all__ = [
    "DROP_STEP_NAMES",
    "MIN_STEPS",
    "STEPS_PER_CONTACT",
    "STEPS_PER_PERIOD",
    "check_steps",
    "check_time_step",
    "default_time_step",
    "wall_contact_time",
]

STEPS_PER_CONTACT = 1000
"""Default steps per contact (the grain on an immovable wall) of the LAMMPS and Kratos drop
tests: restitution, contact time and peaks then err below 1e-4 for every mapped law
(``docs/dem_check.md``)."""

STEPS_PER_PERIOD = 200
"""Default steps per sensor period of the LAMMPS and Kratos drop tests (sensor peak within
1e-4, ``docs/dem_check.md``)."""

MIN_STEPS = 20
"""Fewest steps per contact and per sensor period accepted for a drop test's
``time_step``."""

DROP_STEP_NAMES = ("MIN_STEPS", "STEPS_PER_CONTACT", "STEPS_PER_PERIOD", "default_time_step")
"""The names above that the LAMMPS and Kratos drop modules hand on as theirs."""


def wall_contact_time(grain, law, velocity):
    """Contact time [s] of ``law`` for the grain on an immovable wall at ``velocity``."""
    return wall_impact(law, grain.mass, velocity).contact_time


def default_time_step(
    grain,
    sensor,
    law,
    velocity,
    steps_per_contact=STEPS_PER_CONTACT,
    steps_per_period=STEPS_PER_PERIOD,
):
    """``min(t_c / steps_per_contact, T1 / steps_per_period)`` [s] (no ``T1`` if rigid).

    With the default counts, the LAMMPS and Kratos drop tests' default step
    ``min(t_c / 1000, T1 / 200)``: ``t_c`` is the contact time of the law on an immovable
    wall at ``velocity`` and ``T1`` the sensor period.

    Parameters
    ----------
    grain : Grain
    sensor : Sensor
    law : ContactLaw
    velocity : float
        Impact speed [m/s].
    steps_per_contact : int, default :data:`STEPS_PER_CONTACT`
        Steps per wall contact time.
    steps_per_period : int, default :data:`STEPS_PER_PERIOD`
        Steps per sensor period.

    Returns
    -------
    float
    """
    steps = [wall_contact_time(grain, law, velocity) / steps_per_contact]
    if not sensor.is_rigid:
        steps.append(sensor.period / steps_per_period)
    return min(steps)


def check_time_step(time_step, grain, sensor, law, velocity, min_steps, default):
    """``time_step`` checked against the contact and the sensor period, or the default.

    Parameters
    ----------
    time_step : float or None
        Engine step [s]; ``None`` returns ``default(grain, sensor, law, velocity)``.
    grain, sensor, law, velocity
        As for :func:`default_time_step`.
    min_steps : int
        Fewest steps per contact and per sensor period accepted.
    default : callable
        The engine's ``default_time_step(grain, sensor, law, velocity)`` [s].

    Returns
    -------
    float
        The engine's time step: ``time_step`` as given, or the default [s].

    Raises
    ------
    ParameterError
        For a step not > 0 or coarser than ``t_c / min_steps`` or ``T1 / min_steps``.
    """
    if time_step is None:
        return default(grain, sensor, law, velocity)
    return check_steps(time_step, wall_contact_time(grain, law, velocity), sensor, min_steps)


def check_steps(time_step, contact_time, sensor, min_steps):
    """``time_step`` [s] checked: at least ``min_steps`` steps per ``contact_time`` [s] and
    per sensor period; a ParameterError naming ``time_step`` otherwise."""
    limit = contact_time / min_steps
    if not sensor.is_rigid:
        limit = min(limit, sensor.period / min_steps)
    return check_number(
        "time_step",
        time_step,
        low=0.0,
        high=limit,
        unit=f"s; {min_steps} steps per contact and per sensor period",
    )
