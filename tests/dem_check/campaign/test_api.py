"""run_campaign's arguments, the per-file options, the fit, and ``dem-check campaign``."""

import pandas as pd
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from dem_check import run_campaign, write_trace
from dem_check.campaign import synthetic_record
from dem_check.cli import main

SENSITIVITY = 0.01124  # [V/N]


@pytest.fixture(scope="module")
def small_day(tmp_path_factory, hard_setup):
    """Two volt records of two impacts each (1 MHz), in one folder, with their truth."""
    grain, sensor, law = hard_setup
    folder = tmp_path_factory.mktemp("small-day")
    truth = {}
    for seed, name in enumerate(("run1.csv", "run2.csv")):
        trace, table = synthetic_record(
            grain,
            sensor,
            law,
            [1.8, 2.2],
            [1e-3, 3.5e-3],
            length=6e-3,
            sample_rate=1e6,
            noise=0.03,
            sensitivity=SENSITIVITY,
            seed=seed,
        )
        write_trace(folder / name, trace, "generic")
        truth[name] = table
    return folder, truth


def test_bad_arguments_name_the_parameter(small_day, hard_setup):
    folder, _ = small_day
    grain, sensor, _ = hard_setup
    with pytest.raises(ParameterError, match=r"sensor must be a contactlab\.Sensor"):
        run_campaign(folder, grain)
    with pytest.raises(ParameterError, match="rigid"):
        run_campaign(folder, cl.Sensor.rigid())
    with pytest.raises(ParameterError, match="needs the grain"):
        run_campaign(folder, sensor, fit="linear")
    with pytest.raises(ParameterError, match="fit"):
        run_campaign(folder, sensor, grain, fit="no-such-law")
    with pytest.raises(ParameterError, match=r"sensitivity\['run1.csv'\]"):
        run_campaign(folder, sensor, sensitivity={"run1.csv": -1.0})
    with pytest.raises(ParameterError, match="channel"):
        run_campaign(folder, sensor, channel=1.5)
    with pytest.raises(ParameterError, match="gallery"):
        run_campaign(folder, sensor, gallery=-1)
    with pytest.raises(TypeError):
        run_campaign(folder, sensor, sensitivty=SENSITIVITY)  # a misspelt keyword


def test_per_file_sensitivity_and_globs(small_day, hard_setup):
    folder, truth = small_day
    grain, sensor, _ = hard_setup
    result = run_campaign(
        str(folder / "run*.csv"), sensor, grain, sensitivity={"run2.csv": SENSITIVITY}, gallery=0
    )
    files = result.files.set_index("file")
    assert files.loc[str(folder / "run1.csv"), "status"] == "no sensitivity"
    assert files.loc[str(folder / "run2.csv"), "impacts_ok"] == 2
    # the reconstruction through the whole chain: the 5 %
    rows = result.ok.reset_index(drop=True)
    error = rows["peak_contact_force [N]"] / truth["run2.csv"]["peak_contact_force [N]"] - 1
    assert error.abs().max() < 0.05
    assert result.settings["sensitivity [V/N]"] == {"run2.csv": SENSITIVITY}


def test_fit_gives_parameters_with_intervals(small_day, hard_setup):
    folder, truth = small_day
    grain, sensor, law = hard_setup
    result = run_campaign(
        folder / "run1.csv", sensor, grain, sensitivity=SENSITIVITY, fit="linear", gallery=0
    )
    rows = result.impacts
    assert (rows["status"] == "ok").all() and (rows["reason"] == "").all()
    for name, unit, true in (
        ("stiffness", "N/m", law.stiffness),
        ("damping", "N*s/m", law.damping),
    ):
        value = rows[f"fit_{name} [{unit}]"]
        # the generating law through the exact model: 0.1-0.4 % off at 1 % noise
        assert ((value / true - 1).abs() < 0.02).all(), value.tolist()
        # honest intervals (about +-0.5 %) hold the truth
        assert (rows[f"fit_{name}_low [{unit}]"] < true).all()
        assert (true < rows[f"fit_{name}_high [{unit}]"]).all()
        assert rows[f"fit_{name}_identifiable"].all()
    velocity = rows["fit_velocity [m/s]"] / truth["run1.csv"]["velocity [m/s]"] - 1
    assert velocity.abs().max() < 0.01  # measured 0.13 %
    stats = result.statistics
    assert "fit_stiffness [N/m]" in set(stats["quantity"])


def test_command_line_writes_the_report(small_day, tmp_path, capsys):
    folder, _ = small_day
    out = tmp_path / "out"
    config = "data/traces/model_hard.toml"
    code = main(
        [
            "campaign",
            str(folder / "run1.csv"),
            "--model",
            config,
            "--sensitivity",
            str(SENSITIVITY),
            "--out",
            str(out),
            "--json",
        ]
    )
    captured = capsys.readouterr()
    assert code == 0  # every file and impact analysed
    assert '"impacts_ok": 2' in captured.out
    assert "campaign: 100%" in captured.err  # the progress bar
    assert "report.html" in captured.err
    assert len(pd.read_csv(out / "impacts.csv")) == 2
    assert (out / "report.html").read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


def test_command_line_exit_codes(small_day, tmp_path, capsys):
    folder, _ = small_day
    sensor = ["--resonance", "40e3", "--damping-ratio", "0.02", "--sensor-mass", "1.233e-3"]
    # without --sensitivity both volt records are listed "no sensitivity": exit code 1
    code = main(["campaign", str(folder), *sensor, "--no-progress", "--gallery", "0"])
    assert code == 1
    assert main(["campaign", str(folder), "--resonance", "40e3", "--no-progress"]) == 2
    assert "give the sensor" in capsys.readouterr().err
    assert main(["campaign", str(tmp_path / "none"), *sensor]) == 2
    assert "no such file or folder" in capsys.readouterr().err


def test_a_campaign_without_any_analysable_impact_still_reports(tmp_path, hard_setup):
    import numpy as np

    from dem_check import Trace

    grain, sensor, _ = hard_setup
    uneven = np.cumsum(np.random.default_rng(0).uniform(1.0, 2.0, 5000)) * 1e-7
    noise = np.random.default_rng(1).normal(0.0, 0.03, 5000)
    write_trace(tmp_path / "uneven.csv", Trace(uneven, noise, "N"), "generic")
    result = run_campaign(tmp_path / "uneven.csv", sensor, grain, out=tmp_path / "out")
    (row,) = result.files.to_dict("records")
    assert row["status"] == "not analysable" and "uniform" in row["reason"]
    assert len(result.impacts) == 0 and len(result.statistics) == 0
    page = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert 'id="impact-count">0<' in page and "uneven.csv" in page


def test_an_offset_step_is_a_row_of_the_impacts_table(tmp_path, hard_setup):
    from dem_check.campaign import Effects, realistic_record

    effects = Effects(offsets=((3.0e-3, 0.6),))  # 20 noise sigmas, 1 ms before the hit
    sampling = {"length": 8e-3, "sample_rate": 1e6, "noise": 0.03, "seed": 3}
    record = realistic_record(*hard_setup, [2.0], [4e-3], **sampling, effects=effects)
    write_trace(tmp_path / "stepped.csv", record.trace, "generic")
    result = run_campaign(tmp_path / "stepped.csv", hard_setup[1], hard_setup[0], gallery=0)
    assert result.impacts["status"].tolist() == ["ok", "offset step"]
    step = result.impacts.iloc[1]
    # placed on the samples: within 2 us (two samples at 1 MHz) of the true step
    assert step["onset [s]"] == pytest.approx(3.0e-3, abs=2e-6)
    # its height in the reason: medians of 16 period means of noise 0.03/5 N each side
    height = float(step["reason"].split("changed by ")[1].split(" N")[0])
    assert height == pytest.approx(0.6, abs=0.01) and "stayed" in step["reason"]
    (row,) = result.files.to_dict("records")
    assert row["impacts"] == 1 and row["impacts_ok"] == 1  # a step is no impact
