"""The contact's edges from the reconstruction's own uncertainty
(:mod:`contactlab.inverse.contact_edges`)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from contactlab.errors import ParameterError
from contactlab.inverse.contact_edges import (
    FLANK_HIGH,
    SIGNIFICANCE_SIGMAS,
    significant_edges,
    tikhonov_std,
)


def test_the_spread_is_that_of_solutions_over_noise_draws():
    # independent method: the sample standard deviation of the Tikhonov solution over
    # 4000 noise draws against noise * sqrt(diag(G G^T))
    rng = np.random.default_rng(1)
    h = np.tril(np.exp(-0.3 * np.subtract.outer(np.arange(40), np.arange(12)).clip(0)))[:, :12]
    penalty = 0.5 * np.diff(np.eye(12), axis=0)
    noise = 0.2
    clean = h @ np.sin(np.linspace(0, np.pi, 12))
    normal = h.T @ h + penalty.T @ penalty
    draws = clean[:, None] + rng.normal(0.0, noise, (40, 4000))
    solutions = np.linalg.solve(normal, h.T @ draws)
    # a standard deviation from 4000 draws has a relative standard error of
    # 1 / sqrt(2 * 4000) = 1.1 %; 4 % is more than three of those
    np.testing.assert_allclose(
        tikhonov_std(h, penalty, noise), solutions.std(axis=1, ddof=1), rtol=0.04
    )


def test_without_a_penalty_the_spread_is_the_least_squares_one():
    # closed form: h = 2 I and no penalty gives f = s / 2, of standard deviation noise / 2
    h = 2.0 * np.eye(5)
    np.testing.assert_allclose(tikhonov_std(h, np.zeros((4, 5)), 0.3), 0.15, rtol=1e-12)


def _triangle(t, start, peak_time, end):
    """A pulse of 1 N with straight flanks from ``start`` to ``end`` [s]."""
    rise = np.clip((t - start) / (peak_time - start), 0.0, None)
    fall = np.clip((end - t) / (end - peak_time), 0.0, None)
    return np.minimum(np.minimum(rise, fall), 1.0)


@given(
    start=st.floats(-20e-6, 20e-6),
    rise=st.floats(20e-6, 80e-6),
    fall=st.floats(20e-6, 80e-6),
)
def test_straight_flanks_extrapolate_to_their_zeros(start, rise, fall):
    # a force with straight flanks, read where it is significant (above 3 sigma of a
    # spread of 2 % of the peak): the flanks' lines reach zero at the contact's edges
    t = np.arange(-100e-6, 300e-6, 0.5e-6)
    force = _triangle(t, start, start + rise, start + rise + fall)
    metrics = significant_edges(t, force, np.full(t.size, 0.02))
    # the fitted samples lie on the line exactly: only rounding remains (1e-12 s on
    # times of 1e-4 s)
    assert metrics.start == pytest.approx(start, abs=1e-12)
    assert metrics.end == pytest.approx(start + rise + fall, abs=1e-12)
    assert metrics.peak == pytest.approx(force.max(), rel=1e-15)


def test_a_noise_bump_after_the_contact_does_not_hold_it_open():
    # a bump of 4 % of the peak after the contact, joined to it by a shelf at 3 %
    # (what 1/f noise left at 20-30 sigma): not significant at a spread of 2 % of the
    # peak, so it neither extends the contact nor is read as a second lobe
    t = np.arange(-100e-6, 300e-6, 0.5e-6)
    force = _triangle(t, 0.0, 50e-6, 100e-6)
    tail = (t > 95e-6) & (t < 160e-6)
    force[tail] = np.maximum(force[tail], 0.03 + 0.01 * np.sin(np.pi * (t[tail] - 95e-6) / 65e-6))
    metrics = significant_edges(t, force, np.full(t.size, 0.02))
    # the flank between 10 % and 50 % is the triangle's: its end exactly
    assert metrics.end == pytest.approx(100e-6, abs=1e-12)


def test_the_significance_level_bounds_the_flank_fit():
    # a spread of 5 % of the peak puts the significance level (15 %) above FLANK_LOW:
    # the flank is fitted from there to FLANK_HIGH, and straight flanks still give
    # their zeros
    t = np.arange(-100e-6, 300e-6, 0.5e-6)
    force = _triangle(t, 0.0, 40e-6, 100e-6)
    assert SIGNIFICANCE_SIGMAS * 0.05 < FLANK_HIGH
    metrics = significant_edges(t, force, np.full(t.size, 0.05))
    assert metrics.duration == pytest.approx(100e-6, abs=1e-12)  # exact line: rounding


def test_a_peak_within_the_noise_is_refused():
    t = np.arange(0.0, 1e-4, 1e-6)
    force = _triangle(t, 20e-6, 50e-6, 80e-6)
    with pytest.raises(ParameterError, match="standard deviations"):
        significant_edges(t, force, np.full(t.size, 0.5))
