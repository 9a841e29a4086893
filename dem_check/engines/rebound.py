"""An engine's rebound of one oblique impact on a wall (signs as
:class:`contactlab.ObliqueResult`): what :func:`~dem_check.engines.lammps.lammps_oblique`
and :func:`~dem_check.engines.kratos.kratos_oblique` return."""

from dataclasses import dataclass

__all__ = ["ObliqueRebound"]


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
