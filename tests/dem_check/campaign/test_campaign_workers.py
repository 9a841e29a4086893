"""``run_campaign(workers=...)``: a record's impacts read on forked processes give the
rows and gallery traces of the one-process reading, to the last bit; a bad count is
refused by name; an error inside a worker reaches the file's row as on one process."""

import numpy as np
import pandas as pd
import pytest

from contactlab.errors import ParameterError
from dem_check import run_campaign, write_trace
from dem_check.campaign import Effects, realistic_record
from dem_check.campaign import analysis as analysis_module

NOISE = 0.03  # [N]


@pytest.fixture(scope="module")
def busy_record(tmp_path_factory, hard_setup):
    """One realistic record (every effect on, 2 MHz) of five impacts and their bounces."""
    grain, sensor, law = hard_setup
    record = realistic_record(
        grain,
        sensor,
        law,
        [1.2, 2.0, 1.6, 2.4, 1.8],
        [2e-3, 8e-3, 14e-3, 20e-3, 26e-3],
        length=32e-3,
        sample_rate=2e6,
        noise=NOISE,
        effects=Effects.everything(NOISE, 3.0),
        seed=5,
    )
    path = tmp_path_factory.mktemp("workers") / "day.h5"
    write_trace(path, record.trace, "hdf5", name="day/sensor", time="attrs")
    return path


def test_two_workers_give_the_one_process_rows(busy_record, hard_setup):
    grain, sensor, _ = hard_setup
    one = run_campaign(busy_record, sensor, grain)
    two = run_campaign(busy_record, sensor, grain, workers=2)
    assert (one.impacts["status"] == "ok").sum() >= 5  # impacts to share between them
    pd.testing.assert_frame_equal(one.impacts, two.impacts, check_exact=True)
    assert one.gallery.keys() == two.gallery.keys()
    for key, traces in one.gallery.items():
        other = two.gallery[key]
        for name in ("t", "signal", "force"):
            assert np.array_equal(getattr(traces, name), getattr(other, name))


def test_an_error_in_a_worker_fails_the_file_as_on_one_process(
    busy_record, hard_setup, monkeypatch
):
    grain, sensor, _ = hard_setup

    def broken(*args, **kwargs):
        raise RuntimeError("a broken impact")

    monkeypatch.setattr("dem_check.campaign.workers.analyse_impact", broken)
    for workers in (1, 2):  # forked workers see the patched function too
        files = run_campaign(busy_record, sensor, grain, workers=workers).files
        assert files["status"].tolist() == ["failed"]
        assert "RuntimeError: a broken impact" in files["reason"].iloc[0]
    assert analysis_module.analyse_impact is not broken


@pytest.mark.parametrize("workers", [0, -1, 1.5, True, "2"])
def test_a_bad_worker_count_is_refused_by_name(busy_record, hard_setup, workers):
    grain, sensor, _ = hard_setup
    with pytest.raises(ParameterError, match="workers"):
        run_campaign(busy_record, sensor, grain, workers=workers)
