"""The noise under a pulse predicted from both sides (contactlab.inverse.noise_prediction)
against the closed-form conditional mean of an AR(1) process, a Monte Carlo of its
error variance against the exact one, invariants, and the noise levels' estimate on
1/f noise drawn independently of the toolkit."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pink_noise import pink_by_phases
from scipy.linalg import cholesky, toeplitz

from contactlab.errors import ParameterError
from contactlab.inverse.noise_prediction import (
    ColouredNoise,
    estimate_coloured_noise,
    pink_autocovariance,
    predict_gap,
)
from dem_check.campaign.bounds import free_variance


def _gap(n, first, last):
    """Indices before ``first``, from ``first`` to ``last - 1`` and from ``last`` on."""
    index = np.arange(n)
    return index[:first], index[first:last], index[last:]


def _bridge(phi, y, a, k, b):
    """AR(1) noise of coefficient ``phi`` at sample ``k`` given samples ``a < k < b`` of
    ``y``: the conditional mean, in closed form (the Markov property: only the nearest
    sample on each side counts)."""
    return (
        phi ** (k - a) * (1.0 - phi ** (2 * (b - k))) * y[a]
        + phi ** (b - k) * (1.0 - phi ** (2 * (k - a))) * y[b]
    ) / (1.0 - phi ** (2 * (b - a)))


@given(phi=st.floats(0.05, 0.98), gap=st.integers(1, 40), position=st.floats(0.0, 1.0))
def test_ar1_gap_is_the_markov_bridge_in_closed_form(phi, gap, position):
    """AR(1) noise ``C(k) = phi**|k|`` with no baseline: given every sample outside the
    gap ``(a, b)``, only its two edge samples count, and the conditional mean at ``k`` is
    ``(phi**(k-a) (1 - phi**(2(b-k))) x_a + phi**(b-k) (1 - phi**(2(k-a))) x_b) /
    (1 - phi**(2(b-a)))``."""
    n, first = 120, 40
    last = first + gap
    before, inside, after = _gap(n, first, last)
    rng = np.random.default_rng(5)
    y = rng.normal(size=n)
    autocovariance = phi ** np.arange(n)
    beta, found = predict_gap(autocovariance, y, np.zeros((n, 0)), before, after, inside, 1)
    a, b = first - 1, last
    k = inside[min(int(position * gap), gap - 1)]
    expected = _bridge(phi, y, a, k, b)
    # Cholesky solve against the closed form: rounding (conditioning up to ~1e4 at phi
    # 0.98, measured 1e-12)
    assert found[k - first] == pytest.approx(expected, rel=1e-8, abs=1e-10)
    assert beta.size == 0


@settings(deadline=None)  # a few ms an example; timings are no part of the check
@given(
    phi=st.floats(0.05, 0.98),
    gap=st.integers(1, 30),
    left_out=st.integers(1, 30),
    far=st.integers(1, 20),
    position=st.floats(0.0, 1.0),
)
def test_samples_left_out_next_to_the_gap_move_the_bridge_to_the_next_sample_kept(
    phi, gap, left_out, far, position
):
    """AR(1) noise with samples left out of the conditioning set (another impact's):
    ``left_out`` samples right after the gap and ``far`` samples inside the run before
    it. Only the nearest samples kept on each side count (Markov), so the conditional
    mean is the bridge of the closed form between the last sample kept before the gap,
    ``a``, and the first kept after it, ``c = b + left_out``: the left-out samples are
    neither noise to condition on nor signal to predict; the far run left out changes
    nothing."""
    n, first = 160, 50
    last = first + gap
    index = np.arange(n)
    before = index[: first - 20 - far].tolist() + index[first - 20 : first].tolist()
    after = index[last + left_out :]
    inside = index[first:last]
    y = np.random.default_rng(6).normal(size=n)
    autocovariance = phi ** np.arange(n)
    _, found = predict_gap(autocovariance, y, np.zeros((n, 0)), np.array(before), after, inside, 1)
    a, c = first - 1, last + left_out
    k = inside[min(int(position * gap), gap - 1)]
    expected = _bridge(phi, y, a, k, c)
    # Cholesky solve against the closed form: rounding (as the gap's test above)
    assert found[k - first] == pytest.approx(expected, rel=1e-8, abs=1e-10)


def test_runs_are_averaged_in_blocks_of_their_own():
    """With blocks of 3 samples and a run of ``after`` cut by samples left out, the
    reading equals one made on the two runs' block means by hand: each run's blocks
    start at its first sample (before: end at its last), none straddles the gap."""
    n, q = 120, 3
    index = np.arange(n)
    before = index[10:40]
    after = np.concatenate([index[60:71], index[80:100]])  # 11 = 3 blocks + 2 left over
    inside = index[40:60]
    y = np.random.default_rng(9).normal(size=n)
    autocovariance = 0.8 ** np.arange(n) + np.eye(1, n)[0]
    design = np.column_stack([np.ones(n), index / n])
    beta, found = predict_gap(autocovariance, y, design, before, after, inside, q)
    starts = np.concatenate([np.arange(10, 40, q), np.arange(60, 69, q), np.arange(80, 98, q)])
    members = starts[:, None] + np.arange(q)
    full = toeplitz(autocovariance)
    within = np.array([[full[np.ix_(m, p)].mean() for p in members] for m in members])
    cross = np.array([[full[k, m].mean() for m in members] for k in inside])
    block_y, block_x = y[members].mean(axis=1), design[members].mean(axis=1)
    weights = np.linalg.solve(within, block_x)
    expected_beta = np.linalg.solve(block_x.T @ weights, weights.T @ block_y)
    expected = cross @ np.linalg.solve(within, block_y - block_x @ expected_beta)
    # the same linear algebra by dense matrices: rounding (measured 1e-13)
    np.testing.assert_allclose(beta, expected_beta, rtol=1e-9)
    np.testing.assert_allclose(found, expected, rtol=1e-9, atol=1e-12)


def test_prediction_ignores_the_baseline_and_reproduces_it():
    """Adding ``X gamma`` to the record adds ``gamma`` to the GLS parameters and nothing
    to the predicted noise (the reading is unbiased for any baseline), with blocks."""
    n = 300
    before, inside, after = _gap(n, 100, 160)
    t = np.arange(n) / n
    design = np.column_stack([np.ones(n), t - 0.5])
    autocovariance = 0.5 * 0.9 ** np.arange(n)
    autocovariance[0] += 0.2
    y = np.random.default_rng(2).normal(size=n)
    beta, noise = predict_gap(autocovariance, y, design, before, after, inside, 3)
    gamma = np.array([4.0, -7.0])
    shifted, same = predict_gap(
        autocovariance, y + design @ gamma, design, before, after, inside, 3
    )
    # linear algebra on the same factor: rounding
    np.testing.assert_allclose(shifted, beta + gamma, rtol=1e-9)
    np.testing.assert_allclose(same, noise, atol=1e-9)


def test_error_variance_matches_the_exact_one_by_monte_carlo():
    """White + AR(1) noise drawn by its exact Cholesky factor, a line baseline: the
    spread of the sum of the pulse read over a gap (record less GLS line less predicted
    noise, on noise alone) matches ``free_variance``'s exact variance of that reading;
    with blocks of 4 samples it is no better than it."""
    n, draws = 200, 4000
    before, inside, after = _gap(n, 80, 120)
    t = np.arange(n) / n
    design = np.column_stack([np.ones(n), t - 0.5])
    autocovariance = 0.95 ** np.arange(n)
    autocovariance[0] += 0.3
    rng = np.random.default_rng(8)
    noise = cholesky(toeplitz(autocovariance), lower=True) @ rng.normal(size=(n, draws))
    free = np.zeros(n, dtype=bool)
    free[inside] = True
    exact = free_variance(autocovariance, ~free, free, design, free * 1.0, np.zeros(2))
    spreads = []
    for q in (1, 4):
        beta, predicted = predict_gap(autocovariance, noise, design, before, after, inside, q)
        read = (noise[inside] - design[inside] @ beta - predicted).sum(axis=0)
        spreads.append(float(np.var(read)))
    # 4000 draws give a variance to 2.2 % (sqrt(2 / 4000)): 4 of its sigmas (measured
    # 1.001 times the exact variance)
    assert spreads[0] == pytest.approx(exact, rel=0.09)
    # blocks of 4 use less of the noise's correlation: measured 1.036 times the exact
    # variance; never below it by more than 4 of the draws' sigmas
    assert spreads[1] > exact * 0.91


@pytest.mark.parametrize("white, pink", [(0.03, 0.03), (0.03, 0.01), (0.02, 0.0)])
def test_levels_of_white_and_pink_noise_are_estimated(white, pink):
    """White and 1/f noise drawn by random phases (not the toolkit's draw), a drift line
    and gaps of impacts: the two levels come back to a few per cent."""
    count, dt, period = 50000, 1e-6, 25e-6
    rng = np.random.default_rng(4)
    y = rng.normal(0.0, white, count) + 5.0 * np.linspace(0.0, 1.0, count)
    if pink:
        y += pink_by_phases(rng, count, pink)
    quiet = np.ones(count, dtype=bool)
    for start in range(2000, count, 6000):
        quiet[start : start + 1500] = False
    found = estimate_coloured_noise(y, quiet, dt, count * dt, period)
    # 36000 quiet samples at lags to 50 samples: measured within 0.3 % (white) and 1.9 %
    # (pink) on this seed; 3 and 10 % allow other draws
    assert found.white == pytest.approx(white, rel=0.03)
    assert found.pink == pytest.approx(pink, rel=0.1, abs=0.1 * white)


def test_autocovariance_is_white_plus_pink():
    """``ColouredNoise.autocovariance``: white at lag 0 only, 1/f scaled by its variance,
    held at the last lag of its shape beyond it."""
    shape = pink_autocovariance(10, 1e-6, 1e-3)
    noise = ColouredNoise(white=0.1, pink=0.2, dt=1e-6, shape=shape)
    found = noise.autocovariance(12)
    expected = 0.04 * np.concatenate([shape, [shape[-1]] * 2])
    expected[0] += 0.01
    np.testing.assert_allclose(found, expected, rtol=1e-14)  # the same products
    assert shape[0] == 1.0 and np.all(np.diff(shape) < 0.0)  # a 1/f correlation decays


def test_too_few_quiet_samples_is_refused():
    """A record with no quiet stretch long enough: a ParameterError naming ``quiet``."""
    y = np.random.default_rng(0).normal(size=1000)
    quiet = np.zeros(1000, dtype=bool)
    quiet[::7] = True
    with pytest.raises(ParameterError, match="quiet"):
        estimate_coloured_noise(y, quiet, 1e-6, 1e-3, 25e-6)
