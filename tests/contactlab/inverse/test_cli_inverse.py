"""The inverse commands end to end: a trace file in, identification, force, fit, DEM input."""

import ast
import json

import pytest

import contactlab as cl
from contactlab.cli import main
from contactlab.inverse import synthetic_trace
from contactlab.traces import Trace, write_trace

SENSITIVITY = 0.0225  # [V/N] (22.5 mV/N)
MODEL = """
[grain]
diameter = 5.0e-3
density = 765.0
shear_modulus = 9.0e6
poisson_ratio = 0.2

[contact]
law = "linear"
stiffness = 1e5

[sensor]
diameter = 10.0e-3
thickness = 2.0e-3
resonance = 40e3
damping_ratio = 0.02

[simulation]
velocity = 2.0
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A volt trace of the paper's hard grain (1 % noise) and its model config."""
    folder = tmp_path_factory.mktemp("inverse_cli")
    grain = cl.Grain(diameter=5e-3, density=765.0)
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
    t, signal, truth = synthetic_trace(grain, sensor, law, 2.0, seed=4)
    trace = folder / "impact.csv"
    write_trace(trace, Trace(t, signal * SENSITIVITY, "V", {}), "generic")
    model = folder / "model.toml"
    model.write_text(MODEL)
    return folder, trace, model, truth


def _json(capsys):
    return json.loads(capsys.readouterr().out)


def test_identify_sensor(files, capsys):
    folder, trace, _, _ = files
    png = folder / "ident.png"
    assert main(["identify-sensor", str(trace), "--json", "--plot", str(png)]) == 0
    data = _json(capsys)
    # identification errors ~0.02 % (see test_inverse_identify): 0.5 % is the spec
    assert data["resonance [Hz]"] == pytest.approx(40e3, rel=5e-3)
    assert data["damping_ratio [-]"] == pytest.approx(0.02, rel=0.1)
    assert png.stat().st_size > 10_000


def test_reconstruct_with_resonance_and_with_config(files, capsys):
    folder, trace, model, truth = files
    png = folder / "force.png"
    common = ["reconstruct", str(trace), "--sensitivity", str(SENSITIVITY), "--json"]
    sensor = ["--sensor-mass", "1.233e-3", "--resonance", "40e3", "--damping-ratio", "0.02"]
    assert main([*common, *sensor, "--plot", str(png)]) == 0
    data = _json(capsys)
    # reconstruction errors below 4 % (see test_inverse_reconstruct): 5 % is the spec
    assert data["metrics"]["peak [N]"] == pytest.approx(truth.peak_contact_force, rel=0.05)
    assert png.stat().st_size > 10_000
    # the noise model is reported, and the white one can be asked for: this trace's
    # noise is white, so both give the same force
    assert data["parameters"]["noise_model"] == "white"
    assert main([*common, *sensor, "--noise-model", "white"]) == 0
    assert _json(capsys)["metrics"] == data["metrics"]
    # the contact's edges: where the force is significant (default) or at 2 % of the
    # peak; both within the 5 % of the contact time on this trace
    assert data["parameters"]["contact_edges"] == "significance"
    assert data["metrics"]["duration [s]"] == pytest.approx(truth.contact_time, rel=0.05)
    assert main([*common, *sensor, "--contact-edges", "level"]) == 0
    level = _json(capsys)
    assert level["parameters"]["contact_edges"] == "level"
    assert level["metrics"]["duration [s]"] == pytest.approx(truth.contact_time, rel=0.05)
    assert main([*common, "--sensor-config", str(model), "--method", "inverse"]) == 0
    data = _json(capsys)
    assert data["method"] == "inverse"
    assert data["metrics"]["duration [s]"] == pytest.approx(truth.contact_time, rel=0.05)


def test_fit_then_export(files, capsys):
    folder, trace, model, _ = files
    fit_json = folder / "FIT.json"
    args = ["fit", str(trace), "--sensitivity", str(SENSITIVITY), "--law", "linear"]
    assert main([*args, "--model", str(model), "--out", str(fit_json)]) == 0
    text = capsys.readouterr().out
    assert "fitted law: linear" in text and "fit quality: consistent" in text
    fit = json.loads(fit_json.read_text())
    # fit errors ~0.2 % at 1 % noise (see test_inverse_fit)
    assert fit["law_parameters"]["stiffness"] == pytest.approx(1e5, rel=0.01)
    snippet = folder / "scene.py"
    assert main(["export-dem", str(fit_json), "--to", "yade", "--out", str(snippet)]) == 0
    ast.parse(snippet.read_text())
    assert main(["export-dem", str(fit_json), "--to", "liggghts"]) == 0
    assert "hooke/stiffness" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            [
                *["reconstruct", "{trace}", "--sensor-mass", "1e-3"],
                *["--resonance", "4e4", "--damping-ratio", "0.02"],
            ],
            "in V, not N",
        ),
        (
            ["reconstruct", "{trace}", "--sensitivity", "0.0225", "--resonance", "4e4"],
            "--sensor-mass",
        ),
        (["reconstruct", "{trace}", "--sensitivity", "0.0225"], "--resonance F"),
        (["identify-sensor", "{folder}/missing.csv"], "missing.csv"),
        (["export-dem", "{folder}/missing.json", "--to", "edem"], "not found"),
    ],
)
def test_errors_exit_with_status_2(files, capsys, argv, message):
    folder, trace, _, _ = files
    argv = [a.format(trace=trace, folder=folder) for a in argv]
    assert main(argv) == 2
    assert message in capsys.readouterr().err
