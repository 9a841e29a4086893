"""Force reconstruction against simulated truth: the paper's hard grain on a 40 kHz sensor."""

import json

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse import reconstruct_force, reconstruction_demo, synthetic_trace
from contactlab.inverse.reconstruct import _toeplitz
from contactlab.inverse.regularization import CRITERIA, StandardForm

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)


@pytest.fixture(scope="module")
def hard_case():
    """Preset fig6's grain and law (k = 1e5 N/m, c = 1 N*s/m, 2 m/s) on the 40 kHz disc."""
    from contactlab.config import load_preset

    case = load_preset("fig6")
    return case.grain, case.law, case.simulation["velocity"]


def test_the_raw_signal_is_badly_wrong(hard_case):
    grain, law, velocity = hard_case
    truth = cl.simulate_impact(grain, SENSOR, law, velocity, duration=400e-6, sample_rate=5e6)
    # the hard case of the brief: the raw peak is off by more than half (measured +54 %)
    assert truth.peak_sensor_force / truth.peak_contact_force - 1.0 > 0.5


@pytest.mark.parametrize("method", ["tikhonov", "inverse"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_reconstruction_recovers_peak_and_contact_time(hard_case, method, seed):
    grain, law, velocity = hard_case
    t, signal, truth = synthetic_trace(grain, SENSOR, law, velocity, noise=0.01, seed=seed)
    m = reconstruct_force(t, signal, SENSOR, method).metrics
    # measured over 8 seeds: peak within 3.9 %, contact time within 3.5 %: 5 % is the spec
    assert m.peak == pytest.approx(truth.peak_contact_force, rel=0.05)
    assert m.duration == pytest.approx(truth.contact_time, rel=0.05)
    # the impulse is the best-determined moment of the force (measured within 0.7 %)
    assert m.impulse == pytest.approx(truth.impulse, rel=0.02)


def test_forward_model_is_exact_for_a_piecewise_linear_force():
    """The Toeplitz columns are the sensor's exact response to hat functions: a trapezoid
    with corners on the force grid is reproduced to rounding."""
    grain = cl.Grain(diameter=5e-3, density=765.0)
    dt, q = 1e-7, 4  # trapezoid corners at multiples of q*dt = 0.4 us
    law = cl.laws.PlasticTrapezoid(contact_time=60e-6, ramp_time=8e-6)
    truth = cl.simulate_impact(grain, SENSOR, law, 2.0, duration=100e-6, sample_rate=1 / dt)
    knots = np.arange(0, 251) * q * dt
    force = law.force_at(knots, grain.mass, 2.0)
    rows = 240
    h = _toeplitz(SENSOR, dt, q, rows, knots.size)
    blocks = truth.sensor_force[: rows * q].reshape(rows, q).mean(axis=1)
    # exact discretisation: only rounding of the matrix powers (~1e-12 of the peak)
    np.testing.assert_allclose(h @ force, blocks, atol=1e-9 * truth.peak_sensor_force)


def test_discrepancy_principle_matches_the_residual_to_the_noise():
    rng = np.random.default_rng(3)
    h = np.tril(rng.uniform(0.5, 1.0, (60, 40)))
    y = h @ np.sin(np.linspace(0, 3, 40)) + rng.normal(0.0, 0.05, 60)
    problem = StandardForm(h, y)
    lam = CRITERIA["discrepancy"](problem, 0.05)
    # the root is found to 1e-3 in log10(lambda); the residual follows to ~1e-3
    assert problem.residual2(lam) == pytest.approx(60 * 0.05**2, rel=5e-3)


def test_gcv_and_discrepancy_both_run_on_a_trace(hard_case):
    grain, law, velocity = hard_case
    t, signal, _ = synthetic_trace(grain, SENSOR, law, velocity, seed=0)
    for criterion in CRITERIA:
        rec = reconstruct_force(t, signal, SENSOR, regularization=criterion)
        assert rec.parameters["regularization"] == criterion
        assert rec.parameters["lambda"] > 0.0
        # the force is non-negative everywhere and zero outside the window
        assert rec.force.min() >= 0.0
        ta, tb = rec.parameters["window [s]"]
        # the hats of the first and last force values reach one grid step beyond the window
        step = rec.parameters["grid_step [s]"]
        outside = (rec.t < ta - step) | (rec.t > tb + step)
        assert np.all(rec.force[outside] == 0.0)


def test_result_outputs(hard_case, tmp_path):
    grain, law, velocity = hard_case
    t, signal, truth = synthetic_trace(grain, SENSOR, law, velocity, seed=1)
    rec = reconstruct_force(t, signal, SENSOR, "inverse", cutoff=100e3)
    assert rec.parameters["cutoff [Hz]"] == 100e3
    frame = rec.to_frame()
    assert list(frame.columns) == ["t [s]", "sensor_force [N]", "contact_force [N]"]
    assert len(frame) == t.size
    summary = json.loads(json.dumps(rec.summary()))
    assert summary["method"] == "inverse"
    assert summary["metrics"]["peak [N]"] == rec.metrics.peak
    _, ax = rec.plot(truth=truth)
    assert len(ax.lines) == 4  # truth, signal, reconstruction, zero line
    assert "inverse" in repr(rec)


def test_demo_figure_is_written(tmp_path):
    path = tmp_path / "reconstruction.png"
    errors = reconstruction_demo(path)
    assert path.stat().st_size > 10_000
    # the figure's own numbers: raw peak +54 %, reconstructions within 5 %
    assert errors["raw_peak [-]"] > 0.5
    assert abs(errors["tikhonov_peak [-]"]) < 0.05
    assert abs(errors["inverse_contact_time [-]"]) < 0.05


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"sensor": cl.Sensor.rigid()}, "rigid"),
        ({"sensor": "40 kHz"}, "contactlab.Sensor"),
        ({"method": "tikhonow"}, "Did you mean 'tikhonov'"),
        ({"regularization": "lcurve"}, "regularization must be one of"),
        ({"method": "inverse", "cutoff": 3e6}, "cutoff"),
        ({"cutoff": 1e5}, "cutoff applies to method='inverse'"),
        ({"method": "inverse", "regularization": "gcv"}, "regularization applies"),
        ({"noise_model": "pink"}, "noise_model must be one of"),
        ({"method": "inverse", "noise_model": "ar"}, "noise_model applies"),
        ({"window": (1e-5,)}, "window must be"),
        ({"window": 1e-5}, "window must be"),
        ({"window": (-1.0, 1e-4)}, "window start must lie within the record"),
        ({"baseline_window": (0.0, 1e-6)}, "need at least 16"),
        ({"baseline_window": -1e-4}, "baseline_window must be"),
        ({"max_unknowns": 100.5}, "max_unknowns must be an integer"),
        ({"method": "inverse", "max_unknowns": 100}, "max_unknowns applies"),
        ({"threshold": -1.0}, "threshold must be"),
    ],
)
def test_bad_input_names_the_parameter(hard_case, kwargs, message):
    grain, law, velocity = hard_case
    t, signal, _ = synthetic_trace(grain, SENSOR, law, velocity, seed=0)
    args = {"sensor": SENSOR, **kwargs}
    with pytest.raises(ParameterError, match=message):
        reconstruct_force(t, signal, **args)


def test_synthetic_trace_seed_is_checked(hard_case):
    grain, law, velocity = hard_case
    with pytest.raises(ParameterError, match="seed must be an integer"):
        synthetic_trace(grain, SENSOR, law, velocity, seed=1.5)


def test_the_automatic_window_starts_within_a_short_pre_trigger(hard_case):
    grain, law, velocity = hard_case
    # 20 baseline samples (4 us) are fewer than the quarter period (6.25 us) the window
    # would start before the onset: it starts at the record's first sample instead
    t, signal, truth = synthetic_trace(grain, SENSOR, law, velocity, pre_trigger=4e-6)
    rec = reconstruct_force(t, signal, SENSOR)
    assert rec.parameters["window [s]"][0] == t[0]
    # the contact starts 4 us after the record: still within the 5 % of the main tests
    assert rec.metrics.peak == pytest.approx(truth.peak_contact_force, rel=0.05)


def test_a_trace_without_pre_trigger_reads_its_baseline_after_the_pulse(hard_case):
    grain, law, velocity = hard_case
    t, signal, truth = synthetic_trace(grain, SENSOR, law, velocity, pre_trigger=0.0)
    rec = reconstruct_force(t, signal + 0.2, SENSOR)  # a DC offset the baseline must remove
    start, _ = rec.parameters["baseline_window [s]"]
    assert start > truth.contact_time  # the quietest stretch lies after the contact
    # the contact starts at the record's first sample: the 5 % of the main tests hold
    assert rec.metrics.peak == pytest.approx(truth.peak_contact_force, rel=0.05)
    assert rec.metrics.duration == pytest.approx(truth.contact_time, rel=0.05)


def test_a_trace_too_short_for_a_quiet_stretch_is_refused(hard_case):
    grain, law, velocity = hard_case
    t, signal, _ = synthetic_trace(grain, SENSOR, law, velocity, pre_trigger=0.0)
    with pytest.raises(ParameterError, match="pre-trigger"):
        reconstruct_force(t[:20], signal[:20], SENSOR)
