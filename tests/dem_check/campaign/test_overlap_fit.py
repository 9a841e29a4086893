"""The joint fit of an impact's free ringing with the next impact's lobe (issue 22),
against an independent reference: two closed-form half-sine forces (the undamped linear
contact's: ``A sin(pi s / tau)`` for ``0 <= s <= tau``, impulse ``2 A tau / pi``) pushed
through the sensor's transfer function by :func:`scipy.signal.lsim` (not the fit's own
first-order-hold filter) and superposed.
"""

import math

import numpy as np
import pytest
from scipy import signal

from contactlab.errors import ParameterError
from dem_check.campaign.overlap_fit import joint_ringing

RATE = 2e6  # [Hz]
TAU = 100e-6  # contact time [s]
FIRST, PEAK = 1e-3, 2.35  # the first touch [s] and force peak [N]


def _response(sensor, t, onset, peak):
    """The sensor's signal [N] of a half-sine force of ``peak`` [N] from ``onset`` [s]
    (``lsim``: a linear interpolation of the force between samples, on a grid 10 times
    finer than the record's)."""
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    system = signal.lti([2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w])
    fine = np.linspace(0.0, t[-1], 10 * (t.size - 1) + 1)
    s = fine - onset
    force = np.where((s >= 0.0) & (s <= TAU), peak * np.sin(np.pi * s / TAU), 0.0)
    return np.interp(t, fine, signal.lsim(system, force, fine)[1])


def _fit(sensor, gap, ratio, noise=0.0, seed=0):
    """The joint fit on a pair's record (white noise of ``noise`` [N]) from a period
    after the first contact, as :mod:`dem_check.campaign.overlaps` makes it, and the
    references: the first impact alone on those samples [N], the second's force peak
    [N], impulse [N*s] and signal peak [N]."""
    t = np.arange(0.0, 2.5e-3, 1.0 / RATE)
    first = _response(sensor, t, FIRST, PEAK)
    second = _response(sensor, t, FIRST + gap, ratio * PEAK)
    y = first + second + np.random.default_rng(seed).normal(0.0, noise, t.size)
    span = (t >= FIRST + TAU + sensor.period) & (t <= FIRST + gap + TAU + 16 * sensor.period)
    # the detector's onset lags the touch (up to two periods; half of one here)
    guess = (FIRST + gap + 0.5 * sensor.period, 0.9 * TAU)
    fit = joint_ringing(t[span], y[span], guess, sensor, ("linear", 0.0))
    truth = (2.0 * ratio * PEAK * TAU / math.pi, float(np.max(second)))
    return fit, t[span], first[span], ratio * PEAK, truth


@pytest.mark.parametrize("gap", [200e-6, 300e-6])
@pytest.mark.parametrize("ratio", [1.0, 0.5])
def test_the_joint_fit_reads_both_impacts_without_noise(hard_setup, gap, ratio):
    """Noise-free: the first impact's line and ringing are the first impact alone, and
    the second's force, duration, onset, impulse and signal peak are the closed form's."""
    sensor = hard_setup[1]
    fit, t, first, peak, (impulse, signal_peak) = _fit(sensor, gap, ratio)
    # two discretisations of one sensor (the fit's first-order hold on a grid of 1/128
    # period, lsim on a 10-times finer grid than the record's): measured 1.8e-5 to 5.9e-5
    # of the peak force; 3e-4 is 5 times the largest
    assert np.max(np.abs(fit.values(t, sensor) - first)) <= 3e-4 * PEAK
    # measured within 3.0e-5 (force, impulse), 9.1e-6 (duration), 9.8e-6 (signal peak):
    # 2e-4 is 7 times the largest
    assert fit.amplitude == pytest.approx(peak, rel=2e-4)
    assert fit.duration == pytest.approx(TAU, rel=2e-4)
    assert fit.impulse == pytest.approx(impulse, rel=2e-4)
    assert fit.peak_signal == pytest.approx(signal_peak, rel=2e-4)
    # measured 0.001 samples; a hundredth is the simplex's tolerance (a thousandth) and
    # the discretisations' difference with a margin
    assert abs(fit.onset - (FIRST + gap)) <= 0.01 / RATE
    # measured 1.1e-5 to 2.4e-5 of the peak: the model holds; 1e-4 is 4 times the largest
    assert fit.rms <= 1e-4 * PEAK


def test_the_joint_fit_under_noise(hard_setup):
    """White noise of 1 % of the first peak, the second impact at half the velocity 0.2
    ms after the first (the case the ringing fitted between them alone missed by 8 %):
    the second's numbers within the issue's targets, on 4 seeds."""
    sensor = hard_setup[1]
    for seed in range(4):
        fit, t, first, peak, (impulse, signal_peak) = _fit(sensor, 200e-6, 0.5, 0.03, seed)
        # the targets (peak signal 2 %, impulse and contact 5 %); measured within
        # 0.54 % (peak signal), 0.47 % (impulse), 0.52 % (force), 0.33 % (duration)
        assert fit.peak_signal == pytest.approx(signal_peak, rel=0.02)
        assert fit.impulse == pytest.approx(impulse, rel=0.05)
        assert fit.amplitude == pytest.approx(peak, rel=0.05)
        assert fit.duration == pytest.approx(TAU, rel=0.05)
        # the rms residual is the noise's (0.03 N) where the model holds (measured -2.4
        # to +2.5 %): 10 % is about four of its standard errors on ~900 samples
        assert fit.rms == pytest.approx(0.03, rel=0.1)
        # the first impact's line and ringing: measured within 0.08-0.26 noise sigmas per
        # sample (the two amplitudes and the line read on ~900 samples); one sigma bounds it
        assert np.max(np.abs(fit.values(t, sensor) - first)) <= 0.03


def test_the_joint_fit_refuses_what_it_cannot_read(hard_setup):
    """No samples before the second touch, or a record that does not resolve the
    ringing: a ParameterError that says so, not a fit."""
    sensor = hard_setup[1]
    t = np.arange(0.0, 1e-3, 1.0 / RATE)
    with pytest.raises(ParameterError, match="no ringing to fit"):
        joint_ringing(t, np.zeros(t.size), (t[0] + 0.5e-6, TAU), sensor, ("linear", 0.0))
    coarse = np.arange(0.0, 1e-3, sensor.period / 3.0)
    with pytest.raises(ParameterError, match="not resolved"):
        joint_ringing(coarse, np.zeros(coarse.size), (5e-4, TAU), sensor, ("linear", 0.0))
