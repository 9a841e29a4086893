"""The crosstalk's share of a linear reading and its propagated error
(``contactlab.inverse.crosstalk.Crosstalk.share``), against signals built here from
closed forms (a half-sine pulse and its direct convolution with damped sinusoids) and
against a Monte Carlo over noise seeds; and the removal rule of
``dem_check.campaign.structure.removed_from_impulse``."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from plate_windows import SENSOR, damped
from scipy import linalg, signal

from contactlab.inverse.crosstalk import fit_crosstalk
from contactlab.inverse.least_squares_covariance import toeplitz_quadratic
from contactlab.inverse.local_baseline import local_baseline
from contactlab.inverse.noise_prediction import ColouredNoise
from dem_check.campaign.structure import removed_from_impulse

RATE = 1e6
DT = 1.0 / RATE
T = np.arange(round(6e-3 * RATE)) * DT
ONSET, DURATION = 2e-3, 1e-4
CONTACT_END = ONSET + 2 * DURATION
MODES = [(730.0, 0.01), (1890.0, 0.02), (4100.0, 0.015)]
WEIGHTS = (150.0, 200.0, 300.0)
PULSE = np.where(
    (T >= ONSET) & (T < ONSET + DURATION), 3.0 * np.sin(math.pi * (T - ONSET) / DURATION), 0.0
)
CROSSTALK = sum(
    w * np.convolve(PULSE, damped(T, f, z))[: T.size] * DT
    for (f, z), w in zip(MODES, WEIGHTS, strict=True)
)
FITTED = (T < ONSET - 5e-6) | (T > CONTACT_END + SENSOR.period)
INSIDE = (T >= ONSET) & (T <= CONTACT_END)
DRAWS = 60
"""Noise seeds of the Monte Carlo (the suite's time: each fit takes about 0.1 s)."""


def _fit(noise, autocovariance=None, modes=MODES, exact_force=False):
    """The crosstalk fitted on the record (``exact_force``: with no crosstalk inside the
    pulse, so that the force the method reads there is the pulse itself)."""
    pulse = (T >= ONSET) & (T < CONTACT_END)
    crosstalk = np.where(pulse, 0.0, CROSSTALK) if exact_force else CROSSTALK
    y = PULSE + crosstalk + 0.1 + noise
    return fit_crosstalk(
        T,
        y,
        SENSOR,
        ONSET,
        pulse,
        FITTED,
        CONTACT_END,
        modes,
        drop=False,
        autocovariance=autocovariance,
    )


def _integral(values):
    """A linear reading with a closed meaning: the integral over the pulse [N*s]."""
    return float(np.trapezoid(np.where(INSIDE, values, 0.0), dx=DT))


def _ar1(count, phi, sigma, rng):
    """AR(1) noise of stationary standard deviation ``sigma``, started from its
    stationary distribution (autocovariance ``sigma**2 phi**k``)."""
    innovations = rng.normal(0.0, sigma * math.sqrt(1.0 - phi**2), count)
    start = rng.normal(0.0, sigma)
    return signal.lfilter([1.0], [1.0, -phi], innovations, zi=[phi * start])[0]


def test_the_share_of_the_pulse_integral_matches_the_convolved_crosstalk():
    truth = _integral(CROSSTALK)
    exact = _fit(np.zeros(T.size), exact_force=True)
    share, _ = exact.share([_integral(column) for column in exact.columns.T])
    # the force read is the pulse, the model is the truth's: equal to rounding (1.6e-13)
    assert share == pytest.approx(truth, rel=1e-9)
    # the share is the reading of the fitted values (linearity), to rounding
    assert share == pytest.approx(_integral(exact.values), rel=1e-9)
    found = _fit(np.random.default_rng(3).normal(0.0, 0.01, T.size))
    share, error = found.share([_integral(column) for column in found.columns.T])
    # read as the method reads it, the force under the pulse is the record, which holds
    # the crosstalk itself (2 % of the peak): +2.3 % noise-free; 4 % leaves room for
    # four of the share's propagated standard errors (1.0 % of it here)
    assert share == pytest.approx(truth, rel=0.04)
    assert error < 0.02 * abs(truth)


@pytest.mark.parametrize("coloured", [False, True])
def test_the_propagated_error_matches_a_monte_carlo_over_noise_seeds(coloured):
    rng = np.random.default_rng(11)
    sigma, phi = 0.01, 0.9
    autocovariance = sigma**2 * phi ** np.arange(T.size) if coloured else None
    shares, errors = [], []
    for _ in range(DRAWS):
        noise = _ar1(T.size, phi, sigma, rng) if coloured else rng.normal(0.0, sigma, T.size)
        found = _fit(noise, autocovariance)
        share, error = found.share([_integral(c) for c in found.columns.T])
        shares.append(share)
        errors.append(error)
    spread = float(np.std(shares, ddof=1))
    # the standard deviation of 60 draws is known to 1/sqrt(2 * 59) = 9.2 %: 30 % is
    # 3.3 of its standard errors; the columns (the pulse read from the noisy record)
    # carry noise too, which the propagation leaves out (0.01 N on a 3 N pulse)
    assert float(np.median(errors)) == pytest.approx(spread, rel=0.3)
    # the mean share is the noise-free one (the noise adds no bias): within 4 standard
    # errors of the mean of the draws
    clean = _fit(np.zeros(T.size))
    expected, _ = clean.share([_integral(c) for c in clean.columns.T])
    assert abs(np.mean(shares) - expected) < 4.0 * spread / math.sqrt(DRAWS)


def test_a_mode_left_out_biases_the_others_and_keeping_it_does_not():
    # with every mode fitted the crosstalk through the pulse is read to the 2.3 % the
    # read force costs (above); with one mode left out of the model the other two take
    # part of it (their columns overlap on the pre and post windows of a few periods)
    noise = np.random.default_rng(5).normal(0.0, 0.002, T.size)
    truth = _integral(CROSSTALK)
    every = _fit(noise)
    share, _ = every.share([_integral(c) for c in every.columns.T])
    assert share == pytest.approx(truth, rel=0.03)  # measured +2.1 %, error 0.17 %
    for left_out in range(3):
        fewer = _fit(noise, modes=[m for k, m in enumerate(MODES) if k != left_out])
        biased, _ = fewer.share([_integral(c) for c in fewer.columns.T])
        # measured -19 %, -43 % and -43 % with the 730, 1890 and 4100 Hz mode left out
        assert abs(biased / truth - 1.0) > 0.15, (left_out, biased / truth)


def test_local_baseline_reads_further_records_with_the_same_fit():
    rng = np.random.default_rng(8)
    y = PULSE + 0.2 + 30.0 * T + rng.normal(0.0, 0.01, T.size)
    others = np.column_stack([CROSSTALK, np.sin(2e3 * T), rng.normal(0.0, 1.0, T.size)])
    base = (ONSET - 4e-4, ONSET - 3e-6)
    noise = ColouredNoise(white=0.01, pink=0.005, dt=DT, shape=0.9 ** np.arange(T.size))
    for model in (None, noise):
        args = (base, base[1], CONTACT_END, T[-1], SENSOR, model)
        together = local_baseline(T, y, *args, also=others)
        alone = [local_baseline(T, column, *args).impulse for column in others.T]
        # the same fit, column by column: equal to rounding (1e-12 of the largest)
        scale = max(abs(v) for v in alone)
        assert np.allclose(together.impulses, alone, rtol=0.0, atol=1e-12 * scale)
        assert together.impulse == local_baseline(T, y, *args).impulse
        # linearity: the impulse of a sum is the sum of the impulses
        summed = local_baseline(T, y + others[:, 0], *args).impulse
        assert summed == pytest.approx(together.impulse + together.impulses[0], rel=1e-9)


@given(
    st.floats(-1e3, 1e3, allow_nan=False),
    st.floats(1e-6, 1e3, allow_nan=False),
    st.floats(1e-3, 1e3, allow_nan=False),
)
def test_the_removal_rule_compares_the_squared_share_with_twice_its_variance(share, error, k):
    removed = removed_from_impulse(share, error)
    # the unbiased estimate of the true share's square, s**2 - e**2, against the
    # variance e**2 the removal adds
    if abs(abs(share) - math.sqrt(2.0) * error) > 1e-9 * error:  # off the boundary
        assert removed == (share**2 - error**2 > error**2)
        # a change of unit or of sign changes nothing
        assert removed_from_impulse(-k * share, k * error) == removed


def test_the_fast_toeplitz_quadratic_form_is_scipy_s():
    # against x' scipy.linalg.matmul_toeplitz(lags, x) (FFT at 2 n - 1, inverse FFTs) at
    # a slow, an odd and a fast length, and the dense Toeplitz product at a small one
    rng = np.random.default_rng(2)
    for n in (5003, 4097, 4096):
        lags = 0.9 ** np.arange(n) + rng.normal(0.0, 1e-3, n)
        x = rng.normal(size=(n, 3))
        expected = x.T @ linalg.matmul_toeplitz(lags, x)
        # FFT sums of the same data in another order: rounding (1e-10 of the largest)
        scale = float(np.abs(expected).max())
        assert np.allclose(toeplitz_quadratic(lags, x), expected, rtol=0.0, atol=1e-10 * scale)
    lags, x = 0.5 ** np.arange(7), rng.normal(size=(7, 2))
    dense = x.T @ linalg.toeplitz(lags) @ x
    assert np.allclose(toeplitz_quadratic(lags, x), dense, rtol=1e-12, atol=0.0)
