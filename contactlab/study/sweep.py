"""Monte Carlo sweeps: impacts over a grid of parameters, and their error statistics.

For every grid point the impact is repeated with the contact stiffness scattered
(:class:`~contactlab.study.setup.Scatter`) and two signed relative errors are read per
impact, as an experimenter would (Keska et al. 2021, Figures 10-12):

* contact-time error: ``sensor_response_time / contact_time - 1`` (the first main lobe of
  the sensor signal against the true contact duration);
* peak-force error: ``peak_sensor_force / peak_contact_force - 1``.

Per grid point, in percent: the paper's measure, the standard deviation of the errors over
the repetitions (``time_error [%]``, ``force_error [%]``), and also their mean (the bias,
which the standard deviation does not see) and their RMS, ``rms**2 = mean**2 + std**2``.
The standard deviation is the population one (``ddof = 0``) for that identity to hold.
"""

import itertools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from contactlab.entry_checks import check_flag, check_instance, check_names
from contactlab.errors import ParameterError
from contactlab.study.execution import run_tasks
from contactlab.study.points import batched, error_percent, simulate_point, simulate_points
from contactlab.study.setup import StudySetup
from contactlab.tables import write_csv
from contactlab.validation import check_count, make_folder

__all__ = [
    "ERRORS",
    "SweepResult",
    "diameter_sweep",
    "error_percent",
    "frequency_sweep",
    "point_statistics",
    "run_grid",
    "simulate_point",
    "simulate_points",
]

ERRORS = ("time", "force")
"""The two errors of the study: contact time and peak force."""


def _point_task(task):
    return simulate_point(*task)


def point_statistics(impacts, by):
    """Per-point error statistics of a per-impact frame.

    Parameters
    ----------
    impacts : pandas.DataFrame
        Per-impact frame (:attr:`SweepResult.impacts`).
    by : str or list of str
        Column(s) that identify a grid point.

    Returns
    -------
    pandas.DataFrame
        One row per point: the ``by`` columns, ``repetitions [-]``,
        ``contact_time_mean [s]``, and for ``q`` in time, force: ``q_error [%]``
        (standard deviation, ``ddof = 0``), ``q_error_mean [%]``, ``q_error_rms [%]``.
    """
    check_instance("impacts", impacts, pd.DataFrame, "SweepResult.impacts")
    by = list(check_names("by", by))
    needed = [*by, "contact_time [s]", *(f"{q}_error [%]" for q in ERRORS)]
    missing = [c for c in needed if c not in impacts.columns]
    if missing:
        raise ParameterError(f"impacts has no column(s) {missing} (by = {list(by)!r})")
    groups = impacts.groupby(by, sort=False)
    out = groups.size().rename("repetitions [-]").to_frame()
    out["contact_time_mean [s]"] = groups["contact_time [s]"].mean()
    for q in ERRORS:
        col = f"{q}_error [%]"
        out[col] = groups[col].std(ddof=0)
        out[f"{q}_error_mean [%]"] = groups[col].mean()
        out[f"{q}_error_rms [%]"] = groups[col].apply(lambda e: math.sqrt(np.mean(e**2)))
    return out.reset_index()


@dataclass
class SweepResult:
    """Result of a sweep: one row per impact and one row per grid point.

    Attributes
    ----------
    impacts : pandas.DataFrame
        Per impact: ``point [-]``, ``repetition [-]``, the grid columns,
        ``diameter [m]``, ``resonance [Hz]``, the scattered law parameters
        (``stiffness [N/m]`` ...), true and sensor-read times and peaks, and the signed
        errors ``time_error [%]``, ``force_error [%]``.
    points : pandas.DataFrame
        Per grid point: the grid columns, ``diameter [m]``, ``resonance [Hz]`` and the
        statistics of :func:`point_statistics`.
    setup : StudySetup
        The base set-up.
    grid : dict
        Grid parameter name -> values, as swept.
    seed : int
        Root seed of the draws.
    """

    impacts: pd.DataFrame
    points: pd.DataFrame
    setup: StudySetup
    grid: dict
    seed: int

    def to_csv(self, directory, name):
        """Write ``name.csv`` (points) and ``name_impacts.csv`` (impacts) into a folder.

        Parameters
        ----------
        directory : str or pathlib.Path
            Output folder (created).
        name : str
            Stem of the two file names.

        Returns
        -------
        list of pathlib.Path
            The two files.
        """
        directory = make_folder("directory", directory)
        paths = [directory / f"{name}.csv", directory / f"{name}_impacts.csv"]
        write_csv(self.points, paths[0])
        write_csv(self.impacts, paths[1])
        return paths


def _grid_points(setup, grid):
    """Validated grid: names, their values, and the override dict of every point (the
    first name varies slowest)."""
    if not isinstance(grid, dict) or not grid:
        raise ParameterError(f"grid must be a non-empty dict of name -> values; got {grid!r}")
    names = [setup.check_parameter(name) for name in grid]
    values = []
    for name in names:
        try:
            vals = np.atleast_1d(np.asarray(grid[name], dtype=float))
        except (TypeError, ValueError):
            vals = None
        if vals is None or vals.ndim != 1 or vals.size == 0:
            raise ParameterError(
                f"grid[{name!r}] must be a non-empty 1-D sequence of numbers; got {grid[name]!r}"
            )
        values.append([float(v) for v in vals])
    return (
        names,
        values,
        [dict(zip(names, combo, strict=True)) for combo in itertools.product(*values)],
    )


def run_grid(
    setup,
    grid,
    *,
    seed=0,
    workers=1,
    client=None,
    chunksize=None,
    progress=None,
):
    """Monte Carlo impacts over the Cartesian product of a parameter grid.

    Parameters
    ----------
    setup : StudySetup
        Base set-up, scatter and settings.
    grid : dict
        Parameter name -> values, e.g. ``{"grain.diameter": [2.5e-3, 5e-3],
        "sensor.resonance": np.geomspace(10e3, 300e3, 30)}``; names as in
        :meth:`StudySetup.parameter_names` (an unknown name raises with a near-match
        suggestion). The first name varies slowest.
    seed : int, default 0
        Root seed. Point ``i`` draws from ``SeedSequence(seed, spawn_key=(i,))`` (the
        ``i``-th child of ``SeedSequence(seed).spawn``), so results do not depend on the
        execution order, the number of workers or the backend.
    workers : int, default 1
        Local worker processes. A linear, Hertz or damped-Hertz law is solved by the
        batch solvers instead (:func:`simulate_points`: compiled, in this process or on
        ``client``), which need no workers.
    client : dask.distributed.Client or str, optional
        Run on a Dask cluster instead (see :func:`contactlab.study.execution.run_tasks`).
    chunksize : int, optional
        Grid points per task sent to a worker.
    progress : bool, optional
        tqdm progress bar (default: only on an interactive terminal).

    Returns
    -------
    SweepResult
    """
    if not isinstance(setup, StudySetup):
        raise ParameterError(f"setup must be a StudySetup; got {type(setup).__name__}")
    seed = check_count("seed", seed, low=0)
    progress = check_flag("progress", progress, optional=True)
    check_count("workers", workers)  # here too: a linear law's grid never reaches the pool
    if chunksize is not None:
        check_count("chunksize", chunksize)
    names, values, points = _grid_points(setup, grid)
    factors = [
        setup.scatter.factors(np.random.SeedSequence(seed, spawn_key=(i,)))
        for i in range(len(points))
    ]
    tasks = [(setup, point, f) for point, f in zip(points, factors, strict=True)]
    if batched(setup.law):
        results = simulate_points(tasks, client=client, progress=progress)
    else:
        results = run_tasks(
            _point_task,
            tasks,
            workers=workers,
            client=client,
            chunksize=chunksize,
            progress=progress,
            desc="impacts",
        )
    grid_columns = {name: setup.column(name) for name in names}
    frames = []
    for i, (point, result) in enumerate(zip(points, results, strict=True)):
        n = len(result["contact_time [s]"])
        config = setup.config(point)
        grain, sensor = config.grain, config.sensor
        head = {"point [-]": [i] * n, "repetition [-]": list(range(n))}
        head.update({grid_columns[name]: [point[name]] * n for name in names})
        head.setdefault("diameter [m]", [grain.diameter] * n)
        head.setdefault("resonance [Hz]", [sensor.resonance] * n)
        frames.append(pd.DataFrame({**head, **result}))
    impacts = pd.concat(frames, ignore_index=True)
    by = list(
        dict.fromkeys(["point [-]", *grid_columns.values(), "diameter [m]", "resonance [Hz]"])
    )
    points_frame = point_statistics(impacts, by).drop(columns="point [-]")
    return SweepResult(impacts, points_frame, setup, dict(zip(names, values, strict=True)), seed)


def frequency_sweep(setup, resonances, diameters=None, **options):
    """Errors against sensor resonance (Figures 10 and 11), optionally per grain diameter.

    Parameters
    ----------
    setup : StudySetup
        Base set-up, scatter and settings.
    resonances : array_like
        Sensor resonances [Hz] (``sensor.resonance``, varying fastest).
    diameters : array_like, optional
        Grain diameters [m] (``grain.diameter``); default the set-up's grain only.
    **options
        Keyword arguments of :func:`run_grid` (``seed``, ``workers``, ...).

    Returns
    -------
    SweepResult
    """
    return _along(setup, "sensor.resonance", resonances, "grain.diameter", diameters, options)


def diameter_sweep(setup, diameters, resonances=None, **options):
    """Errors against grain diameter (Figure 12), optionally per sensor resonance.

    Parameters
    ----------
    setup : StudySetup
        Base set-up; how the contact law follows the diameter is
        ``setup.size_dependence``.
    diameters : array_like
        Grain diameters [m] (``grain.diameter``, varying fastest).
    resonances : array_like, optional
        Sensor resonances [Hz] (``sensor.resonance``); default the set-up's sensor only.
    **options
        As for :func:`frequency_sweep`.

    Returns
    -------
    SweepResult
    """
    return _along(setup, "grain.diameter", diameters, "sensor.resonance", resonances, options)


def _along(setup, name, values, other, other_values, options):
    """:func:`run_grid` over ``values`` of ``name`` (varying fastest), for each of
    ``other_values`` of ``other`` when given (else the set-up's own)."""
    grid = {} if other_values is None else {other: other_values}
    return run_grid(setup, {**grid, name: values}, **options)
