"""The onset fit (contactlab.inverse.onset) against signals computed independently of it:
the sensor's step response in closed form, and a Hertz-like start by numerical
convolution with the sensor's impulse response (scipy.integrate.quad), not lsim."""

import math

import numpy as np
import pytest
from scipy import integrate

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse.onset import Rise, fit_onset, rise_shape

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
RATE = 2e6  # [Hz]
W, ZETA = SENSOR.angular_frequency, SENSOR.damping_ratio
A, B = ZETA * W, W * math.sqrt(1.0 - ZETA**2)  # decay rate [1/s], damped frequency [rad/s]


def _step(s):
    """The signal ``k1 x1 + c1 v1`` [N] of the sensor at rest for a unit force step at
    ``s = 0`` (closed form: the mass-spring-damper's step response and its velocity)."""
    s = np.maximum(s, 0.0)
    return np.where(s > 0.0, 1.0 - np.exp(-A * s) * (np.cos(B * s) - A / B * np.sin(B * s)), 0.0)


def _impulse(s):
    """The sensor signal's impulse response [N/(N*s)]: (c1 p + k1) / (m1 p**2 + c1 p + k1)."""
    return np.exp(-A * s) * (2.0 * A * np.cos(B * s) + (W * W - 2.0 * A * A) / B * np.sin(B * s))


def _convolved(force, s):
    """The sensor signal for ``force(u)`` from ``u = 0``, by quadrature [N]."""
    if s <= 0.0:
        return 0.0
    return integrate.quad(lambda u: _impulse(s - u) * force(u), 0.0, s, limit=200)[0]


def _times():
    return np.arange(0.0, 80e-6, 1.0 / RATE)


def _rise(values, t0, end_after=6e-6, noise=1e-3):
    """The record ``0.05 + 40 t`` [N] (an offset and a drift) plus ``values`` (the
    impact's signal on :func:`_times`), with a crossing 2 us after ``t0``."""
    t = _times()
    return Rise(t, 0.05 + 40.0 * t + values, t0 + 2e-6, t0 + end_after, noise)


def _signal(force, t0):
    """The sensor signal [N] on :func:`_times` for ``force(s)`` from the touch ``t0``."""
    return np.array([_convolved(force, x - t0) for x in _times()])


@pytest.mark.parametrize("t0", [30.0e-6, 30.37e-6, 31.81e-6])
def test_a_force_step_is_timed_to_a_hundredth_of_a_sample(t0):
    """A 1.2 N force step (a damped linear contact's start) at a sub-sample time under a
    line, no noise: the fit with q = 0 finds its start."""
    rise = _rise(1.2 * _step(_times() - t0), t0)
    fit = fit_onset(rise, SENSOR, 0.0, 0.0)
    # lsim on a sixteenth of a sample, interpolated: measured within 0.003 samples
    assert fit.onset == pytest.approx(t0, abs=0.01 / RATE)
    assert fit.chi_squared / fit.samples < 1e-2  # the model is exact: no residual


def test_a_hertz_start_is_timed_and_its_exponent_read():
    """A force ``(s / T)**1.5`` (Hertz) convolved by quadrature: the fit with q = 1.5
    finds its start, and of the shapes tried it is 1.5 that fits two such rises best."""
    period = SENSOR.period
    t0 = 30.29e-6
    hertz = _signal(lambda u: 3.0 * (u / period) ** 1.5, t0)
    rise = _rise(hertz, t0, end_after=15e-6)
    fit = fit_onset(rise, SENSOR, 1.5, 0.0)
    # quadrature against lsim's first-order hold: measured within 0.02 samples
    assert fit.onset == pytest.approx(t0, abs=0.05 / RATE)
    later = _rise(0.5 * hertz, t0, end_after=15e-6)
    assert rise_shape([rise, later], SENSOR) == (1.5, 0.0)


def test_the_shape_of_a_linear_contact_is_read_and_its_onsets_under_noise():
    """A damped linear contact's force ``v (c2 + k2 s)`` (bend k2 T / c2 = 2): without
    noise the shape read on four rises is (0, 2); under white noise of 1 % of a 3 N peak
    the shape read is another that fits as well; the onsets are within a sample of the
    touches with the true shape, within 2.5 with the shape read."""
    rng = np.random.default_rng(3)
    period = SENSOR.period
    rises, noisy, starts = [], [], []
    for k, velocity in enumerate((1.0, 1.5, 2.0, 2.5)):
        t0 = 30e-6 + 0.31e-6 * k
        # 0.5 v N stepping at the touch, rising by 2 times that per sensor period
        force = lambda u, v=velocity: 0.5 * v * (1.0 + 2.0 * u / period)  # noqa: E731
        rises.append(_rise(_signal(force, t0), t0, end_after=5e-6))
        y = rises[-1].y + rng.normal(0.0, 0.03, rises[-1].y.size)
        noisy.append(rises[-1]._replace(y=y, noise=0.03))
        starts.append(t0)
    assert rise_shape(rises, SENSOR) == (0.0, 2.0)
    shape = rise_shape(noisy, SENSOR)
    errors = [
        (fit_onset(r, SENSOR, *shape).onset - t0) * RATE
        for r, t0 in zip(noisy, starts, strict=True)
    ]
    known = [
        (fit_onset(r, SENSOR, 0.0, 2.0).onset - t0) * RATE
        for r, t0 in zip(noisy, starts, strict=True)
    ]
    # 30-80 sigma peaks at 2 MHz, the shape known: measured within 0.56 samples
    assert np.max(np.abs(known)) <= 1.0, known
    # the shape read, (0.5, 1): measured within 2.1 samples, early (a larger power from a
    # later touch and a smaller one from an earlier touch fit 1 % noise alike)
    assert np.max(np.abs(errors)) <= 2.5, (shape, errors)


def test_bad_input():
    rise = _rise(_step(_times() - 30e-6), 30e-6)
    with pytest.raises(ParameterError, match="sensor"):
        fit_onset(rise, cl.Sensor.rigid(), 0.0)
    with pytest.raises(ParameterError, match="too few samples"):
        fit_onset(rise._replace(end=rise.rough), SENSOR, 0.0)
    with pytest.raises(ParameterError, match="no impact"):
        rise_shape([rise._replace(end=rise.rough)], SENSOR)
