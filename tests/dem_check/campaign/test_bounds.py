"""The accuracy bounds of the peak signal, the impulse, the peak contact force and the
contact time (dem_check.campaign.bounds) against closed forms, an independent dense
computation, and a Monte Carlo of the campaign's own impulse estimator on noise drawn
independently of ``records.py``."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pink_noise import pink_by_phases
from scipy.integrate import solve_ivp
from scipy.linalg import toeplitz
from scipy.optimize import minimize_scalar

import contactlab as cl
from contactlab.inverse.noise_prediction import estimate_coloured_noise
from dem_check.campaign import Effects
from dem_check.campaign.bounds import (
    LAW_READINGS,
    band_design,
    blue_variance,
    force_band_design,
    free_variance,
    law_design,
    noise_autocovariance,
)
from dem_check.campaign.local import local_baseline


def test_autocovariance_is_the_sum_of_its_parts_in_closed_form():
    """White noise only at lag 0; hum ``a**2 / 2 cos(w tau)`` per harmonic; 1/f noise
    ``sum_k cos(2 pi k m / N) / k`` (written as the sum, not the FFT) scaled to its
    variance."""
    dt, count, total = 1e-6, 50, 400
    effects = Effects(pink=0.02, hum=0.01, mains=60.0, harmonics=(0.5, 0.2, 0.0, 0.1))
    found = noise_autocovariance(count, dt, 0.03, effects, total * dt)
    m = np.arange(count)
    k = np.arange(1, total // 2 + 1)
    weights = 1.0 / k
    weights[-1] *= 0.5  # the Nyquist bin is its own conjugate: counted once in irfft
    pink = (np.cos(2.0 * math.pi * np.outer(m, k) / total) @ weights) / weights.sum()
    hum = sum(
        0.5 * (0.01 * r) ** 2 * np.cos(2.0 * math.pi * n * 60.0 * m * dt)
        for n, r in enumerate((1.0, 0.5, 0.2, 0.0, 0.1), start=1)
    )
    expected = 0.02**2 * pink + hum
    expected[0] += 0.03**2
    # the same sums two ways: rounding only (measured 1e-17 N**2 of 1.3e-3)
    np.testing.assert_allclose(found, expected, rtol=1e-10, atol=1e-16)


def test_pink_autocovariance_is_what_the_records_draw():
    """The sample autocovariance of 1/f noise drawn by random phases (independent of
    ``records.py``), averaged over 300 records, matches the closed form at lags 0-200."""
    rng = np.random.default_rng(3)
    count, lags = 4000, np.array([0, 1, 10, 50, 200])
    sample = np.zeros(lags.size)
    for _ in range(300):
        x = pink_by_phases(rng, count, 1.0)
        sample += [np.mean(x[: count - m] * x[m:]) for m in lags]
    sample /= 300
    expected = noise_autocovariance(201, 1.0, 0.0, Effects(pink=1.0), count * 1.0)[lags]
    # random phases leave each record's lag products little spread: measured at most
    # 0.001 off over 300 records
    np.testing.assert_allclose(sample, expected, atol=0.005)


@given(
    n=st.integers(20, 300),
    phi=st.floats(-0.8, 0.95),
)
def test_blue_of_a_mean_under_ar1_noise_in_closed_form(n, phi):
    """A constant in AR(1) noise (innovation 1): the GLS mean's variance is
    ``1 / ((n - 1)(1 - phi)**2 + 1 - phi**2)`` (the exact AR(1) likelihood)."""
    autocovariance = phi ** np.arange(n) / (1.0 - phi**2)
    found = blue_variance(autocovariance, np.ones((n, 1)), np.ones((1, 1)))[0]
    expected = 1.0 / ((n - 1) * (1.0 - phi) ** 2 + 1.0 - phi**2)
    # Levinson recursion against the closed form: rounding (conditioning up to 1e3)
    assert found == pytest.approx(expected, rel=1e-8)


def test_free_signal_under_white_noise_in_closed_form():
    """White noise, a constant baseline, the signal free on ``m`` samples: the sum of
    the signal there is read with variance ``m sigma**2 (1 + m / n_out)``; one sample
    with ``sigma**2 (1 + 1 / n_out)``."""
    n, sigma = 120, 0.3
    free = np.zeros(n, dtype=bool)
    free[40:70] = True
    autocovariance = np.zeros(n)
    autocovariance[0] = sigma**2
    design = np.ones((n, 1))
    m, outside = free.sum(), n - free.sum()
    total = free_variance(autocovariance, ~free, free, design, free * 1.0, np.zeros(1))
    single = np.zeros(n)
    single[55] = 1.0
    one = free_variance(autocovariance, ~free, free, design, single, np.zeros(1))
    # closed forms: rounding only
    assert total == pytest.approx(m * sigma**2 * (1.0 + m / outside), rel=1e-10)
    assert one == pytest.approx(sigma**2 * (1.0 + 1.0 / outside), rel=1e-10)


def test_free_variance_equals_gls_with_a_column_per_free_sample(hard_setup):
    """The Schur-complement form of ``free_variance`` against the plain GLS with one
    identity column per free sample (dense), under white + 1/f + hum noise."""
    _, sensor, _ = hard_setup
    dt = 1e-6
    t = np.arange(300) * dt
    window = (1e-4, 1.6e-4)
    effects = Effects.everything(0.03, 3.0)
    autocovariance = noise_autocovariance(t.size, dt, 0.03, effects, 25e-3)
    design, terms = band_design(t, window, 2.0 * sensor.resonance, sensor)
    baseline = design[:, terms:]
    free = (t >= window[0]) & (t < window[1])
    weights = free * dt
    tail = np.array([1e-6, 2e-6, 0.0, 0.0])
    found = free_variance(autocovariance, ~free, free, baseline, weights, tail)
    columns = np.column_stack([np.eye(t.size)[:, free], baseline])
    functional = np.concatenate([weights[free], tail])
    information = columns.T @ np.linalg.solve(toeplitz(autocovariance), columns)
    expected = functional @ np.linalg.solve(information, functional)
    # two exact formulas of the same variance: rounding (conditioning ~1e3)
    assert found == pytest.approx(expected, rel=1e-7)


def test_law_onset_column_is_minus_the_signals_slope(hard_setup):
    """The onset column of the linearised law model (a central difference in the first
    touch) equals minus the time derivative of the signal (a difference in time)."""
    grain, sensor, law = hard_setup
    dt = 2e-7
    t = np.arange(2000) * dt
    design, functionals, (peak, impulse, _, _) = law_design(grain, sensor, law, 1.5, t, 5e-5)
    values = design[:, 0] * 1.5
    slope = np.gradient(values, dt)
    inside = (t > 6e-5) & (t < 3e-4)  # away from the touch, where the slope jumps
    # a difference in the touch against one in time over 0.2 us samples: measured
    # 0.03 % of the largest slope (the time difference's truncation)
    np.testing.assert_allclose(design[inside, 3], -slope[inside], atol=2e-3 * np.abs(slope).max())
    # the signal and impulse are proportional to the velocity (a linear law)
    assert functionals[0, 0] == pytest.approx(peak / 1.5, rel=1e-12)  # exact by construction
    assert functionals[0, 1] == pytest.approx(impulse / 1.5, rel=1e-12)


def _two_mass(grain, sensor, stiffness, damping, velocity):
    """Peak contact force [N] and contact time [s] of a linear spring-dashpot between the
    grain and the sensor's moving mass on its spring and dashpot, integrated by scipy's
    ``solve_ivp`` (DOP853, rtol 1e-12; not contactlab's solver): the contact ends where
    its force returns to zero; the peak by a bounded scalar search of the dense output."""
    m1, k1, c1 = sensor.mass, sensor.stiffness, sensor.damping

    def force(y):
        return stiffness * (y[2] - y[0]) + damping * (y[3] - y[1])

    def rhs(_, y):
        return [y[1], (force(y) - k1 * y[0] - c1 * y[1]) / m1, y[3], -force(y) / grain.mass]

    def leave(_, y):
        return force(y)

    leave.terminal, leave.direction = True, -1
    sol = solve_ivp(
        rhs,
        (0.0, 1e-3),
        [0.0, 0.0, 1e-18, velocity],  # the overlap starts positive: the event is its end
        method="DOP853",
        events=leave,
        dense_output=True,
        rtol=1e-12,
        atol=1e-18,
    )
    end = float(sol.t_events[0][0])
    grid = np.linspace(0.0, end, 2001)
    i = int(np.argmax([force(sol.sol(s)) for s in grid]))
    top = minimize_scalar(
        lambda s: -force(sol.sol(s)),
        bounds=(grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]),
        method="bounded",
        options={"xatol": 1e-15},
    )
    return -top.fun, end


def test_law_gradients_of_the_contact_against_an_independent_integration(hard_setup):
    """The peak contact force and contact time, and their gradients in stiffness and
    damping (central differences through contactlab's exact solver), against a two-mass
    integration by ``solve_ivp`` (central differences of 1e-3 of it); and against the
    law's linearity in the velocity (a difference in it through the solver)."""
    grain, sensor, law = hard_setup
    t = np.arange(400) * 1e-6
    _, functionals, truth = law_design(grain, sensor, law, 1.5, t, 5e-5)
    assert LAW_READINGS[2:] == ("peak_contact_force", "contact_time")
    expected = _two_mass(grain, sensor, law.stiffness, law.damping, 1.5)
    # two integrations of the same equations: measured 1e-14 (peak) and 2e-12 (time)
    np.testing.assert_allclose(truth[2:], expected, rtol=1e-9)
    for row, name in ((1, "stiffness"), (2, "damping")):
        size = 1e-3 * getattr(law, name)
        parameters = {"stiffness": law.stiffness, "damping": law.damping}
        up = _two_mass(grain, sensor, **{**parameters, name: parameters[name] + size}, velocity=1.5)
        down = _two_mass(
            grain, sensor, **{**parameters, name: parameters[name] - size}, velocity=1.5
        )
        # central differences of relative steps 1e-4 and 1e-3 (truncation under 1e-6 of
        # the derivative) on integrations good to 1e-12: measured 1e-7 of each other
        np.testing.assert_allclose(
            functionals[row, 2:], (np.array(up) - np.array(down)) / (2.0 * size), rtol=1e-5
        )
    faster = cl.simulate_impact(grain, sensor, law, 1.5 * (1.0 + 1e-3))
    slower = cl.simulate_impact(grain, sensor, law, 1.5 * (1.0 - 1e-3))
    by_velocity = [
        (getattr(faster, n) - getattr(slower, n)) / (2e-3 * 1.5) for n in LAW_READINGS[2:]
    ]
    # a linear law: the peak force proportional to the velocity, the contact time
    # independent of it (measured 2e-13 and exactly 0: rounding)
    assert by_velocity[0] == pytest.approx(functionals[0, 2], rel=1e-9)
    assert abs(by_velocity[1]) < 1e-9 * truth[3] / 1.5
    assert functionals[0, 3] == 0.0


def test_force_band_columns_are_the_sensors_step_response(hard_setup):
    """The force band's first column (a constant force over the window) through the
    sensor against the closed-form step response of ``(2 zeta w s + w**2) / (s**2 + 2
    zeta w s + w**2)``: ``1 - exp(-zeta w s) (cos(wd s) - zeta w / wd sin(wd s))``, then
    its free decay after the window; the forces are the cosines themselves."""
    _, sensor, _ = hard_setup
    dt = 2e-7
    t = np.arange(1500) * dt
    window = (4e-5, 1.6e-4)
    design, forces = force_band_design(t, window, 2.0 * sensor.resonance, sensor)
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    wd = w * math.sqrt(1.0 - zeta**2)

    def step(s):
        s = np.maximum(s, 0.0)
        return np.where(
            s > 0.0,
            1.0 - np.exp(-zeta * w * s) * (np.cos(wd * s) - zeta * w / wd * np.sin(wd * s)),
            0.0,
        )

    start = t[np.argmax(t >= window[0])]
    end = t[np.argmax(t >= window[1])]
    # lsim takes the force linear between samples: its fall at the window's end is a ramp
    # over the sample before ``end``, which the closed form's step at its middle matches
    # to the response's curvature over half a sample (measured 1.0e-4 of the unit force)
    expected = step(t - start) - step(t - end + 0.5 * dt)
    np.testing.assert_allclose(design[:, 0], expected, atol=3e-4)
    inside = (t >= window[0]) & (t < window[1])
    assert np.all(forces[~inside] == 0.0)
    np.testing.assert_allclose(forces[inside, 0], 1.0)  # cos(0): exact


def test_the_campaign_impulse_is_no_better_than_its_bound(hard_setup):
    """Monte Carlo of the campaign's impulse estimator (``local_baseline``) on noise
    alone, drawn independently of ``records.py`` (white + 1/f by random phases, each
    0.03 N): the estimator is linear, so what it reads on noise is its error. Its spread
    must not fall below the best linear unbiased estimator's (``free`` model, more data)
    and is measured 1.2 times it with the ordinary line (docs/campaign.md, "What
    accuracy is possible"); with the noise under the pulse predicted from both sides
    (the white and 1/f levels estimated on the rest of each record) it reaches it."""
    _, sensor, _ = hard_setup
    dt, period = 1e-6, sensor.period
    onset, contact = 16 * period, 1e-4
    post = onset + contact + period
    t = np.arange(round((post + 16 * period) / dt)) * dt
    count = 25000  # a 25 ms record at 1 MHz, as bench_realistic's
    rng = np.random.default_rng(11)
    readings, predicted = [], []
    base = (onset - 8 * period, onset)
    # the white and 1/f levels, estimated on a record of its own
    noise = rng.normal(0.0, 0.03, count) + pink_by_phases(rng, count, 0.03)
    levels = estimate_coloured_noise(noise, np.ones(count, dtype=bool), dt, count * dt, period)
    for _ in range(400):
        noise = rng.normal(0.0, 0.03, count) + pink_by_phases(rng, count, 0.03)
        start = rng.integers(0, count - t.size)
        y = noise[start : start + t.size]
        readings.append(local_baseline(t, y, base, onset, post, t[-1], sensor).impulse)
        local = local_baseline(t, y, base, onset, post, t[-1], sensor, levels)
        predicted.append(local.impulse)
    spread, spread_predicted = float(np.std(readings)), float(np.std(predicted))
    effects = Effects(pink=0.03, hum=0.0)
    autocovariance = noise_autocovariance(t.size, dt, 0.03, effects, count * dt)
    design, terms = band_design(t, (onset, post), 2.0 * sensor.resonance, sensor)
    free = (t >= onset) & (t < post)
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    tail = np.array([zeta / w, math.sqrt(1.0 - zeta**2) / w, 0.0, 0.0])
    bound = math.sqrt(
        free_variance(autocovariance, ~free, free, design[:, terms:], free * dt, tail)
    )
    # 400 draws give the spread to 3.5 % (1 / sqrt(800)); the bound is a lower bound
    assert spread > 0.9 * bound
    # measured 1.15 times the bound: the line read on 8 periods before and 16 after
    # against the best use of the noise's correlation (20 % spare for the draws)
    assert spread < 1.4 * bound
    # the prediction from both sides: measured 0.97 times the bound (blocks of two
    # samples and estimated levels; 3 sigmas of the draws' 3.5 % on either side)
    assert 0.9 * bound < spread_predicted < 1.1 * bound
    # on the same draws: measured 0.85 of the ordinary line's spread
    assert spread_predicted < 0.95 * spread
