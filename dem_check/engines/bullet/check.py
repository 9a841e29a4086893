"""The pybullet drop bench against the reduced model: one check, a convergence study, the
paper's base case."""

import math
from pathlib import Path

import numpy as np

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from dem_check.engines.bullet.drop import drop_test

__all__ = ["base_case_check", "convergence_study", "engine_check"]


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
