"""A campaign over data/traces: ten instrument layouts, one impact each, plus the files
beside them (sidecars, models, the generator, the README) that are not records."""

import json
from pathlib import Path

import pytest

from contactlab.config import load_config
from dem_check import run_campaign

TRACES = Path(__file__).resolve().parents[3] / "data" / "traces"
SENSITIVITY = 0.01124  # [V/N], data/traces/README.md


@pytest.fixture(scope="module")
def samples():
    setup = load_config(TRACES / "model_hard.toml")  # every sample shares its 40 kHz sensor
    return run_campaign(TRACES, setup.sensor, setup.grain, sensitivity=SENSITIVITY, gallery=0)


def test_every_sample_record_is_analysed_and_the_rest_listed(samples):
    files = samples.files.set_index("file")
    records = {str(p) for p in TRACES.iterdir() if (TRACES / f"{p.name}.json").exists()}
    assert len(records) == 10
    assert (files.loc[sorted(records), "status"] == "ok").all()
    assert (files.loc[sorted(records), "impacts_ok"] == 1).all()
    others = files.drop(index=sorted(records))
    assert len(others) == len(list(TRACES.iterdir())) - 10  # nothing skipped silently
    folders = {str(p) for p in TRACES.iterdir() if p.is_dir()}  # real/: listed, not entered
    assert folders and (others.loc[sorted(folders), "status"] == "sub-folder").all()
    # sidecars, models, the generator and the README are not records (issue 23): skipped
    assert (others.drop(index=sorted(folders))["status"] == "skipped").all()


def test_sample_impacts_against_their_truth(samples):
    for _, row in samples.impacts.iterrows():
        truth = json.loads(Path(row["file"] + ".json").read_text(encoding="utf-8"))["truth"]
        # the targets, on 8-16 bit quantised records with 0.2-0.6 mV noise
        assert abs(row["onset [s]"] - truth["onset_time [s]"]) < 10e-6
        assert row["peak_sensor_force [N]"] == pytest.approx(
            truth["peak_sensor_force [N]"], rel=0.02
        )
        assert row["peak_contact_force [N]"] == pytest.approx(
            truth["peak_contact_force [N]"], rel=0.05
        )
        assert row["contact_time [s]"] == pytest.approx(truth["contact_time [s]"], rel=0.05)
