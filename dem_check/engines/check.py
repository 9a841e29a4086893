"""An engine's drop test against the reduced model: one check, a time-step convergence
study, the paper's base case. Every engine's ``check`` module calls these with its own
``drop_test`` (:mod:`dem_check.engines.bullet.check`, :mod:`dem_check.engines.lammps.check`).
"""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from contactlab.tables import write_csv
from dem_check.engines.config import UNSET, engine_config

__all__ = ["EngineChecks", "base_case_check", "convergence_study", "engine_check"]

_NOTES = ("time_step [s]", "numerical_damping [N*s/m]", "steps", "wall_time [s]")
"""Engine metadata every check copies into its comparison's notes."""


def engine_check(drop_test, config, *, time_step=None, tolerances=None, notes=(), **options):
    """Run the impact in an engine and in the reduced model, and compare them.

    Parameters
    ----------
    drop_test : callable
        The engine's ``drop_test`` (the interface of :mod:`dem_check.engines`).
    config : contactlab.config.ImpactConfig
        The set-up, as for ``drop_test`` (no gravity: the reduced model has none); the
        reduced model runs at its velocity over the engine's window.
    time_step : float, optional
        Engine step [s]; default the engine's.
    tolerances : dict, optional
        Tolerances by quantity name (:data:`contactlab.compare.DEFAULT_TOLERANCES`).
    notes : sequence of str
        Further keys of the engine result's ``metadata`` to copy into the notes.
    **options
        The engine's own keywords.

    Returns
    -------
    contactlab.compare.Comparison
        ``a`` is the :class:`EngineResult`, ``b`` the :class:`~contactlab.ImpactResult`
        (exact solver) over the same window. Both start at the first touch, so the
        waveforms are compared without shifting (``align=None``). ``notes`` holds the time
        step, the numerical damping, the steps and their wall time, and ``notes``' keys.
    """
    from contactlab.compare import compare
    from contactlab.solver import simulate_impact

    engine = drop_test(config, time_step=time_step, **options)
    model = simulate_impact(
        config.grain, config.sensor, config.law, config.velocity, duration=float(engine.t[-1])
    )
    comparison = compare(engine, model, tolerances, align=None, labels=(engine.method, "model"))
    comparison.notes.update({key: engine.metadata[key] for key in (*_NOTES, *notes)})
    return comparison


def convergence_study(drop_test, config, time_steps, **options):
    """Errors of an engine against the reduced model as the time step shrinks.

    Parameters
    ----------
    drop_test : callable
        The engine's ``drop_test``.
    config : contactlab.config.ImpactConfig
        The set-up, as for ``drop_test``.
    time_steps : sequence of float
        Engine steps [s], at least two.
    **options
        The engine's own keywords.

    Returns
    -------
    pandas.DataFrame
        One row per step: ``time_step [s]``, ``wall_time [s]`` and the error of each
        quantity of :data:`contactlab.compare.QUANTITIES` as ``<name> error [-]`` (signed
        relative errors; restitution: signed absolute; waveforms: over the model's peak).
        ``attrs["order"]`` maps each quantity to the observed order of convergence, the
        least-squares slope of ``log |error|`` against ``log dt`` (1 for a first-order
        method).
    """
    import pandas as pd

    if time_steps is None or len(time_steps) < 2:
        raise ParameterError(f"time_steps needs at least two steps [s]; got {time_steps!r}")
    rows = []
    for dt in time_steps:
        comparison = engine_check(drop_test, config, time_step=dt, **options)
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
    return frame


def base_case_check(drop_test, name, out_dir, time_step=None, *, notes=(), **options):
    """Engine check of the paper's base case, written to a folder (``make demo``).

    The base case is the preset ``fig6`` grain and law (5 mm grain, k2 = 1e5 N/m,
    c2 = 1 N*s/m, 2 m/s) on the paper's 40 kHz disc sensor
    (``Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)``).

    Parameters
    ----------
    drop_test : callable
        The engine's ``drop_test``.
    name : str
        Engine name, the files' prefix (``"bullet"``, ``"lammps"``).
    out_dir : str or pathlib.Path
        Output folder (created).
    time_step : float, optional
        Engine step [s]; default the engine's.
    notes : sequence of str
        Further metadata keys for the notes (:func:`engine_check`).
    **options
        The engine's own keywords.

    Returns
    -------
    list of pathlib.Path
        ``<name>_base_case.png`` (overlay), ``<name>_base_case.csv`` (the comparison
        table) and ``<name>_base_case.json`` (table, verdict and engine settings).
    """
    import json

    import matplotlib.pyplot as plt

    from contactlab.config import load_preset

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    setup = replace(load_preset("fig6"), sensor=sensor)
    comparison = engine_check(drop_test, setup, time_step=time_step, notes=notes, **options)
    paths = [out / f"{name}_base_case.{ext}" for ext in ("png", "csv", "json")]
    fig, _ = comparison.plot(title=f"base case: {name} vs reduced model, 40 kHz sensor")
    fig.savefig(paths[0], dpi=150)
    plt.close(fig)
    write_csv(comparison.table, paths[1])
    paths[2].write_text(json.dumps(comparison.to_dict(), indent=2), encoding="utf-8")
    return paths


class EngineChecks:
    """The checks of one engine, bound to its ``drop_test``: what an engine's ``check``
    module hands on (:mod:`dem_check.engines.lammps.check`,
    :mod:`dem_check.engines.kratos.check`).

    Parameters
    ----------
    drop_test : callable
        The engine's ``drop_test``.
    name : str
        Engine name, the base case's file prefix.
    notes : sequence of str
        The engine's own metadata keys copied into every comparison's notes.
    """

    def __init__(self, drop_test, name, notes):
        self.drop_test, self.name, self.notes = drop_test, name, tuple(notes)

    def engine_check(self, config, *fields, time_step=UNSET, tolerances=None, **options):
        """Run the impact in the engine and in the reduced model, and compare them
        (:func:`engine_check`: ``config`` an ImpactConfig; ``options`` are the engine's
        ``drop_test`` keywords; the deprecated ``grain, sensor, law, velocity[,
        time_step]`` form warns)."""
        config, time_step = engine_config(
            config, fields, time_step, f"dem_check.{self.name}.engine_check"
        )
        return engine_check(
            self.drop_test,
            config,
            time_step=time_step,
            tolerances=tolerances,
            notes=self.notes,
            **options,
        )

    def convergence_study(self, config, *fields, time_steps=UNSET, **options):
        """Errors of the engine against the reduced model as the time step shrinks
        (:func:`convergence_study`: ``config`` an ImpactConfig, ``time_steps`` [s];
        ``attrs["order"]``: the observed orders; the deprecated ``grain, sensor, law,
        velocity, time_steps`` form warns)."""
        config, time_steps = engine_config(
            config,
            fields,
            time_steps,
            f"dem_check.{self.name}.convergence_study",
            last="time_steps",
        )
        return convergence_study(self.drop_test, config, time_steps, **options)

    def base_case_check(self, out_dir, time_step=None):
        """The engine's check of the paper's base case, written to a folder
        (:func:`base_case_check`: ``<name>_base_case.png``, ``.csv`` and ``.json``)."""
        return base_case_check(self.drop_test, self.name, out_dir, time_step, notes=self.notes)
