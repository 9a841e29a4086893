"""The inverse tools on the shipped sample traces (synthetic, truth in their sidecars)."""

import json
from pathlib import Path

import pytest

from contactlab.config import load_config
from contactlab.errors import ParameterError
from contactlab.inverse import fit_contact, identify_sensor, reconstruct_force
from dem_check import read_trace

TRACES = Path(__file__).parents[3] / "data" / "traces"
SAMPLES = sorted(p.with_suffix("").name for p in TRACES.glob("*.json"))


def load(name):
    meta = json.loads((TRACES / f"{name}.json").read_text())
    trace = read_trace(TRACES / name, sensitivity=meta["sensitivity [V/N]"])
    return trace, load_config(TRACES / meta["model"]), meta


@pytest.mark.parametrize("name", SAMPLES)
def test_reconstruction_meets_the_5_percent_target(name):
    trace, config, meta = load(name)
    truth = meta["truth"]
    raw_error = truth["peak_sensor_force [N]"] / truth["peak_contact_force [N]"] - 1.0
    assert raw_error > 0.15  # every sample is a case the raw signal gets wrong
    pulse = reconstruct_force(trace.t, trace.values, config.sensor).metrics
    # the target: peak and contact time within 5 % of the truth
    assert pulse.peak == pytest.approx(truth["peak_contact_force [N]"], rel=0.05)
    assert pulse.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)


@pytest.mark.parametrize("name", SAMPLES)
def test_identification_finds_the_sensor_or_says_there_is_no_ringing(name):
    trace, config, _ = load(name)
    try:
        found = identify_sensor(trace.t, trace.values)
    except ParameterError as exc:
        # a soft or Hertz pulse barely excites the sensor: refusing is the honest answer
        assert "no free ringing" in str(exc)
        return
    # 8- to 16-bit samples with noise over dozens of periods: 0.5 % on the frequency and
    # 10 % on the damping ratio (the damping sits in the slow decay of a short record)
    assert found.resonance == pytest.approx(config.sensor.resonance, rel=5e-3)
    assert found.damping_ratio == pytest.approx(config.sensor.damping_ratio, rel=0.1)


@pytest.mark.parametrize(
    ("name", "law", "expected"),
    [
        ("tek_tds.csv", "linear", {"stiffness": 1e5, "damping": 1.0}),
        ("rigol_seconds.csv", "linear", {"stiffness": 1e4, "damping": 0.3}),
        # E* = 3 kH / (4 sqrt(R*)) with kH = 1.5e6 N/m**1.5 and R* = 2.5 mm
        ("keysight.csv", "hertz_damped", {"effective_modulus": 22.5e6, "restitution": 0.5}),
    ],
)
def test_fit_recovers_the_generating_law(name, law, expected):
    trace, config, meta = load(name)
    fit = fit_contact(trace.t, trace.values, config.grain, config.sensor, law=law)
    parameters = fit.to_dict()["parameters"]
    for key, value in expected.items():
        # 1 % of noise on a few thousand samples: the fits land within 0.4 % (measured)
        assert parameters[key]["value"] == pytest.approx(value, rel=0.01)
        assert parameters[key]["identifiable"]
    assert parameters["velocity"]["value"] == pytest.approx(meta["velocity [m/s]"], rel=0.01)
