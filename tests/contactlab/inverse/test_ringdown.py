"""Ringing after a contact (contactlab.inverse.ringdown) against damped sinusoids built
here in closed form."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from projection_reference import LoopProjection

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse.noise_colour import ringing_residual
from contactlab.inverse.ringdown import _Projection, free_ringing_residual, refine_poles

SENSOR = cl.Sensor.from_resonance(40e3, 0.01, damping_ratio=0.02)


def _pole(frequency, zeta):
    b = 2.0 * math.pi * frequency
    return complex(-zeta * b / math.sqrt(1.0 - zeta**2), b)


def _windows(poles, rng, rate=30e3, lengths=(1.3e-3, 2.3e-3, 3.8e-3, 1.9e-3), noise=0.0):
    """Windows of the modes ``poles`` at random amplitudes and phases, an offset and a
    line each, and white noise."""
    windows = []
    for length in lengths:
        tau = np.arange(round(length * rate)) / rate
        y = rng.uniform(-1.0, 1.0) + rng.uniform(-50.0, 50.0) * tau
        for pole in poles:
            phase = rng.uniform(0.0, 2.0 * math.pi)
            y += rng.uniform(0.5, 1.0) * np.exp(pole.real * tau) * np.cos(pole.imag * tau + phase)
        windows.append((tau, y + rng.normal(0.0, noise, tau.size)))
    return windows


def test_refine_poles_takes_a_biased_start_to_the_modes():
    # noise-free windows of two modes, each with its own amplitudes, offset and line:
    # started 15 % off in frequency and at three times the damping, the projection's
    # minimum is the modes themselves
    rng = np.random.default_rng(1)
    truth = [_pole(730.0, 0.01), _pole(1890.0, 0.02)]
    start = [_pole(840.0, 0.03), _pole(1700.0, 0.005)]
    refined = refine_poles(_windows(truth, rng), start)
    # 1e-6: the minimiser's tolerance (the model is exact; measured 4e-12)
    np.testing.assert_allclose(refined, truth, rtol=1e-6)


def test_refine_poles_keeps_the_damping_within_its_bounds():
    rng = np.random.default_rng(2)
    truth = [_pole(730.0, 0.01)]
    refined = refine_poles(_windows(truth, rng), [_pole(760.0, 0.02)], damping=(0.02, 0.05))
    zeta = -refined[0].real / abs(refined[0])
    # the truth's 0.01 is below the bound: the damping ratio stays on it (to rounding),
    # the frequency still moves to within 1 % of the mode's (the bound's decay error
    # over 1-3 periods)
    assert zeta == pytest.approx(0.02, abs=1e-9)
    assert refined[0].imag == pytest.approx(truth[0].imag, rel=0.01)


def test_refine_poles_under_white_noise_beats_the_start_and_returns_short_windows():
    rng = np.random.default_rng(3)
    truth = [_pole(730.0, 0.01)]
    windows = _windows(truth, rng, noise=0.1)
    refined = refine_poles(windows, [_pole(800.0, 0.01)])
    # 0.5 %: 0.12 % here; over 37 seeds the error's standard deviation was 0.19 %
    # (amplitudes 0.5-1 at noise 0.1 on 280 samples, 6.8 periods in all)
    assert refined[0].imag == pytest.approx(truth[0].imag, rel=0.005)
    few = [(tau[:4], y[:4]) for tau, y in windows]  # no more samples than amplitudes
    np.testing.assert_array_equal(refine_poles(few, [_pole(800.0, 0.01)]), [_pole(800.0, 0.01)])


def test_refine_poles_refuses_a_pole_that_does_not_oscillate():
    windows = _windows([_pole(730.0, 0.01)], np.random.default_rng(4))
    with pytest.raises(ParameterError, match="poles"):
        refine_poles(windows, [complex(-100.0, 0.0)])
    with pytest.raises(ParameterError, match="factor"):
        refine_poles(windows, [_pole(730.0, 0.01)], factor=1.0)


@pytest.mark.parametrize("degree", [0, 1, 2])
def test_free_ringing_residual_takes_out_the_ringing_and_the_polynomial(degree):
    rate = 2e6
    t = 3e-3 + np.arange(2000) / rate
    s = t - t[0]
    w = SENSOR.angular_frequency
    a, b = SENSOR.damping_ratio * w, w * math.sqrt(1 - SENSOR.damping_ratio**2)
    ringing = 2.0 * np.exp(-a * (s + 1e-4)) * np.sin(b * (s + 1e-4) + 0.4)
    polynomial = np.polynomial.polynomial.polyval(s, [0.3, 40.0, 9e3][: degree + 1])
    # the closed form is in the model's span: nothing is left (rounding of a 2 N ringing)
    assert np.max(np.abs(free_ringing_residual(t, ringing + polynomial, SENSOR, degree))) < 1e-9
    # a slower sine is not in it: most of it is left
    slow = 0.05 * np.sin(2 * math.pi * 1890.0 * s)
    rest = free_ringing_residual(t, ringing + polynomial + slow, SENSOR, degree)
    # 1890 Hz over 1 ms (1.9 periods): a polynomial of degree <= 2 takes at most a
    # third of its energy
    assert float(rest @ rest) > 0.66 * float(slow @ slow)
    if degree == 1:  # the noise floor of a record that starts at its pulse is the same
        same = ringing_residual(t, ringing + polynomial + slow, (t[0], t[-1]), SENSOR)
        np.testing.assert_allclose(same, rest, atol=1e-12)  # one function: rounding only


@settings(max_examples=40, deadline=None)
@given(
    lengths=st.lists(st.integers(8, 200), min_size=1, max_size=12),
    frequencies=st.lists(st.floats(300.0, 5e3), min_size=1, max_size=4),
    seed=st.integers(0, 2**32 - 1),
)
def test_stacked_windows_give_the_loops_projection(lengths, frequencies, seed):
    """The stacked, padded windows (``ringdown._Projection``) against the loop over the
    windows it replaced (``tests/support/projection_reference.py``): the same residual
    sum of squares and normal equations (rows come in another order, which least
    squares does not see), over window counts, lengths and poles."""
    rng = np.random.default_rng(seed)
    rate = 20e3
    windows = []
    for size in lengths:  # refine_poles uses windows of more samples than columns
        tau = np.arange(size + 2 + 2 * len(frequencies)) / rate
        y = rng.normal(size=tau.size) + np.cos(2 * np.pi * frequencies[0] * tau)
        windows.append((tau - tau.mean(), y))
    scale = 2 * np.pi * np.asarray(frequencies)
    x = np.ravel([(rng.uniform(1e-4, 0.06), rng.uniform(0.8, 1.25)) for _ in frequencies])
    stacked, loop = _Projection(windows, scale), LoopProjection(windows, scale)
    r, j = stacked.residual(x), stacked.jacobian(x)
    r0, j0 = loop.residual(x), loop.jacobian(x)
    assert r.shape == r0.shape and j.shape == j0.shape
    # QR and sums taken on other shapes: rounding of the data's scale (1e-16 a term,
    # 2 400 terms at most, a margin of 40)
    scale_r = float(r0 @ r0) + 1.0
    assert abs(float(r @ r) - float(r0 @ r0)) <= 1e-10 * scale_r
    normal = np.abs(j0).T @ np.abs(j0) + 1.0
    assert np.all(np.abs(j.T @ j - j0.T @ j0) <= 1e-9 * normal)
    gradient = np.abs(j0).T @ np.abs(r0) + 1.0
    assert np.all(np.abs(j.T @ r - j0.T @ r0) <= 1e-9 * gradient)


def test_stacked_windows_with_a_repeated_pole_solve_as_lstsq_does():
    """Two equal poles make every window's design rank-deficient: the triangular solve
    is skipped and each window's amplitudes are numpy.linalg.lstsq's (the minimum-norm
    ones), as in the loop."""
    rng = np.random.default_rng(3)
    windows = []
    for size in (40, 44, 150):
        tau = np.arange(size) / 20e3
        windows.append((tau - tau.mean(), rng.normal(size=size)))
    scale = 2 * np.pi * np.array([1e3, 1e3])
    x = np.array([0.01, 1.0, 0.01, 1.0])
    stacked, loop = _Projection(windows, scale), LoopProjection(windows, scale)
    r, r0 = stacked.residual(x), loop.residual(x)
    # the same projection, another order of operations and rows: rounding of |y|**2
    assert abs(float(r @ r) - float(r0 @ r0)) <= 1e-10 * float(r0 @ r0)
