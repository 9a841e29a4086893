"""What pybullet's contact can hold, and how finely the engine must step.

pybullet's soft contact is a spring and a damper, linear in overlap and rate, that never
pulls: exactly :class:`~contactlab.laws.LinearViscoelastic` (:data:`ENGINE_LAWS`). The
engine step is chosen from the shortest contact (the grain on an immovable wall) and the
sensor period.
"""

from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.laws import LinearViscoelastic
from dem_check.engines.steps import check_steps

__all__ = [
    "ENGINE_LAWS",
    "MAX_TIME_STEP",
    "MIN_STEPS",
    "STEPS_PER_CONTACT",
    "STEPS_PER_PERIOD",
    "check_time_step",
    "contact_time_estimate",
    "default_time_step",
    "law_parameters",
]

ENGINE_LAWS = (LinearViscoelastic,)
"""Contact laws pybullet's soft contact represents exactly."""

MAX_TIME_STEP = 1e-7
"""Largest default engine step [s]: 0.1-0.3 % on contact time and peaks for the paper's
cases (measured; ``docs/dem_check.md``)."""

STEPS_PER_CONTACT = 500
"""Default engine steps per contact (shortest contact: the grain on an immovable wall)."""

STEPS_PER_PERIOD = 100
"""Default engine steps per sensor period (explicit spring: frequency error ~4e-4)."""

MIN_STEPS = 20
"""Fewest steps per contact and per sensor period accepted for ``time_step``: coarser steps
give errors of several percent, too large for a cross-check."""


def law_parameters(law):
    """``(k2, c2)`` of a law the engine represents, or a ParameterError naming the law."""
    if not isinstance(law, ENGINE_LAWS):
        names = ", ".join(cls.__name__ for cls in ENGINE_LAWS)
        raise ParameterError(
            f"law {type(law).__name__} cannot be represented in pybullet, whose soft contact "
            f"is a linear spring-damper that never pulls; supported: {names}"
        )
    return law.stiffness, law.damping


def contact_time_estimate(grain, law):
    """Shortest contact [s]: the grain on an immovable wall (force-zero end)."""
    k2, c2 = law_parameters(law)
    return analytic.linear_contact_time(k2, c2, grain.mass, convention="force")


def default_time_step(grain, sensor, law):
    """Default engine step [s].

    ``min(1e-7, t_c / 500, T1 / 100)``: at least :data:`STEPS_PER_CONTACT` steps in the
    shortest contact ``t_c`` (the grain on an immovable wall) and
    :data:`STEPS_PER_PERIOD` per sensor period ``T1``, and at most :data:`MAX_TIME_STEP`.

    Parameters
    ----------
    grain : Grain
    sensor : Sensor
    law : LinearViscoelastic

    Returns
    -------
    float
    """
    steps = [MAX_TIME_STEP, contact_time_estimate(grain, law) / STEPS_PER_CONTACT]
    if not sensor.is_rigid:
        steps.append(sensor.period / STEPS_PER_PERIOD)
    return min(steps)


def check_time_step(time_step, grain, sensor, law):
    """``time_step`` [s] checked (:func:`dem_check.engines.steps.check_steps`), or the
    default."""
    if time_step is None:
        return default_time_step(grain, sensor, law)
    return check_steps(time_step, contact_time_estimate(grain, law), sensor, MIN_STEPS)
