"""A law's impact on an immovable wall: the simulation behind a law's restitution.

:class:`contactlab.laws.ContactLaw` defines forces only; what a law does to a grain on
an immovable wall is simulated here: :func:`wall_impact` and the numbers read off it
(:func:`wall_restitution`, :func:`wall_contact_time`, :func:`wall_dissipated_energy`).
"""

from contactlab.bodies import Grain, Sensor
from contactlab.plausibility import internal
from contactlab.solver.impact import simulate_impact

__all__ = ["wall_contact_time", "wall_dissipated_energy", "wall_impact", "wall_restitution"]


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


def wall_restitution(law, mass, velocity):
    """Coefficient of restitution on an immovable wall [-] (force-zero contact end) of a
    grain of ``mass`` [kg] at ``velocity`` [m/s]."""
    return wall_impact(law, mass, velocity).restitution


def wall_contact_time(law, mass, velocity):
    """Contact duration on an immovable wall [s] (force-zero contact end) of a grain of
    ``mass`` [kg] at ``velocity`` [m/s]."""
    return wall_impact(law, mass, velocity).contact_time


def wall_dissipated_energy(law, mass, velocity):
    """Energy lost in one impact on an immovable wall [J]: ``m v**2 (1 - e**2) / 2``."""
    e = wall_restitution(law, mass, velocity)
    return 0.5 * mass * velocity**2 * (1.0 - e**2)
