"""An engine's rebound of one oblique impact on a wall (signs as
:class:`contactlab.ObliqueResult`): what :func:`~dem_check.engines.lammps.lammps_oblique`
and :func:`~dem_check.engines.kratos.kratos_oblique` return, and the checked start both
run from (:func:`oblique_start`)."""

import math
from dataclasses import dataclass

from contactlab.solver import wall_impact
from contactlab.validation import check_number
from dem_check.engines.record import GAP_STEPS

__all__ = ["MIN_STEPS", "ObliqueRebound", "ObliqueStart", "oblique_start"]

MIN_STEPS = 20
"""Fewest steps per wall contact accepted for ``time_step``."""


@dataclass(frozen=True)
class ObliqueStart:
    """Checked inputs of one oblique impact: ``velocity`` [m/s], ``angle`` [rad], ``spin``
    [rad/s], the normal and tangential speeds ``vn``, ``vt`` [m/s], the normal law's wall
    ``contact_time`` at ``vn`` [s], the ``time_step`` [s] and the release ``gap`` [m]
    (:data:`~dem_check.engines.record.GAP_STEPS` steps of normal travel)."""

    velocity: float
    angle: float
    spin: float
    vn: float
    vt: float
    contact_time: float
    time_step: float
    gap: float


def oblique_start(grain, normal_law, velocity, angle, spin, time_step, steps_per_contact):
    """Check an engine's oblique impact and choose its step.

    Parameters
    ----------
    grain, normal_law, velocity, angle, spin, time_step
        As for :func:`~dem_check.engines.lammps.lammps_oblique`.
    steps_per_contact : int
        The engine's default steps per wall contact time.

    Returns
    -------
    ObliqueStart

    Raises
    ------
    ParameterError
        For a number out of range, or a step longer than 1/:data:`MIN_STEPS` of the
        contact (each named).
    """
    velocity = check_number("velocity", velocity, low=0.0, unit="m/s")
    angle = check_number(
        "angle", angle, low=0.0, high=math.pi / 2, low_open=False, high_open=True, unit="rad"
    )
    spin = check_number("spin", spin, unit="rad/s")
    vn, vt = velocity * math.cos(angle), velocity * math.sin(angle)
    contact_time = wall_impact(normal_law, grain.mass, vn).contact_time
    if time_step is None:
        time_step = contact_time / steps_per_contact
    high = contact_time / MIN_STEPS
    time_step = check_number("time_step", time_step, low=0.0, high=high, unit="s")
    gap = GAP_STEPS * vn * time_step
    return ObliqueStart(velocity, angle, spin, vn, vt, contact_time, time_step, gap)


@dataclass(frozen=True)
class ObliqueRebound:
    """An engine's rebound of one oblique impact.

    Attributes
    ----------
    velocity, angle, spin : float
        Impact speed [m/s], angle from the normal [rad], initial spin [rad/s].
    radius : float
        Grain radius [m].
    rebound_normal_velocity, tangential_velocity, angular_velocity : float
        After the impact: normal speed away from the wall [m/s], tangential velocity
        [m/s], spin [rad/s].
    time_step : float
        The engine's step [s].
    steps : int
        Steps run.
    """

    velocity: float
    angle: float
    spin: float
    radius: float
    rebound_normal_velocity: float
    tangential_velocity: float
    angular_velocity: float
    time_step: float
    steps: int

    @property
    def slip_after(self):
        """Contact-point slip after the impact ``vt' - R spin'`` [m/s]."""
        return self.tangential_velocity - self.radius * self.angular_velocity
