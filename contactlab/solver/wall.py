"""A law's impact on an immovable wall: the simulation behind a law's restitution.

:class:`contactlab.laws.ContactLaw` defines forces only; its convenience methods
(:meth:`~contactlab.laws.ContactLaw.impact`, ``restitution``, ``contact_time``,
``dissipated_energy``) call :func:`wall_impact`, which this module registers with the
laws when the solver is imported (:func:`contactlab.laws.base.use_wall_solver`).
"""

from contactlab.bodies import Grain, Sensor
from contactlab.laws.base import use_wall_solver
from contactlab.plausibility import internal
from contactlab.solver.impact import simulate_impact

__all__ = ["wall_impact"]


def wall_impact(law, mass, velocity, **kwargs):
    """Impact of a grain of ``mass`` [kg] at ``velocity`` [m/s] on an immovable wall.

    Parameters
    ----------
    law : ContactLaw or PlasticTrapezoid
        The contact law.
    mass : float
        Grain mass [kg] (the effective mass for two grains).
    velocity : float
        Impact speed [m/s].
    **kwargs
        Passed to :func:`contactlab.simulate_impact`; ``duration`` defaults to None (the
        contact and its aftermath).

    Returns
    -------
    ImpactResult

    Notes
    -----
    No :class:`~contactlab.errors.PlausibilityWarning`: a law's restitution, contact time
    and energy are properties of the law at any mass and speed (fits and mappings ask
    for them far outside the ranges of real grains); impossible values still raise.
    """
    kwargs.setdefault("duration", None)
    with internal():
        grain = Grain.from_mass(mass)
        return simulate_impact(grain, Sensor.rigid(), law, velocity=velocity, **kwargs)


use_wall_solver(wall_impact)
