"""Coloured noise: the autoregressive model, its whitening, and the reconstruction by
generalised least squares against a closed-form pulse through a known sensor."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy import signal as sg

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse import reconstruct_force
from contactlab.inverse.noise_colour import ARNoise, fit_ar_noise, ringing_residual, whiten_problem

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)


def _ar(coefficients, count, seed, burn=2000):
    """``count`` samples of the AR process of unit innovations, past its start-up."""
    w = np.random.default_rng(seed).normal(size=count + burn)
    return sg.lfilter([1.0], [1.0, *(-np.asarray(coefficients))], w)[burn:], w[burn:]


def test_burg_recovers_a_known_ar_process():
    x, _ = _ar([1.5, -0.56], 4000, seed=1)  # poles 0.8 and 0.7
    model = fit_ar_noise(x)
    assert model.order == 2
    # asymptotic standard error sqrt((1 - a2**2) / n) = 0.013: 0.05 is about 4 of them
    np.testing.assert_allclose(model.coefficients, [1.5, -0.56], atol=0.05)
    # the innovation's standard deviation is known to 1 / sqrt(2 n) = 1.1 %: 4 of them
    assert model.innovation == pytest.approx(1.0, rel=0.045)


def test_white_noise_is_called_white():
    rng = np.random.default_rng(5)
    orders = [fit_ar_noise(rng.normal(size=100)).order for _ in range(40)]
    # the 1 % likelihood-ratio test bounds the false models at about 1 %: 0.4 expected in
    # 40 windows, 3 or more has a probability of 8e-4
    assert sum(order > 0 for order in orders) <= 2, orders


@given(
    a1=st.floats(-0.9, 0.9),
    a2=st.floats(-0.5, 0.4),
    seed=st.integers(0, 2**16),
)
def test_whitening_with_the_true_coefficients_returns_the_innovations(a1, a2, seed):
    x, w = _ar([a1, a2], 300, seed, burn=0)
    model = ARNoise(coefficients=np.array([a1, a2]), innovation=1.0, samples=300)
    # A(z) is the exact inverse of the recursion: rounding only
    np.testing.assert_allclose(model.whiten(x), w[2:], rtol=0, atol=1e-12 * np.abs(x).max())


def test_whitening_a_problem_starts_on_the_samples_before_it():
    rng = np.random.default_rng(2)
    model = ARNoise(coefficients=np.array([0.6]), innovation=1.0, samples=100)
    h, data = rng.normal(size=(10, 3)), rng.normal(size=10)
    before = rng.normal(size=8)  # four blocks of two
    hw, dw, noise = whiten_problem(model, h, data, before, 2, 0.7)
    # one block before the window starts the filter: every row of the problem is kept,
    # the matrix's first row unchanged (the model is zero before the window)
    assert hw.shape == h.shape and noise == 1.0
    np.testing.assert_allclose(hw[0], h[0])
    np.testing.assert_allclose(dw[0], data[0] - 0.6 * before[-2:].mean())
    np.testing.assert_allclose(dw[1:], data[1:] - 0.6 * data[:-1])
    # without samples before it the first row is dropped
    assert whiten_problem(model, h, data, before[:1], 2, 0.7)[0].shape == (9, 3)
    # the white model leaves the problem and the block noise as they are
    assert whiten_problem(None, h, data, before, 2, 0.7)[2] == 0.7


def test_the_ringing_residual_is_the_noise():
    dt = 5e-7
    t = np.arange(2000) * dt
    w, zeta = SENSOR.angular_frequency, SENSOR.damping_ratio
    a, b = zeta * w, w * np.sqrt(1.0 - zeta**2)
    noise = np.random.default_rng(4).normal(0.0, 0.01, t.size)
    y = 0.5 + 40.0 * t + np.exp(-a * t) * (0.8 * np.cos(b * t) - 0.3 * np.sin(b * t)) + noise
    residual = ringing_residual(t, y, (0.0, t[-1]), SENSOR)
    # the ringing (closed form, the sensor's poles) and the line are fitted exactly: what
    # is left is the noise less its projection on four columns, whose norm is about
    # sqrt(4 / 2000) = 4.5 % of the noise's; 13 % is three of those
    assert np.linalg.norm(residual - noise) < 0.13 * np.linalg.norm(noise)


@pytest.mark.parametrize(
    ("noise", "message"),
    [
        (np.ones(5), "at least 20"),
        (np.r_[np.ones(30), np.nan], "not finite"),
        (np.ones(40), "constant"),
    ],
)
def test_bad_noise_is_refused(noise, message):
    with pytest.raises(ParameterError, match=message):
        fit_ar_noise(noise)


# ---------------------------------------------------------------------------
# Independent check: a half-sine force through the sensor, solved by scipy, with noise
# from a known AR(1) process
# ---------------------------------------------------------------------------
RATE, CONTACT, PEAK = 2e6, 100e-6, 3.0


@pytest.fixture(scope="module")
def half_sine_signal():
    """The sensor's response to ``PEAK sin(pi t / CONTACT)`` on ``[0, CONTACT]``: scipy's
    ``lsim`` on a grid ten times finer (the input linear between its samples, an error of
    (pi dt / CONTACT)**2 / 8 = 1e-5 of the peak), 1 ms before the touch and 2 ms after."""
    dt = 1.0 / RATE
    t = np.arange(-1e-3, 2e-3, dt)
    fine = np.linspace(t[0], t[-1], 10 * (t.size - 1) + 1)
    force = np.where((fine >= 0.0) & (fine <= CONTACT), PEAK * np.sin(np.pi * fine / CONTACT), 0.0)
    w, zeta = SENSOR.angular_frequency, SENSOR.damping_ratio
    system = sg.lti([2.0 * zeta * w, w**2], [1.0, 2.0 * zeta * w, w**2])
    _, response, _ = sg.lsim(system, force, fine - fine[0])
    return t, response[::10]


def _errors(t, clean, seed, noise_model):
    x, _ = _ar([0.9], t.size, seed)
    y = clean + 0.05 * x / x.std()  # 1.7 % of the peak, correlated over ~10 samples
    m = reconstruct_force(t, y, SENSOR, noise_model=noise_model).metrics
    return (
        m.peak / PEAK - 1.0,
        m.duration / CONTACT - 1.0,
        m.impulse / (2 * PEAK * CONTACT / np.pi) - 1.0,
    )


def test_generalised_least_squares_beats_the_white_model_under_ar_noise(half_sine_signal):
    t, clean = half_sine_signal
    gls = np.array([_errors(t, clean, seed, "ar") for seed in range(6)])
    ols = np.array([_errors(t, clean, seed, "white") for seed in range(6)])
    # measured over seeds 0-5: peak within 1.3 % (white model: up to 7.3 %), contact
    # time within 3.7 %, impulse within 1.3 %: the 5 % targets are asserted
    assert np.abs(gls[:, 0]).max() < 0.05, gls
    assert np.abs(gls[:, 1]).max() < 0.05, gls
    assert np.abs(gls[:, 2]).max() < 0.05, gls
    # the white model's GCV fits the correlated noise as force: its mean peak error was
    # 5.8 times the whitened one's (4.3 % against 0.75 %); at least twice is asserted
    assert np.abs(ols[:, 0]).mean() > 2.0 * np.abs(gls[:, 0]).mean(), (gls, ols)


def test_on_white_noise_the_model_stays_white(half_sine_signal):
    t, clean = half_sine_signal
    y = clean + np.random.default_rng(0).normal(0.0, 0.03, t.size)
    ar = reconstruct_force(t, y, SENSOR)
    white = reconstruct_force(t, y, SENSOR, noise_model="white")
    assert ar.parameters["noise_model"] == "white"
    # the same estimator, so the same force (the same operations in the same order)
    np.testing.assert_array_equal(ar.force, white.force)


class _TwoMinima:
    """A problem whose GCV score over log10(lambda) in [-4, 2] has a rough minimum at -2
    (depth 1) and a smooth one at 0 (depth ``smooth``), with 100 effective parameters
    for 200 data (so one standard error of the score is sqrt(2 / 100) = 14 %)."""

    y = np.zeros(200)

    def __init__(self, smooth, smoothest):
        self.smooth, self.smoothest = smooth, smoothest

    def bracket(self):
        return -4.0, 2.0

    def dof(self, lam):
        return 100.0

    def residual2(self, lam):
        x = np.log10(lam)
        score = min(1.0 + (x + 2.0) ** 2, self.smooth + 4.0 * x**2)
        return score * 100.0**2


@pytest.mark.parametrize(
    ("smooth", "smoothest", "expected"),
    [(1.02, True, 0.0), (1.02, False, -2.0), (1.3, True, -2.0), (0.98, False, 0.0)],
)
def test_gcv_takes_the_smoothest_minimum_within_one_standard_error(smooth, smoothest, expected):
    from contactlab.inverse.regularization import CRITERIA

    lam = CRITERIA["gcv"](_TwoMinima(smooth, smoothest), None)
    # the bounded refinement finds the parabola's vertex to its tolerance, ~1e-5 in x
    assert np.log10(lam) == pytest.approx(expected, abs=1e-3)
