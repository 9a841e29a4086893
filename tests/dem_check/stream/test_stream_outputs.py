"""What a stream writes is what the toolkit reads: the trace, the campaign, the command."""

import warnings

import numpy as np
import pytest

import dem_check
from dem_check.cli import main
from dem_check.stream import DEFAULT_CASE, Flow, run_stream, score
from dem_check.stream.scoring import REACH_PERIODS, true_events

pytestmark = pytest.mark.lammps

CASE = DEFAULT_CASE.with_(duration=6e-3, noise=0.005, flow=Flow(rate=500.0, arrivals="regular"))
"""Three particles 2 ms apart (no pile-up), white noise so that a noise floor exists."""


@pytest.fixture(scope="module")
def result():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the chaff's density is below grains' range
        return run_stream(CASE)


def test_trace_reads_back_and_the_campaign_finds_every_impact(result, tmp_path):
    trace = result.trace()
    assert trace.sample_interval == pytest.approx(1e-6, rel=1e-12)  # the case's 1 MHz
    result.write(tmp_path, trace)
    back = dem_check.read_trace(tmp_path / "trace.csv")
    # shortest round-trip floats: the same doubles come back
    assert np.array_equal(back.values, trace.values) and np.array_equal(back.t, trace.t)
    campaign = dem_check.run_campaign([tmp_path / "trace.csv"], result.case.sensor)
    # three particles; re-contacts long after their impact would be signals of their own
    events = true_events(result.truth, REACH_PERIODS * result.case.sensor.period)
    assert (result.truth["contact"] == 0).sum() == 3
    assert campaign.summary()["impacts"] == len(events)
    scored = score(result, trace=trace)
    assert scored.counts["hits"] == len(events) and scored.counts["false_alarms"] == 0
    # the onsets within two sensor periods (the matching tolerance; 25 us at 40 kHz)
    assert np.abs(scored.matches["onset_error [s]"]).max() < 2 * result.case.sensor.period


def test_trace_samples_the_step_series(result):
    trace = result.trace(sample_rate=250e3, noise=0.0)
    steps = result.steps
    # point samples of S1, linear between steps: exact at a step's own time
    k = len(steps) // 2
    t_k = steps["t [s]"].iloc[k]
    assert np.interp(t_k, trace.t, trace.values) == pytest.approx(
        steps["sensor_force [N]"].iloc[k], abs=np.abs(np.diff(trace.values)).max()
    )


def test_command_writes_the_report(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(
        "[stream]\nduration = 3e-3\nnoise = 0.005\n[flow]\nrate = 1000.0\n"
        "arrivals = 'regular'\n[[particles]]\nspecies = 'wheat'\n"
        "contact = {law = 'hertz_damped', from_material = true, restitution = 0.5}\n",
        encoding="utf-8",
    )
    out = tmp_path / "out"
    assert main(["stream", str(case), "--out", str(out), "--no-progress"]) == 0
    for name in ("report.html", "trace.csv", "truth.csv", "signal.png", "summary.json"):
        assert (out / name).is_file(), name
    page = (out / "report.html").read_text(encoding="utf-8")
    # self-contained: inline figures, nothing fetched, no script
    assert "<svg" in page and "<script" not in page
    assert 'src="http' not in page and "<link" not in page


def test_laboratory_effects_reach_the_trace(result):
    from dem_check.campaign import Effects

    clean = result.trace(noise=0.0)
    hum = result.trace(noise=0.0, effects=Effects(hum=0.05, mains=50.0, harmonics=()))
    extra = np.asarray(hum.values) - np.asarray(clean.values)
    t = np.asarray(hum.t)
    basis = np.column_stack([np.sin(2 * np.pi * 50.0 * t), np.cos(2 * np.pi * 50.0 * t)])
    (a, b), *_ = np.linalg.lstsq(basis, extra, rcond=None)
    # what was added is exactly a 50 Hz sine of amplitude 0.05 N (rounding only)
    assert np.hypot(a, b) == pytest.approx(0.05, rel=1e-9)
    assert np.abs(basis @ [a, b] - extra).max() < 1e-12


def test_the_cases_effects_are_the_traces_default(result):
    import copy

    from dem_check.campaign import Effects

    effects = Effects(pink=0.01, drift=0.05, hum=0.02, full_scale=30.0, bits=12)
    realistic = copy.copy(result)
    realistic.case = result.case.with_(effects=effects)
    default, given = realistic.trace(), result.trace(effects=effects)
    # the same effects from the same seed: the same samples
    assert np.array_equal(default.values, given.values)
    # a 12-bit ADC of +-30 N: every sample on its grid of 60 / 2**12 N (rounding only)
    lsb = 60.0 / 2**12
    assert (
        np.abs(np.asarray(default.values) / lsb - np.round(np.asarray(default.values) / lsb)).max()
        < 1e-6
    )
