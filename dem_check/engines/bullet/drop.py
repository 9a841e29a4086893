"""The pybullet drop test: one impact of the reduced model rebuilt in the engine."""

import math
import time

from contactlab.validation import check_number
from dem_check.engines.bullet.limits import contact_time_estimate
from dem_check.engines.bullet.run import read_steps, step_engine
from dem_check.engines.bullet.scene import drop_scene
from dem_check.engines.config import UNSET, engine_config
from dem_check.engines.record import step_limit

__all__ = ["MAX_STEPS", "TAIL", "drop_test"]

MAX_STEPS = 2_000_000
"""Most engine steps one drop test records (0.2 s of engine time at 1e-7 s, about 16 s of
stepping; five Python floats a step, about 320 MB); more is refused, not allocated."""

TAIL = 20e-6
"""Time simulated after the last contact and the end of the sensor signal's first lobe
[s]: the engine stops there unless ``duration`` is given."""


def drop_test(
    config,
    *fields,
    time_step=UNSET,
    gravity=False,
    compensate_damping=False,
    gap=None,
    duration=None,
    threshold=0.0,
):
    """Drop the grain on the sensor in pybullet and read the impact like the reduced model.

    Parameters
    ----------
    config : contactlab.config.ImpactConfig
        The set-up: ``grain`` (a sphere of its diameter and mass); ``sensor`` (a plate of
        mass ``m1`` on a prismatic joint with the element ``k1, c1`` as a joint force;
        ``Sensor.rigid()`` is a fixed plate); ``law``, a LinearViscoelastic (other laws
        raise ParameterError, see the module docstring); ``velocity``, the grain speed
        towards the plate at release [m/s], the impact speed without gravity (may be 0
        with ``gravity=True`` and a ``gap``).
    *fields
        Deprecated: ``drop_test(grain, sensor, law, velocity[, time_step])``
        (:func:`dem_check.engines.config.engine_config`).
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
    >>> setup = cl.config.ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": 2.0})
    >>> res = drop_test(setup)
    >>> round(res.contact_time * 1e6, 1)  # pi sqrt(m/k) = 70.3 us
    70.3
    """
    import pybullet as pb

    config, time_step = engine_config(config, fields, time_step, "dem_check.bullet.drop_test")
    grain, sensor, law = config.grain, config.sensor, config.law
    scene = drop_scene(
        grain,
        sensor,
        law,
        config.velocity,
        time_step,
        gravity,
        compensate_damping=compensate_damping,
        gap=gap,
    )
    threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    dt = scene.time_step
    if duration is None:
        after = 10.0 * contact_time_estimate(grain, law) + 20.0 * sensor.period + TAIL
        stop = math.ceil(TAIL / dt)
    else:
        after = check_number("duration", duration, low=0.0, unit="s")
        stop = None
    limit = step_limit(scene, after, MAX_STEPS, "engine")
    client = pb.connect(pb.DIRECT)  # a fresh engine per run: nothing carries over
    try:
        plate, body = scene.build(client)
        clock = time.perf_counter()
        columns, complete = step_engine(scene, client, plate, body, stop, limit)
        wall = time.perf_counter() - clock
    finally:
        pb.disconnect(client)
    return read_steps(scene, columns, threshold, complete, wall)
