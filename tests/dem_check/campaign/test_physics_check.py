"""A campaign flags impacts its grain cannot produce: the issue's sensitivity slip."""

import numpy as np
import pytest

import contactlab as cl
from dem_check import write_trace
from dem_check.campaign import run_campaign, synthetic_record

SENSITIVITY = 0.01124
"""The synthetic record's sensitivity [V/N] (11.24 mV/N, as data/traces)."""


@pytest.fixture(scope="module")
def volt_record(tmp_path_factory, hard_setup):
    grain, sensor, law = hard_setup
    folder = tmp_path_factory.mktemp("physics")
    onsets = 1e-3 + 3e-3 * np.arange(4)
    trace, _ = synthetic_record(
        grain,
        sensor,
        law,
        [1.6, 2.0, 2.2, 2.4],
        onsets,
        length=onsets[-1] + 2.5e-3,
        sample_rate=2e6,
        noise=0.03,
        sensitivity=SENSITIVITY,
        seed=3,
    )
    path = folder / "day.csv"
    write_trace(path, trace, "generic")
    return path


def test_the_right_sensitivity_leaves_every_impact_ok(volt_record, hard_setup):
    grain, sensor, _ = hard_setup
    result = run_campaign([volt_record], sensor, grain, sensitivity=SENSITIVITY, progress=False)
    assert list(result.impacts["status"]) == ["ok"] * 4


def test_a_sensitivity_a_thousand_times_too_large_flags_every_impact(volt_record, hard_setup):
    grain, sensor, _ = hard_setup
    with pytest.warns(cl.PlausibilityWarning, match=r"did you mean 0\.01124 V/N"):
        result = run_campaign(
            [volt_record], sensor, grain, sensitivity=SENSITIVITY * 1000, progress=False
        )
    impacts = result.impacts
    assert list(impacts["status"]) == ["implausible"] * 4
    assert impacts["reason"].str.contains("velocity change").all()
    assert result.summary()["impacts_ok"] == 0


def test_without_a_grain_nothing_is_judged(volt_record, hard_setup):
    _, sensor, _ = hard_setup
    with pytest.warns(cl.PlausibilityWarning):
        result = run_campaign(
            [volt_record], sensor, None, sensitivity=SENSITIVITY * 1000, progress=False
        )
    assert list(result.impacts["status"]) == ["ok"] * 4
