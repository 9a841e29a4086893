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
from pathlib import Path

import numpy as np
import pandas as pd

from contactlab import analytic
from contactlab.batch import dask_linear_impacts, linear_impacts
from contactlab.errors import ParameterError
from contactlab.laws import LinearViscoelastic
from contactlab.solver import simulate_impact
from contactlab.study.execution import progress_bar, run_tasks
from contactlab.study.setup import StudySetup
from contactlab.validation import check_count

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

_IMPACT_COLUMNS = (
    "contact_time [s]",
    "sensor_response_time [s]",
    "peak_contact_force [N]",
    "peak_sensor_force [N]",
    "time_error [%]",
    "force_error [%]",
)


_CLOSED_FORMS = {
    "linear": lambda law, m, v: analytic.linear_contact_time(
        law.stiffness, law.damping, m, convention="force"
    ),
    "hertz": lambda law, m, v: analytic.hertz_contact_time(law.k_hertz, m, v),
    "plastic_trapezoid": lambda law, m, v: law.contact_time,
}
"""Rigid-wall contact times in closed form [s]; other laws simulate the wall impact."""


def _rigid_contact_time(law, mass, velocity):
    """Contact time of the law on an immovable wall [s]."""
    closed = _CLOSED_FORMS.get(law.name)
    return law.contact_time(mass, velocity) if closed is None else closed(law, mass, velocity)


def error_percent(reading, truth):
    """Error of a reading against the truth [%]: ``100 (reading / truth - 1)``.

    Works on floats and arrays; a reading above the truth gives a positive error.
    """
    return 100.0 * (reading / truth - 1.0)


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
    grain, sensor, law, velocity = setup.at(overrides)
    extremes = {float(np.min(factors)), float(np.max(factors))}
    shortest = min(
        sensor.period,
        *(_rigid_contact_time(setup.scattered(law, f), grain.mass, velocity) for f in extremes),
    )
    sample_rate = setup.samples_per_period / shortest
    columns = setup.varied_columns()
    out = {name: [] for name in (*columns, *_IMPACT_COLUMNS)}
    for factor in factors:
        drawn = setup.scattered(law, float(factor))
        res = simulate_impact(grain, sensor, drawn, velocity, sample_rate=sample_rate)
        params = drawn.parameters()
        for name, column in zip(setup.varied, columns, strict=True):
            out[column].append(params[name])
        out["contact_time [s]"].append(res.contact_time)
        out["sensor_response_time [s]"].append(res.sensor_response_time)
        out["peak_contact_force [N]"].append(res.peak_contact_force)
        out["peak_sensor_force [N]"].append(res.peak_sensor_force)
        out["time_error [%]"].append(error_percent(res.sensor_response_time, res.contact_time))
        out["force_error [%]"].append(error_percent(res.peak_sensor_force, res.peak_contact_force))
    return out


def _point_task(task):
    return simulate_point(*task)


def _linear_frame(tasks):
    """The batch solver's input rows of every impact of the tasks, and the drawn laws."""
    rows, laws = [], []
    for setup, overrides, factors in tasks:
        grain, sensor, law, velocity = setup.at(overrides)
        for factor in factors:
            drawn = setup.scattered(law, float(factor))
            laws.append(drawn)
            rows.append(
                {
                    "m1 [kg]": sensor.mass,
                    "k1 [N/m]": sensor.stiffness,
                    "c1 [N*s/m]": sensor.damping,
                    "m2 [kg]": grain.mass,
                    "k2 [N/m]": drawn.stiffness,
                    "c2 [N*s/m]": drawn.damping,
                    "v0 [m/s]": velocity,
                }
            )
    return pd.DataFrame(rows), laws


LINEAR_BLOCKS = 20
"""Blocks a batched sweep is solved in when a progress bar is shown (one update each)."""


def _solve_linear(frame, client, progress):
    """``linear_impacts(frame)``: on a Dask cluster, or here in blocks under a bar."""
    if client is not None:
        return dask_linear_impacts(frame, client)
    bar = progress_bar(len(frame), progress, "impacts", unit="impact")
    if bar is None:
        return linear_impacts(frame, threads=None)
    parts = []
    with bar:
        size = max(1, math.ceil(len(frame) / LINEAR_BLOCKS))
        for lo in range(0, len(frame), size):
            parts.append(linear_impacts(frame.iloc[lo : lo + size], threads=None))
            bar.update(len(parts[-1]))
    return pd.concat(parts)


def simulate_points(tasks, *, client=None, progress=None):
    """:func:`simulate_point` of every ``(setup, overrides, factors)`` task.

    A linear (Kelvin-Voigt) law is solved for all tasks at once by
    :func:`contactlab.batch.linear_impacts` (on every core of this machine, or on
    ``client``'s Dask cluster when one is given, partitioned by rows), which gives the
    single solver's numbers (to 1e-9, ``docs/batch.md``) and reads the sensor lobe exactly
    instead of on an output grid; any other law goes through :func:`simulate_point`,
    task by task, here.

    Parameters
    ----------
    tasks : iterable of (StudySetup, dict, array_like)
        Set-up, grid-point overrides and scatter factors, as :func:`simulate_point` takes.
    client : dask.distributed.Client or str, optional
        Dask cluster for a linear law.
    progress : bool, optional
        tqdm progress bar (default: only on an interactive terminal).

    Returns
    -------
    list of dict
        One :func:`simulate_point` dict per task.
    """
    tasks = list(tasks)
    if not tasks or not all(isinstance(t[0].law, LinearViscoelastic) for t in tasks):
        return [simulate_point(*task) for task in tasks]
    frame, laws = _linear_frame(tasks)
    solved = _solve_linear(frame, client, progress)
    results, start = [], 0
    for setup, _, factors in tasks:
        stop = start + len(factors)
        part = solved.iloc[start:stop]
        out = {
            column: [law.parameters()[name] for law in laws[start:stop]]
            for name, column in zip(setup.varied, setup.varied_columns(), strict=True)
        }
        out["contact_time [s]"] = part["contact_time [s]"].tolist()
        out["sensor_response_time [s]"] = part["response_time [s]"].tolist()
        out["peak_contact_force [N]"] = part["peak_contact_force [N]"].tolist()
        out["peak_sensor_force [N]"] = part["peak_sensor_force [N]"].tolist()
        out["time_error [%]"] = error_percent(
            part["response_time [s]"], part["contact_time [s]"]
        ).tolist()
        out["force_error [%]"] = error_percent(
            part["peak_sensor_force [N]"], part["peak_contact_force [N]"]
        ).tolist()
        results.append(out)
        start = stop
    return results


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
    by = [by] if isinstance(by, str) else list(by)
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
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        paths = [directory / f"{name}.csv", directory / f"{name}_impacts.csv"]
        self.points.to_csv(paths[0], index=False)
        self.impacts.to_csv(paths[1], index=False)
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
        Local worker processes. A linear law is solved by the batch solver instead
        (:func:`simulate_points`: compiled, in this process or on ``client``), which
        needs no workers.
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
    names, values, points = _grid_points(setup, grid)
    factors = [
        setup.scatter.factors(np.random.SeedSequence(seed, spawn_key=(i,)))
        for i in range(len(points))
    ]
    tasks = [(setup, point, f) for point, f in zip(points, factors, strict=True)]
    if isinstance(setup.law, LinearViscoelastic):
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
        grain, sensor, _, _ = setup.at(point)
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
    grid = {} if diameters is None else {"grain.diameter": diameters}
    return run_grid(setup, {**grid, "sensor.resonance": resonances}, **options)


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
        Keyword arguments of :func:`run_grid` (``seed``, ``workers``, ...).

    Returns
    -------
    SweepResult
    """
    grid = {} if resonances is None else {"sensor.resonance": resonances}
    return run_grid(setup, {**grid, "grain.diameter": diameters}, **options)
