"""The drop bench's scene: what pybullet is given, checked (:func:`drop_scene`) and built.

The scene (SI units, engine z axis up; the model's x axis points down, into the sensor):
the grain is a free sphere, the sensor a disc on a prismatic joint (or a fixed plate),
the contact the engine's soft contact on the grain (see :mod:`dem_check.engines.bullet`).
"""

import math
from dataclasses import dataclass

import numpy as np

from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import LinearViscoelastic
from contactlab.validation import check_number
from dem_check.engines.bullet.limits import check_time_step, law_parameters

__all__ = [
    "DEFAULT_PLATE",
    "GRAVITY",
    "PLATE_DAMPING",
    "PLATE_STIFFNESS",
    "DropScene",
    "drop_scene",
]

DEFAULT_PLATE = (10e-3, 2e-3)
"""Plate diameter and thickness [m] when the sensor does not give them: the paper's disc.

Only the plate's mass and joint matter for a central, frictionless impact; its size only
has to hold the grain."""

GRAVITY = 9.80665
"""Standard gravity [m/s**2], used when ``gravity=True``."""

PLATE_STIFFNESS, PLATE_DAMPING = 1e30, 0.0
"""Plate contact stiffness [N/m] and damping [N*s/m]: in series and in parallel with the
grain's they leave ``k2`` and ``c2`` (the engine's hidden default damping is 0.1 N*s/m)."""


@dataclass(frozen=True)
class DropScene:
    """A checked drop test: what the engine is given (build it with :func:`drop_scene`).

    Attributes
    ----------
    grain, sensor, law
        The bodies and the contact law.
    time_step : float
        Engine step [s].
    contact_stiffness : float
        ``k2`` passed to the engine [N/m].
    contact_damping : float
        Damping passed to the engine [N*s/m]: ``c2``, or ``c2 - k2 dt`` when compensated.
    numerical_damping : float
        Damping the implicit contact adds, ``k2 dt`` [N*s/m].
    compensate_damping : bool
        Whether ``contact_damping`` cancels ``numerical_damping``.
    gravity : float
        Gravity along the travel [m/s**2] (0 when off).
    velocity : float
        Grain speed at release [m/s].
    gap : float
        Distance from the grain to the plate at release [m].
    """

    grain: Grain
    sensor: Sensor
    law: LinearViscoelastic
    time_step: float
    contact_stiffness: float
    contact_damping: float
    numerical_damping: float
    compensate_damping: bool
    gravity: float
    velocity: float
    gap: float

    @property
    def impact_speed(self):
        """Grain speed at first touch, ``sqrt(v**2 + 2 g gap)`` [m/s]."""
        return math.sqrt(self.velocity**2 + 2.0 * self.gravity * self.gap)

    @property
    def approach_time(self):
        """Time from release to first touch [s] (uniform acceleration)."""
        return 2.0 * self.gap / (self.velocity + self.impact_speed)

    @property
    def preload(self):
        """Static force on the sensor element from the plate's weight [N]."""
        return 0.0 if self.sensor.is_rigid else self.sensor.mass * self.gravity

    @property
    def plate_rest(self):
        """Joint coordinate of the plate at rest under its weight [m]."""
        return 0.0 if self.sensor.is_rigid else self.preload / self.sensor.stiffness

    def build(self, client):
        """Create the scene in a connected pybullet client.

        Parameters
        ----------
        client : int
            Physics client id from ``pybullet.connect(pybullet.DIRECT)``.

        Returns
        -------
        plate, grain : int
            Body ids; the plate's joint (if any) is joint 0 of ``plate``.
        """
        import pybullet as pb

        pb.setPhysicsEngineParameter(
            fixedTimeStep=self.time_step,
            numSubSteps=0,  # sub-steps misreport the contact normal force
            contactSlop=0.0,  # the default 1e-5 m slop delays the spring by 10 um of overlap
            useSplitImpulse=0,  # split impulse corrects penetration outside the spring-damper
            deterministicOverlappingPairs=1,  # the same result on every run
            physicsClientId=client,
        )
        # SI units throughout: scaled units (mm) trip the multibody velocity clamp (100/s)
        pb.setGravity(0.0, 0.0, -self.gravity, physicsClientId=client)
        diameter, thickness = DEFAULT_PLATE
        if self.sensor.diameter and self.sensor.thickness:
            diameter, thickness = self.sensor.diameter, self.sensor.thickness
        disc = pb.createCollisionShape(
            pb.GEOM_CYLINDER, radius=diameter / 2, height=thickness, physicsClientId=client
        )
        below = [0.0, 0.0, -thickness / 2]  # the plate's top at z = 0 when undeflected
        if self.sensor.is_rigid:
            plate, link = (
                pb.createMultiBody(
                    baseMass=0.0,
                    baseCollisionShapeIndex=disc,
                    basePosition=below,
                    physicsClientId=client,
                ),
                -1,
            )
        else:
            plate, link = (
                pb.createMultiBody(
                    baseMass=0.0,
                    linkMasses=[self.sensor.mass],
                    linkCollisionShapeIndices=[disc],
                    linkVisualShapeIndices=[-1],
                    linkPositions=[below],
                    linkOrientations=[[0.0, 0.0, 0.0, 1.0]],
                    linkInertialFramePositions=[[0.0, 0.0, 0.0]],
                    linkInertialFrameOrientations=[[0.0, 0.0, 0.0, 1.0]],
                    linkParentIndices=[0],
                    linkJointTypes=[pb.JOINT_PRISMATIC],
                    linkJointAxis=[[0.0, 0.0, -1.0]],  # joint coordinate = deflection x1
                    physicsClientId=client,
                ),
                0,
            )
            # the default velocity motor locks the joint: free it (zero maximum force)
            pb.setJointMotorControl2(
                plate, 0, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=client
            )
            pb.resetJointState(plate, 0, self.plate_rest, 0.0, physicsClientId=client)
        sphere = pb.createCollisionShape(
            pb.GEOM_SPHERE, radius=self.grain.radius, physicsClientId=client
        )
        grain = pb.createMultiBody(
            baseMass=self.grain.mass,
            baseCollisionShapeIndex=sphere,
            basePosition=[0.0, 0.0, self.grain.radius - self.plate_rest + self.gap],
            physicsClientId=client,
        )
        pb.resetBaseVelocity(grain, [0.0, 0.0, -self.velocity], physicsClientId=client)
        for body, index, stiffness, damping in (
            (plate, link, PLATE_STIFFNESS, PLATE_DAMPING),
            (grain, -1, self.contact_stiffness, self.contact_damping),
        ):
            pb.changeDynamics(
                body,
                index,
                restitution=0.0,  # the law alone dissipates; engine restitution adds a target
                lateralFriction=0.0,  # head-on impact: friction rows would only cost time
                spinningFriction=0.0,
                rollingFriction=0.0,
                jointDamping=0.0,
                contactStiffness=stiffness,
                contactDamping=damping,
                physicsClientId=client,
            )
            # body-wide settings go to index -1: given with a link index, pybullet
            # silently ignores the whole call
            pb.changeDynamics(
                body,
                -1,
                linearDamping=0.0,  # the default 0.04 would slow the grain
                angularDamping=0.0,
                activationState=pb.ACTIVATION_STATE_DISABLE_SLEEPING,  # never freeze a body
                physicsClientId=client,
            )
            info = pb.getDynamicsInfo(body, index, physicsClientId=client)
            if (info[9], info[8]) != (stiffness, damping):  # guard that trap
                raise RuntimeError(
                    f"pybullet did not take contactStiffness={stiffness}, "
                    f"contactDamping={damping} (it reads {info[9]}, {info[8]})"
                )
        return plate, grain


def drop_scene(
    grain,
    sensor,
    law,
    velocity,
    time_step=None,
    gravity=False,
    *,
    compensate_damping=False,
    gap=None,
):
    """Check a drop test's parameters and return its :class:`DropScene`.

    Parameters are those of :func:`drop_test`.

    Returns
    -------
    DropScene
    """
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    for name, flag in (("gravity", gravity), ("compensate_damping", compensate_damping)):
        if not isinstance(flag, bool | np.bool_):  # gravity=9.81 would silently mean True
            raise ParameterError(f"{name} must be True or False; got {flag!r}")
    k2, c2 = law_parameters(law)
    velocity = check_number("velocity", velocity, low=0.0, low_open=not gravity, unit="m/s")
    dt = check_time_step(time_step, grain, sensor, law)
    numerical = k2 * dt
    if compensate_damping and c2 < numerical:
        raise ParameterError(
            f"compensate_damping needs the law's damping c2 = {c2:.4g} N*s/m >= k2 * dt = "
            f"{numerical:.4g} N*s/m; use time_step <= {c2 / k2:.4g} s or "
            "compensate_damping=False"
        )
    if gap is None:
        gap = 3.5 * dt * velocity  # touch half a step off the grid, as in a real drop
    else:
        gap = check_number("gap", gap, low=0.0, low_open=False, unit="m")
    if velocity == 0.0 and gap == 0.0:
        raise ParameterError("velocity = 0 needs a gap > 0 [m] to fall through")
    return DropScene(
        grain=grain,
        sensor=sensor,
        law=law,
        time_step=dt,
        contact_stiffness=k2,
        contact_damping=c2 - numerical if compensate_damping else c2,
        numerical_damping=numerical,
        compensate_damping=bool(compensate_damping),
        gravity=GRAVITY if gravity else 0.0,
        velocity=velocity,
        gap=gap,
    )
