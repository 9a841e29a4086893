"""One grid point of a sweep: its impacts, one by one or all points at once in a batch.

:func:`simulate_point` simulates the repetitions of one grid point with
:func:`contactlab.simulate_impact` and reads the two errors of the study (the sensor's
first lobe against the contact time, its peak against the contact force's);
:func:`simulate_points` does the same for many points, handing a linear or Hertz-family
law to the batch solvers (:mod:`contactlab.batch`) in one call.
"""

import math
from collections.abc import Iterable
from dataclasses import replace

import numpy as np
import pandas as pd

from contactlab.batch import (
    dask_hertz_impacts,
    dask_linear_impacts,
    hertz_impacts,
    linear_impacts,
)
from contactlab.batch.dask import check_client
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.laws.base import stated
from contactlab.laws.closed_form import closed_value
from contactlab.quantities import columns
from contactlab.solver.wall import wall_contact_time
from contactlab.study.execution import progress_bar
from contactlab.study.setup import StudySetup
from contactlab.validation import check_values

__all__ = ["batched", "error_percent", "simulate_point", "simulate_points"]

_READING_NAMES = (
    "contact_time",
    "sensor_response_time",
    "peak_contact_force",
    "peak_sensor_force",
)
"""An impact's readings kept per point, as :mod:`contactlab.quantities` names them."""

_READINGS = columns(*_READING_NAMES)


def _with_errors(readings):
    """The readings (column -> array) and the study's two errors [%] computed from them."""
    time, response, force, signal = (np.asarray(readings[name]) for name in _READINGS)
    return {
        **{name: np.asarray(readings[name]).tolist() for name in _READINGS},
        "time_error [%]": error_percent(response, time).tolist(),
        "force_error [%]": error_percent(signal, force).tolist(),
    }


def _rigid_contact_time(law, mass, velocity):
    """Contact time of the law on an immovable wall [s]: its closed form where the law
    states an exact one, else the simulated wall impact."""
    closed = closed_value(law, "contact_time", mass, velocity)
    return wall_contact_time(law, mass, velocity) if closed is None else closed


def error_percent(reading, truth):
    """Error of a reading against the truth [%]: ``100 (reading / truth - 1)``.

    Works on floats and arrays; a reading above the truth gives a positive error.
    """
    return 100.0 * (reading / truth - 1.0)


def _checked_point(setup, factors, where=""):
    """``factors`` as a float array after checking the set-up and the factors of a grid
    point (the overrides are checked by :meth:`StudySetup.config`); ``where`` prefixes
    the names in the messages (``"tasks[3] "``)."""
    if not isinstance(setup, StudySetup):
        raise ParameterError(f"{where}setup must be a StudySetup; got {type(setup).__name__}")
    return check_values(f"{where}factors", factors, unit="-")


def _checked_tasks(tasks):
    """The tasks as a list of ``(setup, overrides, factors)``, each checked."""
    if isinstance(tasks, str | bytes) or not isinstance(tasks, Iterable):
        raise ParameterError(
            f"tasks must be an iterable of (StudySetup, overrides, factors); got {tasks!r}"
        )
    checked = []
    for i, task in enumerate(tasks):
        if not isinstance(task, tuple | list) or len(task) != 3:
            raise ParameterError(
                f"tasks[{i}] must be (StudySetup, overrides dict, factors); got {task!r}"
            )
        setup, overrides, factors = task
        checked.append((setup, overrides, _checked_point(setup, factors, f"tasks[{i}] ")))
    return checked


def simulate_point(setup, overrides, factors):
    """Simulate the repetitions of one grid point.

    Parameters
    ----------
    setup : StudySetup
        The base set-up.
    overrides : dict
        Grid parameter name -> value at this point.
    factors : array_like
        Scatter factors [-] of the ``setup.varied`` parameters, one impact each.

    Returns
    -------
    dict
        Column name -> list of per-impact values: the scattered law parameters
        (``stiffness [N/m]`` ...) and ``contact_time [s]``, ``sensor_response_time [s]``,
        ``peak_contact_force [N]``, ``peak_sensor_force [N]``, ``time_error [%]``,
        ``force_error [%]``.

    Notes
    -----
    The window is the solver's default (the whole first contact and five sensor periods
    of ringing after it, in which the sensor's first lobe has long ended); the output
    grid has ``setup.samples_per_period`` samples per the shortest of the sensor period
    and the rigid-wall contact times of the two extreme draws (the contact time is
    monotone in a scattered stiffness, damping or pulse length, so one of them is the
    shortest of all draws).
    """
    factors = _checked_point(setup, factors)
    config = setup.config(overrides)
    grain, sensor, law, velocity = config.grain, config.sensor, config.law, config.velocity
    extremes = {float(np.min(factors)), float(np.max(factors))}
    shortest = min(
        sensor.period,
        *(_rigid_contact_time(setup.scattered(law, f), grain.mass, velocity) for f in extremes),
    )
    sample_rate = setup.samples_per_period / shortest
    varied = setup.varied_columns()
    out = {name: [] for name in (*varied, *_READINGS)}
    for factor in factors:
        drawn = replace(config, law=setup.scattered(law, float(factor)))
        res = drawn.simulate(sample_rate=sample_rate)
        params = drawn.law.parameters()
        for name, column in zip(setup.varied, varied, strict=True):
            out[column].append(params[name])
        for column, name in zip(_READINGS, _READING_NAMES, strict=True):
            out[column].append(getattr(res, name))
    return {**{column: out[column] for column in varied}, **_with_errors(out)}


_BATCHED = {
    "linear": (linear_impacts, dask_linear_impacts),
    "hertz": (hertz_impacts, dask_hertz_impacts),
}
"""Batch solvers a sweep hands impacts to, by the name a law's ``batch_contact()`` gives:
the solver and its Dask twin (:meth:`ImpactConfig.batch_row` writes the rows)."""


def _batch_solver(law):
    """The name of the law's batch solver, or None."""
    batch_contact = stated(law, "_batch_contact")
    return None if batch_contact is None else batch_contact()[0]


def _batch_frame(tasks):
    """The batch solver's input rows of every impact of the tasks, and the drawn laws."""
    rows, laws = [], []
    for setup, overrides, factors in tasks:
        config = setup.config(overrides)
        for factor in factors:
            drawn = replace(config, law=setup.scattered(config.law, float(factor)))
            laws.append(drawn.law)
            rows.append(drawn.batch_row())
    return pd.DataFrame(rows), laws


BATCH_BLOCKS = 20
"""Blocks a batched sweep is solved in when a progress bar is shown (one update each)."""


def _solve_batch(frame, impacts, on_dask, client, progress):
    """``impacts(frame)``: on a Dask cluster, or here in blocks under a bar."""
    if client is not None:
        return on_dask(frame, client)
    bar = progress_bar(len(frame), progress, "impacts", unit="impact")
    if bar is None:
        return impacts(frame, threads=None)
    parts = []
    with bar:
        size = max(1, math.ceil(len(frame) / BATCH_BLOCKS))
        for lo in range(0, len(frame), size):
            parts.append(impacts(frame.iloc[lo : lo + size], threads=None))
            bar.update(len(parts[-1]))
    return pd.concat(parts)


def batched(law):
    """Whether a sweep hands impacts with this law to a batch solver."""
    return _batch_solver(law) in _BATCHED


def _batch_kind(tasks):
    """The :data:`_BATCHED` entry every task's law shares, or None."""
    kinds = {type(task[0].law) for task in tasks}
    if len(kinds) != 1:
        return None
    return _BATCHED.get(_batch_solver(tasks[0][0].law))


def simulate_points(tasks, *, client=None, progress=None):
    """:func:`simulate_point` of every ``(setup, overrides, factors)`` task.

    A linear (Kelvin-Voigt), elastic Hertz or damped Hertz (Tsuji) law is solved for
    all tasks at once by :func:`contactlab.batch.linear_impacts` or
    :func:`contactlab.batch.hertz_impacts` (on every core of this machine, or on
    ``client``'s Dask cluster when one is given, partitioned by rows), which give the
    single solver's numbers (``docs/batch.md``) and read the sensor lobe on the exact or
    dense solution instead of an output grid; any other law goes through
    :func:`simulate_point`, task by task, here.

    Parameters
    ----------
    tasks : iterable of (StudySetup, dict, array_like)
        Set-up, grid-point overrides and scatter factors, as :func:`simulate_point` takes.
    client : dask.distributed.Client or str, optional
        Dask cluster for a batched law.
    progress : bool, optional
        tqdm progress bar (default: only on an interactive terminal).

    Returns
    -------
    list of dict
        One :func:`simulate_point` dict per task.
    """
    tasks = _checked_tasks(tasks)
    client = check_client(client)
    progress = check_flag("progress", progress, optional=True)
    kind = _batch_kind(tasks) if tasks else None
    if kind is None:
        return [simulate_point(*task) for task in tasks]
    impacts, on_dask = kind
    frame, laws = _batch_frame(tasks)
    solved = _solve_batch(frame, impacts, on_dask, client, progress)
    results, start = [], 0
    for setup, _, factors in tasks:
        stop = start + len(factors)
        part = solved.iloc[start:stop]
        out = {
            column: [law.parameters()[name] for law in laws[start:stop]]
            for name, column in zip(setup.varied, setup.varied_columns(), strict=True)
        }
        out.update(_with_errors(part))
        results.append(out)
        start = stop
    return results
