"""The crosstalk switches of the single-trace paths: ``crosstalk=`` on ``compare_trace`` and
``compare_laws``, ``--no-crosstalk`` on ``contactlab reconstruct``/``fit`` and ``dem-check
compare`` (issue 22).

One record of the hard grain at 2 m/s, 1 ms into 4 ms at 2 MHz, white noise 1 % of the
peak and the plate's modes ringing at 2 % of it (seed 3 of
``test_realistic_single_trace.py``, where the removal's accuracy is asserted). With the
removal on, the modes are named and the post-contact residual is noise; off, the ringing
is left in the signal and flagged ``not free ringing`` with its ratio to the noise.
"""

import json
from pathlib import Path

import numpy as np
import pytest

from contactlab.cli import main as contactlab_main
from contactlab.compare import compare_trace
from contactlab.config import load_config
from contactlab.inverse import compare_laws
from dem_check import write_trace
from dem_check.campaign import Effects, realistic_record
from dem_check.cli import main as dem_check_main

ROOT = Path(__file__).resolve().parents[3]
MODEL = ROOT / "data" / "traces" / "model_hard.toml"
REMOVED = "structural crosstalk removed"


@pytest.fixture(scope="module")
def crosstalk_record():
    config = load_config(MODEL)
    from contactlab.laws import LinearViscoelastic

    law = LinearViscoelastic(stiffness=4e4, damping=0.5)
    record = realistic_record(
        config.grain,
        config.sensor,
        law,
        [2.0],
        [1e-3],
        length=4e-3,
        sample_rate=2e6,
        noise=0.03,
        effects=Effects(crosstalk=0.02),
        seed=3,
    )
    return record, law


@pytest.fixture(scope="module")
def files(crosstalk_record, tmp_path_factory):
    """The record as a CSV in newtons and the hard grain's set-up with its law as TOML."""
    folder = tmp_path_factory.mktemp("crosstalk")
    trace = folder / "impact.csv"
    write_trace(trace, crosstalk_record[0].trace, format="generic")
    model = folder / "model.toml"
    text = MODEL.read_text(encoding="utf-8")
    model.write_text(text.replace("stiffness = 1e5", "stiffness = 4e4").replace(
        "damping = 1.0 ", "damping = 0.5 "))  # fmt: skip
    return trace, model


def _run(main, argv, capsys):
    code = main(argv)
    out = capsys.readouterr().out
    return code, json.loads(out)


def test_reconstruct_command_removes_or_keeps_the_crosstalk(files, crosstalk_record, capsys):
    trace, model = files
    argv = ["reconstruct", str(trace), "--sensor-config", str(model), "--json"]
    _, on = _run(contactlab_main, argv, capsys)
    _, off = _run(contactlab_main, [*argv, "--no-crosstalk"], capsys)
    truth = crosstalk_record[0].truth.iloc[0]["contact_time [s]"]
    assert any(note.startswith(REMOVED) for note in on["notes"]), on["notes"]
    assert "not free ringing" not in on["status"]
    assert not any(note.startswith(REMOVED) for note in off["notes"])
    assert "not free ringing" in off["status"]
    # kept, the ringing holds the reconstructed force up: the contact time is longer
    # than with the removal (+4.4 % against +0.7 % measured through the command, after
    # main's merge; reconstruct_force on the record in memory gave +12 % to +25 %)
    duration = on["metrics"]["duration [s]"]
    assert abs(duration / truth - 1.0) < 0.05  # the 5 % target
    assert off["metrics"]["duration [s]"] > duration


def test_fit_command_removes_or_keeps_the_crosstalk(files, capsys):
    trace, model = files
    argv = ["fit", str(trace), "--law", "linear", "--model", str(model), "--velocity", "2",
            "--json"]  # fmt: skip
    _, on = _run(contactlab_main, argv, capsys)
    _, off = _run(contactlab_main, [*argv, "--no-crosstalk"], capsys)
    assert any(note.startswith(REMOVED) for note in on["baseline_notes"])
    assert "not free ringing" not in on["baseline_status"]
    assert "not free ringing" in off["baseline_status"]
    assert not any(note.startswith(REMOVED) for note in off["baseline_notes"])


def test_compare_command_removes_or_keeps_the_crosstalk(files, capsys):
    trace, model = files
    argv = ["compare", str(trace), "--model", str(model), "--json"]
    _, on = _run(dem_check_main, argv, capsys)
    _, off = _run(dem_check_main, [*argv, "--no-crosstalk"], capsys)
    notes_on = [v for k, v in on["notes"].items() if k.startswith("baseline note")]
    notes_off = [v for k, v in off["notes"].items() if k.startswith("baseline note")]
    assert any(note.startswith(REMOVED) for note in notes_on), on["notes"]
    assert "not free ringing" not in on["notes"]["baseline status"]
    assert off["notes"]["baseline status"] == "not free ringing"
    assert not any(note.startswith(REMOVED) for note in notes_off)


def test_compare_trace_and_compare_laws_take_the_switch(crosstalk_record):
    record, law = crosstalk_record
    config = load_config(MODEL)
    from dataclasses import replace

    config = replace(config, law=law)
    on = compare_trace(record.trace, config)
    off = compare_trace(record.trace, config, crosstalk=False)
    assert "not free ringing" not in on.notes["baseline status"]
    assert off.notes["baseline status"] == "not free ringing"
    t, y = np.asarray(record.trace.t), np.asarray(record.trace.values)
    laws_off = compare_laws(t, y, config.grain, config.sensor, ["linear"], 2.0, crosstalk=False)
    laws_on = compare_laws(t, y, config.grain, config.sensor, ["linear"], 2.0)
    assert laws_off.best.baseline_status == "not free ringing"
    assert "not free ringing" not in laws_on.best.baseline_status
