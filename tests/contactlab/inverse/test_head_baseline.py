"""The baseline under a pulse at a record's first sample
(:func:`contactlab.inverse.local_baseline.head_baseline`, used by
:func:`contactlab.inverse.pulse.pulse_baseline`): the campaign's head level, a line or a
quadratic fitted with the sensor's free ringing after the contact, extrapolated back."""

import functools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import ParameterError, ResolutionWarning
from contactlab.inverse import synthetic_trace
from contactlab.inverse.local_baseline import head_baseline
from contactlab.inverse.pulse import pulse_baseline

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
GRAIN = cl.Grain(diameter=5e-3, density=765.0)
LAW = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
LENGTH = 2.5e-3
"""Record length [s]: the pulse, its ringing and the 1.6 ms (64 sensor periods) fitted."""
RATE = 2e6
"""Sample rate [Hz]: 50 samples per sensor period."""


@functools.cache
def _pulse():
    """The noise-free impact at the record's first sample: time [s], signal [N], and the
    contact's end [s]."""
    t, signal, truth = synthetic_trace(
        GRAIN, SENSOR, LAW, 2.0, duration=LENGTH, sample_rate=RATE, pre_trigger=0.0, noise=0.0
    )
    return t, signal, float(truth.contact_time), float(truth.peak_sensor_force)


def _drift(t, slope, curvature):
    """A drift of 0.1 N at the start, ``slope`` [N/s] and ``curvature`` [N/s**2]."""
    return 0.1 + slope * t + curvature * t**2


@pytest.mark.parametrize(("slope", "curvature"), [(700.0, 0.0), (-300.0, 2e5), (0.0, -4e5)])
def test_a_polynomial_drift_under_a_noise_free_pulse_is_found_exactly(slope, curvature):
    """Without noise the sensor's free ringing after the contact is exactly the damped
    sinusoid fitted, so a line or quadratic drift is the fit's exact solution: the
    level extrapolated under the pulse is the drift itself."""
    t, signal, contact_time, peak = _pulse()
    drift = _drift(t, slope, curvature)
    base = head_baseline(t, signal + drift, 1.5 * contact_time, float(t[-1]), SENSOR)
    under = t <= base.post[0]
    # the least-squares solution to rounding: 1e-9 of the 5.6 N peak
    np.testing.assert_allclose(base.values[under], drift[under], rtol=0.0, atol=1e-9 * peak)
    # noise-free, a curvature is significant against the rounding the fit leaves
    assert base.head[2] == (2 if curvature else base.head[2])
    # the impulse (the record less the level up to the post window, plus the fitted
    # ringing's closed-form tail) is the signal's integral: the record holds 12 decay
    # times of the ringing, so its trapezoid misses 6e-6 of the tail; 1e-4 allows the
    # trapezoid's error on 50 samples a period
    assert base.impulse == pytest.approx(float(np.trapezoid(signal, t)), rel=1e-4)


@settings(max_examples=20, deadline=None)
@given(
    slope=st.floats(-2.0, 2.0),
    curvature=st.floats(-2.0, 2.0),
    seed=st.integers(0, 2**16),
)
def test_the_baseline_under_the_pulse_is_the_drift_within_a_noise_sigma(slope, curvature, seed):
    """A drift of up to 200 noise sigmas over the record (slope and curvature each up
    to 100 sigma over its 2.5 ms) and white noise of 1 % of the peak: the level under
    the pulse is the drift to within one noise sigma, and not flagged as drifting."""
    t, signal, _, peak = _pulse()
    sigma = 0.01 * peak
    drift = _drift(t, slope * 100 * sigma / LENGTH, curvature * 100 * sigma / LENGTH**2)
    noisy = signal + drift + np.random.default_rng(seed).normal(0.0, sigma, t.size)
    found = pulse_baseline(t, noisy, SENSOR, first_touch=False)
    under = t <= found.post[0]
    # the fit's extrapolation over the pulse (0.1 ms back from a 1.6 ms window of 3200
    # samples) scatters with the white noise: measured over 30 random drifts in this
    # range at most 0.125 sigma (median 0.044), over 30 lines at most 0.07; a curvature
    # under 3 of its standard errors, kept as a line, adds about as much. One sigma is
    # 8 times the largest, and half the 2 % target on the peak signal (2 sigma)
    assert np.max(np.abs(found.values[under] - drift[under])) < sigma
    assert found.status.startswith("short pre-trigger")
    # a polynomial drift is followed: the line through what the fit leaves after the
    # contact, extrapolated to the start, is the noise's (at most 0.18 sigma measured
    # over the 30 drifts), under the one-sigma flag
    assert "drifting baseline" not in found.status, found.notes


def test_the_level_is_numpy_polyfit_on_the_noise_free_drift():
    """Against an independent reference: a smooth, non-polynomial drift (a 3 Hz sine of
    2 N, as thermal wander) under a noisy pulse. ``numpy.polyfit`` of the degree the
    fit chose on the noise-free drift over the samples it fitted, extrapolated back,
    is the level an exact fit of that degree gives; the head level on the noisy record
    is that to within its scatter."""
    t, signal, _, peak = _pulse()
    sigma = 0.01 * peak
    drift = 2.0 * np.sin(2 * np.pi * 3.0 * t + 0.4)
    noisy = signal + drift + np.random.default_rng(7).normal(0.0, sigma, t.size)
    found = pulse_baseline(t, noisy, SENSOR, first_touch=False)
    first, last, degree = found.head
    fitted = (t >= first) & (t <= last)
    reference = np.polyval(np.polyfit(t[fitted], drift[fitted], degree), t)
    under = t <= found.post[0]
    # the extrapolation's scatter (above; over 10 seeds of this record at most 0.11
    # sigma, median 0.06): half a sigma is 4 times the largest
    assert np.max(np.abs(found.values[under] - reference[under])) < 0.5 * sigma
    # and the reference is the drift: a 3 Hz sine is a line over 1.6 ms to 0.0015 sigma
    # under the pulse (measured; the fit kept a line); 0.01 sigma is 6 times that
    assert np.max(np.abs(reference[under] - drift[under])) < 0.01 * sigma


def test_a_record_too_short_after_its_pulse_is_refused_with_the_reason():
    t, signal, contact_time, _ = _pulse()
    keep = t <= 1.5 * contact_time + 30 / RATE  # 30 samples after the contact
    with pytest.raises(ParameterError, match="record a pre-trigger"):
        head_baseline(t[keep], signal[keep], 1.5 * contact_time, float(t[keep][-1]), SENSOR)


def test_a_record_too_coarse_for_the_ringing_is_fitted_after_it_has_decayed():
    """At 120 kHz (3 samples a sensor period) the ringing is not fitted: the level is
    fitted from 5 decay times after the contact, where it has decayed."""
    with pytest.warns(ResolutionWarning):  # the simulation says the rate is coarse
        t, signal, truth = synthetic_trace(
            GRAIN,
            SENSOR,
            LAW,
            2.0,
            duration=10e-3,
            sample_rate=1.2e5,
            pre_trigger=0.0,
            noise=0.0,
        )
    sigma = 0.01 * truth.peak_sensor_force
    drift = _drift(t, 50.0, 0.0)
    noisy = signal + drift + np.random.default_rng(1).normal(0.0, sigma, t.size)
    found = pulse_baseline(t, noisy, SENSOR, first_touch=False)
    # 1 ms (5 decay times of 0.2 ms) after the contact's end at 0.1 ms
    assert found.head[0] == pytest.approx(1.1e-3, abs=2 / 1.2e5)
    under = t <= found.post[0]
    # measured 0.13 sigma (fitted from the contact, where the aliased ringing is not
    # zero-mean, a quadratic was 4.6 sigma off); one sigma as above
    assert np.max(np.abs(found.values[under] - drift[under])) < sigma
    assert found.status == "short pre-trigger"
