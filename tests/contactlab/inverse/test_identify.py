"""Sensor identification from free ringing, against simulated sensors of known resonance."""

import json
import math

import numpy as np
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse import identify_sensor, matrix_pencil
from contactlab.inverse.identify import DECAY_TIMES

RESONANCE = 40e3  # [Hz]
DAMPING_RATIO = 0.02  # [-]
SEEDS = range(5)


@pytest.fixture(scope="module")
def impact():
    """The paper's hard grain on the 40 kHz disc sensor: 1 ms at 2 MHz (50 samples/period)."""
    grain = cl.Grain(diameter=5e-3, density=765.0)
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, RESONANCE, damping_ratio=DAMPING_RATIO)
    law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
    return cl.simulate_impact(grain, sensor, law, 2.0, duration=1e-3, sample_rate=2e6)


@pytest.fixture(scope="module")
def identified(impact):
    """Identifications of the impact's ringing with 1 % noise (of the peak), five seeds."""
    sigma = 0.01 * impact.peak_sensor_force
    out = []
    for seed in SEEDS:
        noise = np.random.default_rng(seed).normal(0.0, sigma, impact.t.size)
        out.append(identify_sensor(impact.t, impact.sensor_force + noise))
    return out


def test_recovers_resonance_and_damping_from_impact_ringing(identified):
    for ident in identified:
        # Cramer-Rao bound at 1 % noise over ~36 periods is ~0.02 %; 0.5 % is the spec
        assert ident.resonance == pytest.approx(RESONANCE, rel=5e-3)
        # the damping's standard error is ~1 % of it; 10 % is the spec
        assert ident.damping_ratio == pytest.approx(DAMPING_RATIO, rel=0.1)


def test_standard_errors_are_honest(identified):
    z = np.array(
        [
            [
                (i.resonance - RESONANCE) / i.resonance_stderr,
                (i.damping_ratio - DAMPING_RATIO) / i.damping_ratio_stderr,
            ]
            for i in identified
        ]
    )
    # each truth within 3.5 sigma: a 1-in-2000 event per value for honest errors
    assert np.all(np.abs(z) < 3.5)
    # RMS of 10 standard normal scores lies in [0.35, 1.72] with 99.9 % probability;
    # errors too small (optimistic) or too large (pessimistic) fail here
    assert 0.35 < math.sqrt(np.mean(z**2)) < 1.72


def test_automatic_window_starts_after_the_contact(impact, identified):
    contact_end = impact.contact_intervals[-1][1]
    decay = 1.0 / (DAMPING_RATIO * 2.0 * math.pi * RESONANCE)  # 199 us
    for ident in identified:
        assert contact_end < ident.window[0] < 3 * contact_end
        # DECAY_TIMES decay times of a first fit (796 us here, the record ends 902 us
        # after the window's start): that fit's damping is within a few per cent of the
        # truth at 1 % noise, 10 % is ample
        span = min(DECAY_TIMES * decay, impact.t[-1] - ident.window[0])
        assert ident.window[1] - ident.window[0] == pytest.approx(span, rel=0.1)
        assert ident.window[1] <= impact.t[-1]


def test_matrix_pencil_is_exact_on_noiseless_exponentials():
    dt = 1e-6
    n = np.arange(300)
    poles = np.array([-2e3 + 2j * np.pi * 50e3, -5e3 + 2j * np.pi * 120e3])
    y = np.real(np.exp(np.outer(n * dt, poles)) @ np.array([1.0, 0.5j]))
    found = matrix_pencil(y, dt, 4)
    upper = np.sort_complex(found[found.imag > 0])
    # noiseless data: the pencil's eigenvalues are exact to rounding (~1e-9 relative)
    np.testing.assert_allclose(upper, np.sort_complex(poles), rtol=1e-8)


def test_tap_with_offset_and_explicit_window():
    """A hammer-tap record: offset baseline, a short pulse, then ringing; window given."""
    t = np.arange(-200, 4000) * 5e-7
    w = 2 * np.pi * 25e3
    zeta = 0.03
    wd = w * math.sqrt(1 - zeta**2)
    ring = np.where(t > 0, np.exp(-zeta * w * t) * np.sin(wd * t + 0.3), 0.0)
    y = 0.2 + 3.0 * ring + np.random.default_rng(0).normal(0.0, 0.01, t.size)
    ident = identify_sensor(t, y, window=(40e-6, t[-1]))
    # noise 0.3 % of the amplitude: errors ~1e-4; 1e-3 leaves room
    assert ident.resonance == pytest.approx(25e3, rel=1e-3)
    assert ident.damping_ratio == pytest.approx(zeta, rel=1e-2)
    assert ident.offset == pytest.approx(0.2, abs=1e-3)
    assert ident.window == (40e-6, t[-1])
    inside = t >= 40e-6
    # the fitted ringing reproduces the noiseless signal to the noise level
    np.testing.assert_allclose(ident.ringing(t[inside]), 0.2 + 3.0 * ring[inside], atol=5e-3)


def test_result_converts_and_reports(identified):
    ident = identified[0]
    sensor = ident.to_sensor(1.233e-3)
    assert isinstance(sensor, cl.Sensor)
    assert sensor.resonance == pytest.approx(ident.resonance, rel=1e-12)
    assert sensor.damping_ratio == pytest.approx(ident.damping_ratio, rel=1e-12)
    data = json.loads(json.dumps(ident.to_dict()))
    assert data["resonance [Hz]"] == ident.resonance
    assert data["window [s]"] == list(ident.window)
    assert "Hz" in repr(ident) and "damping_ratio" in repr(ident)


def test_too_few_samples_is_refused(impact):
    with pytest.raises(ParameterError, match="holds 5 samples"):
        identify_sensor(impact.t, impact.sensor_force, window=(500e-6, 502e-6))


def test_window_shorter_than_two_periods_is_refused(impact):
    with pytest.raises(ParameterError, match="ringing periods"):
        identify_sensor(impact.t, impact.sensor_force, window=(500e-6, 530e-6))


def test_noise_without_ringing_is_refused():
    t = np.arange(3000) * 1e-6
    noise = np.random.default_rng(1).normal(0.0, 1.0, t.size)
    with pytest.raises(ParameterError, match="ringing"):
        identify_sensor(t, noise, window=(0.0, t[-1]))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"window": (1e-4,)}, "window must be"),
        ({"window": 1e-4}, "window must be"),
        ({"window": (3e-4, 1e-4)}, "window end"),
        ({"window": (float("nan"), 1e-4)}, "window start"),
        ({"max_pencil_samples": 500.5}, "max_pencil_samples must be an integer"),
    ],
)
def test_bad_arguments_name_the_parameter(impact, kwargs, message):
    with pytest.raises(ParameterError, match=message):
        identify_sensor(impact.t, impact.sensor_force, **kwargs)


def test_non_uniform_time_is_refused(impact):
    t = impact.t.copy()
    t[10] += 0.3 * (t[11] - t[10])
    with pytest.raises(ParameterError, match="uniformly sampled"):
        identify_sensor(t, impact.sensor_force)
