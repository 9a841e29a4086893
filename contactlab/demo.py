"""``make demo``: the paper's base case and its impact figures, written to a results folder."""

import json

import numpy as np

from contactlab.bodies import Sensor
from contactlab.config import list_presets, load_preset
from contactlab.impact import simulate_impact

__all__ = ["run_demo"]


def _jsonable(obj):
    if isinstance(obj, dict):
        return {k: _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def run_demo(out):
    """Simulate the paper's base case on a rigid wall and on its sensor, and Figures 5-9.

    Parameters
    ----------
    out : pathlib.Path
        Output folder (created).

    Returns
    -------
    list of pathlib.Path
        Files written: ``base_case.png``, ``summary.json`` and ``fig5.png`` ... ``fig9.png``.
    """
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    written = []
    # base case: the paper's grain, hard contact k2 = 1e5 N/m, c2 = 1 N*s/m, v0 = 2 m/s
    base = load_preset("fig6")
    sim = dict(base.simulation)
    wall = simulate_impact(base.grain, Sensor.rigid(), base.law, **sim)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained", sharey=True)
    wall.plot(ax=axes[0], title="immovable wall (S1 = S2)")
    summary = {"base_case_rigid_wall": wall.summary()}
    for sensor_hz in (40e3,):
        sensor = Sensor.from_disc(10e-3, 2e-3, sensor_hz, damping_ratio=0.02)
        res = simulate_impact(base.grain, sensor, base.law, **sim)
        res.plot(ax=axes[1], title=f"sensor {sensor_hz / 1e3:g} kHz")
        summary["base_case_40kHz_sensor"] = res.summary()
    path = out / "base_case.png"
    fig.savefig(path, dpi=150)
    plt.close(fig)
    written.append(path)
    for name in list_presets():
        res = load_preset(name).simulate()
        fig, _ = res.plot(
            title=f"{name}: {type(res.law).__name__}, {res.sensor.resonance / 1e3:g} kHz"
        )
        path = out / f"{name}.png"
        fig.savefig(path, dpi=150)
        plt.close(fig)
        written.append(path)
        summary[name] = res.summary()
    path = out / "summary.json"
    path.write_text(json.dumps(_jsonable(summary), indent=2))
    written.append(path)
    return written
