"""Stepping pybullet and reading its recorded steps as an :class:`EngineResult`.

:func:`step_engine` drives a built :class:`~dem_check.engines.bullet.scene.DropScene`
step by step, applying the sensor element as a joint force and recording the states;
:func:`read_steps` turns the recorded columns into the model's coordinates and signals.
"""

import math

import numpy as np

from contactlab.errors import ParameterError
from dem_check.engines.record import warn_short_window
from dem_check.engines.result import EngineResult, contact_crossings

__all__ = ["read_steps", "step_engine"]


def step_engine(scene, client, plate, grain, stop, step_limit):
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


def read_steps(scene, columns, threshold, complete, wall):
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
    starts, ends = contact_crossings(indicator, steps)
    if starts.size == 0:
        raise ParameterError(
            f"the grain did not reach the plate in {steps[-1]:.4g} s; check velocity and gap"
        )
    touch = float(starts[0])
    t = steps - touch
    intervals = [(float(a - touch), float(b - touch)) for a, b in zip(starts, ends, strict=True)]
    if not complete or math.isnan(intervals[-1][1]):
        warn_short_window("engine", t[-1], stacklevel=3)
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
        method="pybullet",
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
