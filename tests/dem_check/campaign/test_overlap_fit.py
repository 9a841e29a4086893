"""The joint fit of an impact's free ringing with the next impact's lobe (issue 22),
against an independent reference: two closed-form half-sine forces (the undamped linear
contact's: ``A sin(pi s / tau)`` for ``0 <= s <= tau``, impulse ``2 A tau / pi``) pushed
through the sensor's transfer function by :func:`scipy.signal.lsim` (not the fit's own
first-order-hold filter) and superposed. A second impact of another law: the undamped
Hertz contact's force ``x**1.5`` of ``x'' = -x**1.5`` (integrated here by
:func:`scipy.integrate.solve_ivp`, not the fit's :func:`force_shape`), through ``lsim``
too; and a force no family has (a rectangle).
"""

import math

import numpy as np
import pytest
from scipy import integrate, signal

from contactlab.errors import ParameterError
from contactlab.inverse.noise_prediction import ColouredNoise
from dem_check.campaign.overlap_fit import REJECT_SIGMAS, checked_joint_ringing, joint_ringing

RATE = 2e6  # [Hz]
TAU = 100e-6  # contact time [s]
FIRST, PEAK = 1e-3, 2.35  # the first touch [s] and force peak [N]


def _hertz(u):
    """The undamped Hertz contact's force over its peak at ``u`` [-] of its duration:
    ``x**1.5`` of ``x'' = -x**1.5``, ``x(0) = 0``, ``x'(0) = 1``, to ``x``'s return to 0."""

    def back(s, x):
        return x[0] if s > 1e-6 else 1.0

    back.terminal, back.direction = True, -1.0
    solved = integrate.solve_ivp(
        lambda _, x: [x[1], -(abs(x[0]) ** 1.5)],
        (0.0, 10.0),
        [0.0, 1.0],
        events=back,
        rtol=1e-11,
        atol=1e-13,
        dense_output=True,
    )
    end = float(solved.t_events[0][0])
    peak = float(solved.sol(0.5 * end)[0]) ** 1.5  # the symmetric pulse's top, mid-contact
    return np.abs(solved.sol(np.clip(u, 0.0, 1.0) * end)[0]) ** 1.5 / peak


SHAPES = {
    "linear": lambda u: np.sin(np.pi * u),
    "hertz": _hertz,
    "rectangle": lambda u: np.ones_like(u),
}
"""Unit-peak forces against the time over the contact's duration [-]."""


def _response(sensor, t, onset, peak, shape="linear"):
    """The sensor's signal [N] of a force of ``peak`` [N] and :data:`SHAPES` ``shape``
    from ``onset`` [s] (``lsim``: a linear interpolation of the force between samples, on
    a grid 10 times finer than the record's)."""
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    system = signal.lti([2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w])
    fine = np.linspace(0.0, t[-1], 10 * (t.size - 1) + 1)
    s = fine - onset
    inside = (s >= 0.0) & (s <= TAU)
    force = np.where(inside, peak * SHAPES[shape](s / TAU), 0.0)
    return np.interp(t, fine, signal.lsim(system, force, fine)[1])


def _record(sensor, gap, ratio, noise, seed, shapes=("linear", "linear")):
    """A pair's record (white noise of ``noise`` [N]), the joint fit's span and guess
    from a period after the first contact, as :mod:`dem_check.campaign.overlaps` makes
    them, the first impact's signal and the second's (noise-free) [N]."""
    t = np.arange(0.0, 2.5e-3, 1.0 / RATE)
    first = _response(sensor, t, FIRST, PEAK, shapes[0])
    second = _response(sensor, t, FIRST + gap, ratio * PEAK, shapes[1])
    y = first + second + np.random.default_rng(seed).normal(0.0, noise, t.size)
    span = (t >= FIRST + TAU + sensor.period) & (t <= FIRST + gap + TAU + 16 * sensor.period)
    # the detector's onset lags the touch (up to two periods; half of one here)
    guess = (FIRST + gap + 0.5 * sensor.period, 0.9 * TAU)
    return t[span], y[span], guess, first[span], second


def _fit(sensor, gap, ratio, noise=0.0, seed=0):
    """The joint fit on a pair's record (:func:`_record`) and the references: the first
    impact alone on the span [N], the second's force peak [N], impulse [N*s] and signal
    peak [N]."""
    t, y, guess, first, second = _record(sensor, gap, ratio, noise, seed)
    fit = joint_ringing(t, y, guess, sensor, ("linear", 0.0))
    truth = (2.0 * ratio * PEAK * TAU / math.pi, float(np.max(second)))
    return fit, t, first, ratio * PEAK, truth


def _white(sigma):
    """White noise of ``sigma`` [N] at :data:`RATE` as the record's noise model."""
    return ColouredNoise(white=sigma, pink=0.0, dt=1.0 / RATE, shape=np.ones(1))


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


MISREAD = [
    ("hertz", ("linear", 0.0), 200e-6, 0.5),
    ("hertz", ("linear", 0.0), 300e-6, 1.0),
    ("linear", ("hertz", 0.0), 200e-6, 0.5),
    ("linear", ("hertz", 0.0), 300e-6, 1.0),
]
"""A second impact of one law with the record's family the other: (its shape, the family
given, the gap [s], its force over the first's)."""


@pytest.mark.parametrize(("shape", "family", "gap", "ratio"), MISREAD)
def test_a_misread_family_is_rejected_and_refitted(hard_setup, shape, family, gap, ratio):
    """The joint fit with the wrong family is rejected by its chi-squared under the
    record's noise, refitted with every family, and the second impact's numbers are then
    the closed form's within the issue's targets; with the family right the same record's
    fit is kept."""
    sensor = hard_setup[1]
    noise = _white(0.03)  # 1 % of the first peak, as test_the_joint_fit_under_noise
    t, y, guess, _, second = _record(sensor, gap, ratio, 0.03, 1, ("linear", shape))
    checked = checked_joint_ringing(t, y, guess, sensor, family, noise)
    assert checked.rejected is not None
    assert checked.rejected.family == family
    assert checked.rejected.excess > REJECT_SIGMAS
    assert checked.accepted
    assert checked.joint.family[0] == shape
    assert checked.joint.excess <= REJECT_SIGMAS
    assert "was rejected" in checked.note() and f"the {shape} contact" in checked.note()
    u = np.linspace(0.0, 1.0, 20001)
    impulse = ratio * PEAK * TAU * np.trapezoid(SHAPES[shape](u), u)
    # the targets (peak signal 2 %, impulse, force and duration 5 %)
    assert checked.joint.peak_signal == pytest.approx(float(np.max(second)), rel=0.02)
    assert checked.joint.impulse == pytest.approx(impulse, rel=0.05)
    assert checked.joint.amplitude == pytest.approx(ratio * PEAK, rel=0.05)
    assert checked.joint.duration == pytest.approx(TAU, rel=0.05)
    right = checked_joint_ringing(t, y, guess, sensor, (shape, 0.0), noise)
    assert right.accepted and right.rejected is None


def test_a_force_no_family_has_is_not_trusted(hard_setup):
    """A rectangular second force (neither family's shape): every family's fit is
    rejected, and the result says so."""
    sensor = hard_setup[1]
    t, y, guess, _, _ = _record(sensor, 200e-6, 0.5, 0.03, 2, ("linear", "rectangle"))
    checked = checked_joint_ringing(t, y, guess, sensor, ("linear", 0.0), _white(0.03))
    assert not checked.accepted
    assert checked.joint.excess > REJECT_SIGMAS
    assert "no family agrees" in checked.note()


def test_without_a_noise_model_the_fit_is_not_checked(hard_setup):
    """No noise estimate of the record: the record's family is kept, and the note says
    the check was not made."""
    sensor = hard_setup[1]
    t, y, guess, _, _ = _record(sensor, 200e-6, 0.5, 0.03, 1, ("linear", "hertz"))
    checked = checked_joint_ringing(t, y, guess, sensor, ("linear", 0.0), None)
    assert checked.accepted and checked.joint.family == ("linear", 0.0)
    assert math.isnan(checked.joint.chi_squared)
    assert "not checked" in checked.note()
