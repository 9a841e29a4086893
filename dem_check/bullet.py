"""The reduced model's impact rebuilt in a rigid-body engine (pybullet): a drop bench.

:func:`drop_test` drops a sphere on a plate in pybullet and reads the result as
:func:`contactlab.simulate_impact` does, so the two can be compared number by number
(:func:`engine_check`, :func:`dem_check.compare`).

The scene (SI units, engine z axis up; the model's x axis points down, into the sensor):

* the **grain** is a free sphere of the grain's diameter and mass;
* the **sensor** is a disc (cylinder) of the sensor's diameter and thickness
  (:meth:`Sensor.from_disc`), or of :data:`DEFAULT_PLATE` when the sensor does not know
  them, with mass ``m1`` on a PRISMATIC joint of a fixed base. The measuring element
  (``k1``, ``c1``) is a joint force ``-(k1 x1 + c1 v1)`` applied before every step from
  the joint state, and the sensor signal is read from the same state,
  ``S1 = k1 x1 + c1 v1``. :meth:`Sensor.rigid` is a fixed plate (``S1 = S2``);
* the **contact** is the engine's soft contact with ``contactStiffness = k2`` and
  ``contactDamping = c2`` on the grain. The engine combines two bodies' values as springs
  in series and dampers in parallel, so the plate gets ``1e30`` and ``0``.

Which laws the engine can represent
-----------------------------------
pybullet's soft contact is a spring and a damper, linear in overlap and rate, that never
pulls: exactly :class:`~contactlab.laws.LinearViscoelastic`. Every other law (Hertz and
its damped variants, Hunt-Crossley, Walton-Braun, linear-plastic, Thornton, the prescribed
trapezoid) raises :class:`~contactlab.errors.ParameterError` naming it.

The engine's bias
-----------------
The engine solves the contact implicitly: the force at the end of a step is
``k2 d + c d'`` of the *end-of-step* state, which is the force of the start-of-step
overlap plus an extra damper ``k2 dt``. This numerical damping ``k2 * dt`` [N*s/m] is
reported (``result.numerical_damping``); ``compensate_damping=True`` passes
``contactDamping = c2 - k2 dt`` instead, which needs ``c2 >= k2 dt``. The sensor spring,
applied explicitly before each step, is symplectic and adds no damping.
"""

import math
import time
import warnings
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from contactlab import analytic, metrics
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError, WindowWarning
from contactlab.laws import LinearViscoelastic
from contactlab.result import ImpactSignals
from contactlab.validation import check_number

__all__ = [
    "DEFAULT_PLATE",
    "ENGINE_LAWS",
    "DropScene",
    "EngineResult",
    "base_case_check",
    "convergence_study",
    "default_time_step",
    "drop_scene",
    "drop_test",
    "engine_check",
]

ENGINE_LAWS = (LinearViscoelastic,)
"""Contact laws pybullet's soft contact represents exactly."""

DEFAULT_PLATE = (10e-3, 2e-3)
"""Plate diameter and thickness [m] when the sensor does not give them: the paper's disc.

Only the plate's mass and joint matter for a central, frictionless impact; its size only
has to hold the grain."""

GRAVITY = 9.80665
"""Standard gravity [m/s**2], used when ``gravity=True``."""

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

MAX_STEPS = 2_000_000
"""Most engine steps one drop test records (0.2 s of engine time at 1e-7 s, about 16 s of
stepping); more is refused, not allocated."""

_BYTES_PER_STEP = 5 * 32
"""Memory recorded per step: five Python floats (list slot and float object)."""

TAIL = 20e-6
"""Time simulated after the last contact and the end of the sensor signal's first lobe
[s]: the engine stops there unless ``duration`` is given."""

PLATE_STIFFNESS, PLATE_DAMPING = 1e30, 0.0
"""Plate contact stiffness [N/m] and damping [N*s/m]: in series and in parallel with the
grain's they leave ``k2`` and ``c2`` (the engine's hidden default damping is 0.1 N*s/m)."""


def _law_parameters(law):
    """``(k2, c2)`` of a law the engine represents, or a ParameterError naming the law."""
    if not isinstance(law, ENGINE_LAWS):
        names = ", ".join(cls.__name__ for cls in ENGINE_LAWS)
        raise ParameterError(
            f"law {type(law).__name__} cannot be represented in pybullet, whose soft contact "
            f"is a linear spring-damper that never pulls; supported: {names}"
        )
    return law.stiffness, law.damping


def _contact_time_estimate(grain, law):
    """Shortest contact [s]: the grain on an immovable wall (force-zero end)."""
    k2, c2 = _law_parameters(law)
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
    steps = [MAX_TIME_STEP, _contact_time_estimate(grain, law) / STEPS_PER_CONTACT]
    if not sensor.is_rigid:
        steps.append(sensor.period / STEPS_PER_PERIOD)
    return min(steps)


def _check_time_step(time_step, grain, sensor, law):
    if time_step is None:
        return default_time_step(grain, sensor, law)
    limit = _contact_time_estimate(grain, law) / MIN_STEPS
    if not sensor.is_rigid:
        limit = min(limit, sensor.period / MIN_STEPS)
    return check_number(
        "time_step",
        time_step,
        low=0.0,
        high=limit,
        unit=f"s; {MIN_STEPS} steps per contact and per sensor period",
    )


class EngineResult(ImpactSignals):
    """One impact run in the engine (see :func:`drop_test`).

    The same signals and headline numbers as :class:`contactlab.ImpactResult`, read from
    the engine's steps instead of an exact solution.

    Signals (numpy arrays, one sample per engine step, time ``t`` [s] from the first touch,
    negative before it): ``contact_force`` (S2, the engine's contact normal force) [N],
    ``sensor_force`` (S1 from the joint state) [N], ``x1``, ``x2`` [m], ``v1``, ``v2``
    [m/s] and ``overlap`` [m].

    Headline numbers: ``contact_time`` [s], ``peak_contact_force`` [N],
    ``sensor_response_time`` [s], ``peak_sensor_force`` [N], ``impulse`` [N*s],
    ``restitution`` [-], ``rebound_velocity`` [m/s], ``contact_intervals`` [(start, end) s],
    ``numerical_damping`` [N*s/m], and ``metadata`` (engine settings, steps, wall time).

    Notes
    -----
    The contact lasts while the overlap and the engine's spring-damper force
    ``k2 d + c d'`` (``c`` as passed to the engine) are both positive; its start and end are
    located by linear interpolation between steps of ``k2 d + c min(d', 0)``. With
    ``c = 0`` these are the overlap's sign changes. Peaks are the largest step values (500
    steps per contact put them within ~1e-5 of the continuous peak), the impulse is the sum
    of the engine's per-step impulses, and the sensor signal's first lobe is read with
    :func:`contactlab.metrics.pulse_metrics`, as for a measured trace.
    """

    def __init__(self, *, grain, sensor, law, velocity, t, signals, intervals, metadata, threshold):
        self.grain, self.sensor, self.law = grain, sensor, law
        self.velocity = velocity
        self.threshold = threshold
        self.t = t
        self.x1, self.v1, self.x2, self.v2, self.contact_force, self.sensor_force = signals
        self.overlap = self.x2 - self.x1
        self.contact_intervals = intervals
        self.metadata = metadata

    method = "pybullet"
    """Where the result comes from (as :attr:`contactlab.ImpactResult.method`)."""

    @property
    def time_step(self):
        """Engine step [s]."""
        return self.metadata["time_step [s]"]

    @property
    def numerical_damping(self):
        """Damping the implicit contact adds, ``k2 * dt`` [N*s/m] (compensated or not)."""
        return self.metadata["numerical_damping [N*s/m]"]

    @cached_property
    def _contact_peak(self):
        start, end = self.contact_intervals[0]
        return metrics.peak(self.t, self.contact_force, start, end)

    @cached_property
    def sensor_pulse(self):
        """:class:`contactlab.metrics.PulseMetrics` of the sensor signal's first lobe."""
        return metrics.pulse_metrics(self.t, self.sensor_force, self.threshold)

    @property
    def sensor_lobe(self):
        """(start, end) [s] of the sensor signal's first lobe above ``threshold``."""
        return self.sensor_pulse.start, self.sensor_pulse.end

    @property
    def sensor_response_time(self):
        """Duration of the sensor signal's first lobe [s] (nan if it does not end)."""
        return self.sensor_pulse.duration

    @property
    def peak_sensor_force(self):
        """Largest sensor signal S1 in its first lobe [N]."""
        return self.sensor_pulse.peak

    @property
    def impulse(self):
        """Sum of the engine's contact impulses ``dt * S2`` over all steps [N*s]."""
        return self.time_step * float(np.sum(self.contact_force))

    @property
    def rebound_velocity(self):
        """Grain speed away from the sensor at the end of its last contact [m/s]."""
        end = self.contact_intervals[-1][1]
        return -float(np.interp(end, self.t, self.v2))

    def summary(self):
        """Headline numbers and engine settings as a dict with unit-bearing keys (JSON-ready)."""
        return {**self._headline(), **self.metadata}

    def __repr__(self):
        return (
            f"EngineResult({type(self.law).__name__}, engine='pybullet', "
            f"time_step={self.time_step:.3g} s, "
            f"contact_time={self.contact_time * 1e6:.4g} us, "
            f"peak_contact_force={self.peak_contact_force:.4g} N, "
            f"sensor_response_time={self.sensor_response_time * 1e6:.4g} us, "
            f"peak_sensor_force={self.peak_sensor_force:.4g} N, "
            f"restitution={self.restitution:.4g}, "
            f"numerical_damping={self.numerical_damping:.3g} N*s/m, "
            f"contacts={len(self.contact_intervals)})"
        )


def _crossings(indicator, t):
    """(rise, fall) times [s] where ``indicator`` changes sign, linearly interpolated.

    A trailing ``nan`` fall marks a contact still open at the end.
    """
    positive = indicator > 0.0
    edges = np.flatnonzero(positive[1:] != positive[:-1]) + 1
    y0, y1 = indicator[edges - 1], indicator[edges]
    times = t[edges - 1] + (t[edges] - t[edges - 1]) * y0 / (y0 - y1)
    rises = times[positive[edges]]
    falls = times[~positive[edges]]
    if positive[-1]:
        falls = np.append(falls, np.nan)
    return rises, falls


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
    k2, c2 = _law_parameters(law)
    velocity = check_number("velocity", velocity, low=0.0, low_open=not gravity, unit="m/s")
    dt = _check_time_step(time_step, grain, sensor, law)
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


def _run(scene, client, plate, grain, stop, step_limit):
    """Step the engine; return the recorded columns ``(q, q', z, z', S2)`` and whether it ended.

    Element 0 is the state at release, element ``i`` the state after step ``i``. ``stop``
    is the number of steps run after both the last contact (engine force > 0) and the end of
    the sensor signal's first lobe (``None``: all ``step_limit`` steps). Per step: one joint
    force, one engine step, four state reads and stores into preallocated lists (a numpy
    row assignment costs 0.7 us, five list stores 0.1 us).
    """
    import pybullet as pb

    rigid = scene.sensor.is_rigid
    k1 = 0.0 if rigid else scene.sensor.stiffness
    c1 = 0.0 if rigid else scene.sensor.damping
    q0, preload = scene.plate_rest, scene.preload
    step, joint_state = pb.stepSimulation, pb.getJointState
    motor, torque = pb.setJointMotorControl2, pb.TORQUE_CONTROL
    position, velocity = pb.getBasePositionAndOrientation, pb.getBaseVelocity
    contacts = pb.getContactPoints
    qs, qds, zs, zds, forces = ([0.0] * (step_limit + 1) for _ in range(5))
    qs[0] = q = q0
    qd = s1 = 0.0
    zs[0] = position(grain, physicsClientId=client)[0][2]
    zds[0] = velocity(grain, physicsClientId=client)[0][2]
    last_contact = lobe_end = -1
    rising = False
    end = step_limit
    for i in range(1, step_limit + 1):
        if not rigid:
            motor(plate, 0, torque, force=-(s1 + preload), physicsClientId=client)
        step(physicsClientId=client)
        if not rigid:
            q, qd = joint_state(plate, 0, physicsClientId=client)[:2]
        force = 0.0
        for point in contacts(grain, plate, physicsClientId=client):
            force += point[9]
        qs[i], qds[i], forces[i] = q, qd, force
        zs[i] = position(grain, physicsClientId=client)[0][2]
        zds[i] = velocity(grain, physicsClientId=client)[0][2]
        s1 = force if rigid else k1 * (q - q0) + c1 * qd
        if force > 0.0:
            last_contact = i
        if last_contact < 0:
            continue
        if s1 > 0.0:
            rising = True
        elif rising and lobe_end < 0:
            lobe_end = i
        if stop is not None and lobe_end >= 0 and i >= max(last_contact, lobe_end) + stop:
            end = i
            break
    columns = np.array([qs, qds, zs, zds, forces])[:, : end + 1]
    return columns, stop is None or end < step_limit


def _read(scene, columns, threshold, complete, wall):
    """The :class:`EngineResult` of the recorded columns."""
    import pybullet as pb

    q, qd, z, zd, force = columns
    sensor, dt = scene.sensor, scene.time_step
    x1 = q - scene.plate_rest
    x2 = scene.grain.radius - scene.plate_rest - z
    v1, v2 = qd, -zd
    indicator = scene.contact_stiffness * (x2 - x1) + scene.contact_damping * np.minimum(
        v2 - v1, 0.0
    )
    steps = np.arange(force.size) * dt
    starts, ends = _crossings(indicator, steps)
    if starts.size == 0:
        raise ParameterError(
            f"the grain did not reach the plate in {steps[-1]:.4g} s; check velocity and gap"
        )
    touch = float(starts[0])
    t = steps - touch
    intervals = [(float(a - touch), float(b - touch)) for a, b in zip(starts, ends, strict=True)]
    if not complete or math.isnan(intervals[-1][1]):
        warnings.warn(
            f"the engine window ({t[-1]:.4g} s after touch) ended before the contact and the "
            "sensor signal's first lobe were over; give a longer duration",
            WindowWarning,
            stacklevel=3,
        )
    sensor_force = force.copy() if sensor.is_rigid else sensor.stiffness * x1 + sensor.damping * v1
    metadata = {
        "engine": f"pybullet (API {pb.getAPIVersion()})",
        "time_step [s]": dt,
        "steps": force.size - 1,
        "touch_time [s]": touch,
        "gravity [m/s^2]": scene.gravity,
        "contact_stiffness [N/m]": scene.contact_stiffness,
        "contact_damping_passed [N*s/m]": scene.contact_damping,
        "numerical_damping [N*s/m]": scene.numerical_damping,
        "compensate_damping": scene.compensate_damping,
        "wall_time [s]": wall,
    }
    return EngineResult(
        grain=scene.grain,
        sensor=sensor,
        law=scene.law,
        velocity=scene.impact_speed,
        t=t,
        signals=(x1, v1, x2, v2, force, sensor_force),
        intervals=intervals,
        metadata=metadata,
        threshold=threshold,
    )


def drop_test(
    grain,
    sensor,
    law,
    velocity,
    time_step=None,
    gravity=False,
    *,
    compensate_damping=False,
    gap=None,
    duration=None,
    threshold=0.0,
):
    """Drop the grain on the sensor in pybullet and read the impact like the reduced model.

    Parameters
    ----------
    grain : Grain
        The grain (a sphere of its diameter and mass).
    sensor : Sensor
        The sensor: a plate of mass ``m1`` on a prismatic joint with the element ``k1, c1``
        as a joint force; ``Sensor.rigid()`` is a fixed plate.
    law : LinearViscoelastic
        Grain-plate contact; other laws raise ParameterError (see the module docstring).
    velocity : float
        Grain speed towards the plate at release [m/s]; the impact speed without gravity.
        May be 0 with ``gravity=True`` and a ``gap``.
    time_step : float, optional
        Engine step [s]; default :func:`default_time_step`. At most 1/20 of the contact
        (on an immovable wall) and of the sensor period.
    gravity : bool, default False
        Standard gravity along the travel. The plate then starts at rest under its weight
        and ``x1``, ``S1`` are read from there (a piezoelectric sensor does not report its
        static preload; rounding leaves ``|S1| ~ 1e-18 N`` before touch, so read lobes
        with a small ``threshold``). The impact speed is ``sqrt(v**2 + 2 g gap)``.
    compensate_damping : bool, default False
        Pass ``contactDamping = c2 - k2 * dt`` to cancel the implicit contact's numerical
        damping ``k2 * dt``; needs ``c2 >= k2 * dt``.
    gap : float, optional
        Distance between grain and plate at release [m]; default 3.5 steps of travel.
    duration : float, optional
        Time simulated after the first touch [s]. Default: until :data:`TAIL` after both
        the last contact and the end of the sensor signal's first lobe (a
        :class:`~contactlab.errors.WindowWarning` if that takes longer than ten contact
        times and twenty sensor periods).
    threshold : float, default 0
        Level [N] at which the sensor signal's first lobe is read.

    Returns
    -------
    EngineResult
        Its ``metadata`` holds the engine settings, ``numerical_damping [N*s/m]``, the
        steps taken, the time from release to touch and the wall time of the steps.

    Raises
    ------
    ParameterError
        For a law the engine cannot represent, a time step too coarse for the contact or
        the sensor, ``compensate_damping`` with ``c2 < k2 * dt``, ``gravity`` or
        ``compensate_damping`` not a bool, or a grain that never reaches the plate.

    Examples
    --------
    >>> import contactlab as cl
    >>> grain = cl.Grain(diameter=5e-3, density=765.0)
    >>> law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=0.0)
    >>> res = drop_test(grain, cl.Sensor.rigid(), law, velocity=2.0)
    >>> round(res.contact_time * 1e6, 1)  # pi sqrt(m/k) = 70.3 us
    70.3
    """
    import pybullet as pb

    scene = drop_scene(
        grain,
        sensor,
        law,
        velocity,
        time_step,
        gravity,
        compensate_damping=compensate_damping,
        gap=gap,
    )
    threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    dt = scene.time_step
    if duration is None:
        after = 10.0 * _contact_time_estimate(grain, law) + 20.0 * sensor.period + TAIL
        stop = math.ceil(TAIL / dt)
    else:
        after = check_number("duration", duration, low=0.0, unit="s")
        stop = None
    step_limit = math.ceil((scene.approach_time + after) / dt)
    if step_limit > MAX_STEPS:
        raise ParameterError(
            f"duration = {after:.4g} s at time_step = {dt:.3g} s needs {step_limit} engine "
            f"steps; the bench records at most {MAX_STEPS} (about "
            f"{MAX_STEPS * _BYTES_PER_STEP / 1e6:.0f} MB of signals): shorten duration or "
            "lengthen time_step"
        )
    client = pb.connect(pb.DIRECT)  # a fresh engine per run: nothing carries over
    try:
        plate, body = scene.build(client)
        clock = time.perf_counter()
        columns, complete = _run(scene, client, plate, body, stop, step_limit)
        wall = time.perf_counter() - clock
    finally:
        pb.disconnect(client)
    return _read(scene, columns, threshold, complete, wall)


def engine_check(
    grain, sensor, law, velocity, time_step=None, *, compensate_damping=False, tolerances=None
):
    """Run the impact in pybullet and in the reduced model, and compare them.

    Parameters
    ----------
    grain, sensor, law, velocity, time_step, compensate_damping
        As for :func:`drop_test` (no gravity: the reduced model has none).
    tolerances : dict, optional
        Tolerances by quantity name (:data:`dem_check.compare.DEFAULT_TOLERANCES`).

    Returns
    -------
    dem_check.compare.Comparison
        ``a`` is the :class:`EngineResult`, ``b`` the :class:`~contactlab.ImpactResult`
        (exact solver) over the same window. Both start at the first touch, so the
        waveforms are compared without shifting (``align=None``). ``notes`` holds the time
        step, the numerical damping and the wall time of the engine steps.
    """
    from contactlab.solver import simulate_impact
    from dem_check.compare import compare

    engine = drop_test(
        grain, sensor, law, velocity, time_step, compensate_damping=compensate_damping
    )
    model = simulate_impact(grain, sensor, law, velocity, duration=float(engine.t[-1]))
    comparison = compare(engine, model, tolerances, align=None, labels=("pybullet", "model"))
    meta = engine.metadata
    comparison.notes.update(
        {
            key: meta[key]
            for key in (
                "time_step [s]",
                "numerical_damping [N*s/m]",
                "contact_damping_passed [N*s/m]",
                "compensate_damping",
                "steps",
                "wall_time [s]",
            )
        }
    )
    return comparison


def convergence_study(
    grain,
    sensor,
    law,
    velocity,
    time_steps=(4e-7, 2e-7, 1e-7, 5e-8),
    *,
    compensate_damping=False,
):
    """Errors of the engine against the reduced model as the time step shrinks.

    Parameters
    ----------
    grain, sensor, law, velocity, compensate_damping
        As for :func:`drop_test`.
    time_steps : sequence of float
        Engine steps [s], at least two.

    Returns
    -------
    pandas.DataFrame
        One row per step: ``time_step [s]``, ``wall_time [s]`` and the error of each
        quantity of :data:`dem_check.compare.QUANTITIES` as ``<name> error [-]`` (signed
        relative errors; restitution: signed absolute; waveforms: over the model's peak).
        ``attrs["order"]`` maps each quantity to the observed order of convergence, the
        least-squares slope of ``log |error|`` against ``log dt`` (1 for a first-order
        method).
    """
    import pandas as pd

    if len(time_steps) < 2:
        raise ParameterError(f"time_steps needs at least two steps [s]; got {time_steps!r}")
    rows = []
    for dt in time_steps:
        comparison = engine_check(
            grain, sensor, law, velocity, dt, compensate_damping=compensate_damping
        )
        row = {"time_step [s]": comparison.notes["time_step [s]"]}
        for item in comparison.table.itertuples():
            absolute = item.basis == "absolute"
            row[f"{item.quantity} error [-]"] = item.a - item.b if absolute else item.rel_error
        row["wall_time [s]"] = comparison.notes["wall_time [s]"]
        rows.append(row)
    frame = pd.DataFrame(rows)
    log_dt = np.log(frame["time_step [s]"].to_numpy())
    frame.attrs["order"] = {}
    for column in frame.columns:
        if column.endswith(" error [-]"):
            error = np.abs(frame[column].to_numpy(dtype=float))
            slope = np.polyfit(log_dt, np.log(error), 1)[0] if np.all(error > 0) else math.nan
            frame.attrs["order"][column.removesuffix(" error [-]")] = float(slope)
    frame.attrs["compensate_damping"] = bool(compensate_damping)
    return frame


def base_case_check(out_dir, time_step=None):
    """Engine check of the paper's base case, written to a folder (``make demo``).

    The base case is the preset ``fig6`` grain and law (5 mm grain, k2 = 1e5 N/m,
    c2 = 1 N*s/m, 2 m/s) on the paper's 40 kHz disc sensor
    (``Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)``).

    Parameters
    ----------
    out_dir : str or pathlib.Path
        Output folder (created).
    time_step : float, optional
        Engine step [s]; default :func:`default_time_step`.

    Returns
    -------
    list of pathlib.Path
        ``bullet_base_case.png`` (overlay), ``bullet_base_case.csv`` (the comparison
        table) and ``bullet_base_case.json`` (table, verdict and engine settings).
    """
    import json

    import matplotlib.pyplot as plt

    from contactlab.config import load_preset

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    base = load_preset("fig6")
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    comparison = engine_check(base.grain, sensor, base.law, base.simulation["velocity"], time_step)
    paths = [out / f"bullet_base_case.{ext}" for ext in ("png", "csv", "json")]
    fig, _ = comparison.plot(title="base case: pybullet vs reduced model, 40 kHz sensor")
    fig.savefig(paths[0], dpi=150)
    plt.close(fig)
    comparison.table.to_csv(paths[1], index=False)
    paths[2].write_text(json.dumps(comparison.to_dict(), indent=2), encoding="utf-8")
    return paths
