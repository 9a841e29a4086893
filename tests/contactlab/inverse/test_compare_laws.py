"""Ranking contact laws by BIC: the true law is found across grains, sensors and laws."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.cli import main
from contactlab.errors import ParameterError
from contactlab.inverse import compare_laws, fit_contact, synthetic_trace
from contactlab.inverse.fit_models import FIT_MODELS

GRAIN = cl.Grain(diameter=5e-3, density=765.0)
SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
HARD = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
TRACES = Path(__file__).resolve().parents[3] / "data" / "traces"


@settings(
    max_examples=5,
    deadline=None,
    derandomize=True,
    phases=(Phase.explicit, Phase.generate),  # no shrinking: each example is 4 fits
    suppress_health_check=[HealthCheck.too_slow],
)
@given(
    law=st.sampled_from(tuple(FIT_MODELS)),
    diameter=st.floats(2e-3, 8e-3),  # [m] seeds and grains of 2-8 mm
    density=st.floats(600.0, 1400.0),  # [kg/m^3]
    resonance=st.floats(20e3, 100e3),  # [Hz] quartz force sensors
    contact_time=st.floats(60e-6, 250e-6),  # [s] hard to soft grains
    restitution=st.floats(0.3, 0.9),  # [-]
    velocity=st.floats(1.0, 4.0),  # [m/s]
    seed=st.integers(0, 1000),
)
def test_bic_picks_the_true_law_across_grains_and_sensors(
    law, diameter, density, resonance, contact_time, restitution, velocity, seed
):
    grain = cl.Grain(diameter=diameter, density=density)
    sensor = cl.Sensor.from_resonance(resonance, mass=1.233e-3, damping_ratio=0.02)
    spec = FIT_MODELS[law]
    truth = spec.build(spec.guess(grain, velocity, contact_time, restitution), grain)
    t, y, _ = synthetic_trace(
        grain,
        sensor,
        truth,
        velocity,
        duration=max(400e-6, 3.0 * contact_time),
        sample_rate=2e6,
        # the noise window must end an onset-to-peak time (up to ~0.6 contact times)
        # before the pulse: a pre-trigger of one contact time leaves >= 40 % of it
        pre_trigger=max(100e-6, contact_time),
        seed=seed,
    )
    result = compare_laws(t, y, grain, sensor)
    assert result.best.law_name == law, result.summary()
    assert result.best.quality.consistent, result.summary()
    names = [r.fit.law_name for r in result.ranking]
    assert sorted(names) == sorted(FIT_MODELS)
    # the ranking is by BIC; chi2 differences of the rejected laws are in the thousands
    assert [r.bic for r in result.ranking] == sorted(r.bic for r in result.ranking)
    for r in result.ranking[1:]:
        nested = {law, r.fit.law_name} == {"hertz", "hertz_damped"}
        # hertz is hertz_damped at e = 1: with a hertz truth the extra parameter buys
        # nothing and costs ln n (supported, delta BIC ~ ln n). A wrong law is rejected by
        # its own tests, or at least disfavoured (delta BIC > 10): a slow sensor can make
        # a wrong law's misfit too small for the absolute tests (measured: linear truth,
        # 20 kHz sensor, 60 us contact: hertz_damped reduced chi2 1.13, delta BIC 67)
        allowed = {"supported"} if nested and law == "hertz" else {"rejected", "disfavoured"}
        assert r.verdict in allowed, result.summary()


def test_a_short_noise_window_does_not_bias_the_velocity():
    """Found by a seeded sweep like the one above: undamped Hertz, 3.3 mm grain at
    3.84 m/s on an 84 kHz sensor, 57 noise samples. Without a fitted baseline offset the
    noise window's mean (known to sigma / sqrt(57) = 0.13 sigma) was wrong by that much
    over the whole record, which moved the impulse and the velocity 0.5 % (3.861 m/s,
    interval 3.854-3.868, for a true 3.8405) and left correlated residuals (Ljung-Box
    p = 0.002); with a 1 ms pre-trigger the bias vanished."""
    grain = cl.Grain(diameter=3.2565e-3, density=1299.7)
    sensor = cl.Sensor.from_resonance(83.797e3, mass=1.233e-3, damping_ratio=0.02)
    law = cl.laws.Hertz(cl.analytic.hertz_stiffness(10.181e6, grain.radius))
    t, y, _ = synthetic_trace(grain, sensor, law, 3.8405, duration=525e-6, sample_rate=2e6, seed=5)
    fit = fit_contact(t, y, grain, sensor, "hertz")
    assert fit.quality.noise_samples < 100
    assert fit.quality.consistent
    low, high = fit.parameters["velocity"].ci95
    assert low < 3.8405 < high
    offset = fit.baseline_offset
    # the fitted offset is of the size the noise window's mean can be off (a few sigma/sqrt(m))
    assert abs(offset.value) < 4.0 * fit.goodness["noise [N]"] / np.sqrt(57)
    assert offset.ci95[0] < offset.value < offset.ci95[1] and offset.unit == "N"


def test_comparison_from_the_command_line(tmp_path, capsys):
    """`contactlab fit --law auto` on tek_tds.csv (the paper's linear law, 8-bit): best
    linear, every other law rejected, the best fit written for export-dem."""
    out = tmp_path / "FIT.json"
    argv = [
        "fit",
        str(TRACES / "tek_tds.csv"),
        "--law",
        "auto",
        "--model",
        str(TRACES / "model_hard.toml"),
        "--sensitivity",
        "0.01124",
    ]
    assert main([*argv, "--out", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(c))
    assert data["best"] == "linear" and data["best_consistent"] is True
    assert sorted(data["rejected"]) == ["hertz", "hertz_damped", "walton_braun"]
    first = data["laws"][0]
    assert first["law"] == "linear"
    assert first["delta_bic [-]"] == 0.0 and first["verdict"] == "best"
    n, p = data["samples"], first["fitted_quantities"]
    chi2 = first["reduced_chi_squared [-]"] * first["fit"]["quality"]["degrees_of_freedom"]
    # BIC as documented, to rounding
    assert first["bic [-]"] == pytest.approx(chi2 + p * math.log(n), rel=1e-12)
    assert json.loads(out.read_text())["law"] == "linear"


def test_text_output_names_the_rejected_laws_and_both_rebounds(capsys):
    argv = [
        "fit",
        str(TRACES / "tek_tds.csv"),
        "--law",
        "linear",
        "--model",
        str(TRACES / "model_hard.toml"),
        "--sensitivity",
        "0.01124",
    ]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "fit quality: consistent" in text
    # k = 1e5 N/m, c = 1 N*s/m on 50 mg: 0.540 with a force-zero end, 0.516 at zero
    # overlap (analytic.linear_restitution), printed as fitted
    assert "rebound on a rigid wall: 0.54" in text and "zero overlap" in text


def test_no_consistent_law_is_said():
    t, y, _ = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, sample_rate=1e6, seed=0)
    result = compare_laws(t, y, GRAIN, SENSOR, laws=["hertz", "walton_braun"])
    assert sorted(result.rejected) == ["hertz", "walton_braun"]
    assert "no candidate law is consistent" in result.summary()
    assert result.to_dict()["best_consistent"] is False


@pytest.mark.parametrize(
    ("laws", "message"),
    [
        ([], "at least one"),
        (["linear", "hertz_dampd"], "Did you mean 'hertz_damped'"),
        ("lineer", "Did you mean 'linear'"),
    ],
)
def test_bad_laws_are_named(laws, message):
    t, y, _ = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, sample_rate=1e6, seed=0)
    with pytest.raises(ParameterError, match=message):
        compare_laws(t, y, GRAIN, SENSOR, laws=laws)
