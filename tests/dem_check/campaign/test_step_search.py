"""Offset steps next to impacts and to one another (issue 22): the step placed in an
impact's ringing (:mod:`dem_check.campaign.step_ringing`) against brute-force least
squares and against the truth of an exact model, and runs of the first pass that are
steps (:mod:`dem_check.campaign.step_runs`) on white noise.
"""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rise_reference import loop_rise

from contactlab.inverse.local_baseline import _ringing
from dem_check.campaign.step_ringing import (
    height_across,
    place_across,
    rise,
    second_across,
)
from dem_check.campaign.step_runs import run_steps
from dem_check.campaign.steps import drift_slopes, find_steps, remove_steps, split
from dem_check.campaign.window_medians import nan_medians

DT = 0.5e-6
"""Sampling interval [s] (2 MHz)."""


def _window(sensor, at, *, height=0.3, noise=0.0, seed=0):
    """A window of 1600 samples: level 0.1 N, a main lobe (a half sine of 2 N over 200
    samples from sample 400), the sensor's free ringing from the contact's end (0.6 N)
    and a step of ``height`` [N] at sample ``at``; white noise of ``noise`` [N]."""
    n, period = 1600, round(sensor.period / DT)
    i = np.arange(n)
    x = np.full(n, 0.1)
    x[400:600] += 2.0 * np.sin(np.pi * (i[400:600] - 400) / 200)
    after = i >= 600  # free ringing from the contact's end
    columns = _ringing((i[after] - 500) * DT, sensor)[0]
    x[after] += columns @ np.array([0.5, -0.3])
    x[at:] += height
    x += np.random.default_rng(seed).normal(0.0, noise, n) if noise else 0.0
    return x, period


def _brute_force(x, kept, columns, height):
    """Index of the least-squares step: every place tried with numpy's lstsq."""
    best, where = np.inf, None
    for j in range(1, kept.size):
        u = (np.arange(kept.size) >= j).astype(float)
        m = np.column_stack([columns, u])
        coef, *_ = np.linalg.lstsq(m, x[kept], rcond=None)
        rss = float(np.sum((x[kept] - m @ coef) ** 2))
        if np.sign(coef[-1]) == np.sign(height) and rss < best:
            best, where = rss, int(kept[j])
    return where


@pytest.mark.parametrize("at", [700, 950, 1300])
def test_a_step_in_the_ringing_is_placed_exactly_on_the_exact_model(hard_setup, at):
    sensor = hard_setup[1]
    x, period = _window(sensor, at)
    index, lobe = place_across(x, 0.1, 0.3, period, 0.05, (sensor, DT))
    assert lobe is None
    assert index == at  # the model is exact: the residual vanishes there only


def test_the_cumulative_sums_give_the_brute_force_least_squares(hard_setup):
    sensor = hard_setup[1]
    x, period = _window(sensor, 900, noise=0.03, seed=3)
    index, _ = place_across(x, 0.1, 0.3, period, 0.05, (sensor, DT))
    # the same model fitted by lstsq for every place of the step (an independent method)
    start, stop = 400 - period, 600 + period  # the lobe with a period either side
    kept = np.r_[np.arange(start), np.arange(stop, x.size)]
    peak = 500
    ring = _ringing(np.clip(kept - peak, 0, None) * DT, sensor)[0]
    ring[kept < stop] = 0.0
    columns = np.column_stack([np.ones(kept.size), ring])
    assert index == _brute_force(x, kept, columns, 0.3)
    assert abs(index - 900) <= 2  # 10 noise sigmas: two samples of a split's scatter


@pytest.mark.parametrize("at", [360, 700, 1300])
@pytest.mark.parametrize("given", [0.15, 0.2, 0.4])
def test_the_height_across_an_impact_is_read_again_on_the_exact_model(hard_setup, at, given):
    # the period means' height off by up to half (drift, hum and 1/f noise bend their
    # windows): with 0.15 or 0.2 N for a 0.3 N step 40 samples before the lobe, the lobe
    # started at the step and the step was flagged inside it
    sensor = hard_setup[1]
    x, period = _window(sensor, at)
    height = height_across(x, 0.1, given, period, 0.05, (sensor, DT))
    assert height == pytest.approx(0.3, abs=1e-9)  # least squares on the exact model
    assert place_across(x, 0.1, height, period, 0.05, (sensor, DT)) == (at, None)


def test_a_step_inside_the_main_lobe_is_flagged(hard_setup):
    sensor = hard_setup[1]
    x, period = _window(sensor, 480)
    index, lobe = place_across(x, 0.1, 0.3, period, 0.05, (sensor, DT))
    # the lobe: period means further than the step and 0.05 N from both levels, and a
    # period either side
    assert lobe[0] < 400 < 600 < lobe[1]
    assert index == (lobe[0] + lobe[1]) // 2  # its middle: at most half the lobe off


@settings(max_examples=40, deadline=None)
@given(
    before=st.integers(40, 300),
    after=st.integers(700, 1500),
    # their sum at most 0.6 N under the 2 N lobe: larger, the lobe is taken as where the
    # period means lie further than the sum from both levels, its flanks are left to the
    # fit, and the heights come out a few mN off (0.497 and 0.503 N for two of 0.5 N)
    heights=st.tuples(st.floats(0.1, 0.3), st.floats(0.1, 0.3)),
    sign=st.sampled_from([1.0, -1.0]),
)
def test_two_steps_either_side_of_the_lobe_are_placed_exactly_on_the_exact_model(
    hard_setup, before, after, heights, sign
):
    # a step before the lobe (which the period means place from 325 on: half a period
    # of averaging and a period either side) and one in the ringing; the level change
    # across the impact is their sum, which place_across places as one step
    sensor = hard_setup[1]
    x, period = _window(sensor, before, height=sign * heights[0])
    x[after:] += sign * heights[1]
    total = sign * sum(heights)
    index, lobe = place_across(x, 0.1, total, period, 0.05, (sensor, DT))
    assert lobe is None
    second, fitted, _ = second_across(x, 0.1, total, period, 0.05, (sensor, DT), index)
    assert sorted([index, second]) == [before, after]  # the model is exact
    truth = dict(zip((before, after), heights, strict=True))
    # least squares on the exact model: the heights to rounding
    assert fitted == pytest.approx((sign * truth[index], sign * truth[second]), abs=1e-9)


def _levels(offsets, n=4000, noise=0.03, seed=1):
    """White noise of ``noise`` [N] on ``n`` samples with steps ``(index, height)``."""
    x = np.random.default_rng(seed).normal(0.0, noise, n)
    for at, height in offsets:
        x[at:] += height
    return x


@pytest.mark.parametrize(
    "offsets",
    [((2000, 0.3),), ((1800, 0.3), (2200, -0.3)), ((1800, 0.3), (2200, 0.3))],
    ids=["one", "box", "staircase"],
)
def test_a_run_of_steps_is_read_as_its_steps(offsets):
    period = 50  # 40 kHz at 2 MHz
    x = _levels(offsets)
    runs = [(1800, 2199, 1700, 2400)]  # (first, last, mask start, mask stop)
    masked = np.zeros(x.size, dtype=bool)
    masked[1700:2400] = True
    ((_, steps),) = run_steps(x, runs, period, masked, np.zeros(x.size))
    assert [s.index for s in steps] == [at for at, _ in offsets]  # 10 sigma: exact
    for step, (_, height) in zip(steps, offsets, strict=True):
        # medians of 400-1600 samples of white noise: within 4 standard errors
        assert step.height == pytest.approx(height, abs=4 * 0.03 * 1.2533 / np.sqrt(400))
    assert np.std(remove_steps(x, steps)) == pytest.approx(0.03, rel=0.1)  # no level left


def test_an_impact_shaped_run_is_no_step():
    period = 50
    x = _levels(())
    x[2000:2200] += 1.0 * np.sin(np.pi * np.arange(200) / 200)  # a main lobe, 33 sigma
    masked = np.zeros(x.size, dtype=bool)
    masked[1900:2400] = True
    assert run_steps(x, [(2000, 2199, 1900, 2400)], period, masked, np.zeros(x.size)) == []


def test_the_split_is_the_least_absolute_deviation_one():
    # the closed form: for a clean step the cost is least exactly at it
    x = np.r_[np.zeros(30), np.ones(70)]
    assert split(x, 0.0, 1.0, 0.01) == (30, 0)


def test_a_lobe_rises_where_it_leaves_the_level_not_at_one_sample_out():
    # a level of 0 N with white noise of 0.03 N (1 MHz, 25-sample periods), one sample
    # 0.2 N off it (6.7 sigma, over the 4 of a rise) at 300 and a half sine of 1 N over
    # 100 samples from 400: the rise is the lobe's (within the quarter period's half
    # margin it is returned with, and the half sine's first samples, under 4 sigma)
    x = np.random.default_rng(4).normal(0.0, 0.03, 600)
    x[300] += 0.2
    x[400:500] += np.sin(np.pi * np.arange(100) / 100)
    at = rise(x[:450], 0, (0.0, 0.0), 25)
    assert 390 <= at <= 405
    x[300] -= 0.2  # without the sample out: the same place
    assert rise(x[:450], 0, (0.0, 0.0), 25) == at


def test_a_plate_modes_slow_ringing_is_no_step_and_a_step_beside_it_is():
    # 30 ms at 1 MHz (25-sample periods of a 40 kHz sensor), white noise 0.03 N; from 22
    # ms a 730 Hz plate mode (zeta 0.01) of 0.04 N: it moves the 16-period medians by
    # 0.06 N, 12.6 sigmas of the record's level changes (measured), but the level does
    # not stay: the changes around it spread as much (2.0 sigmas of those)
    n, period, dt = 30000, 25, 1e-6
    t = np.arange(n) * dt
    x = np.random.default_rng(1).normal(0.0, 0.03, n)
    ringing = t >= 22e-3
    s, w = t[ringing] - 22e-3, 2.0 * np.pi * 730.0
    x[ringing] += 0.04 * np.exp(-0.01 * w * s) * np.sin(w * s)
    quiet = np.zeros(n, dtype=bool)
    assert find_steps(x, period, quiet) == []
    x[10000:] += 0.15  # a 5-sigma step in the quiet part: found where it is
    (step,) = find_steps(x, period, quiet)
    assert step.index == 10000
    # medians of 16 period means, each of 25 samples: 0.03 / sqrt(400) = 1.5 mN
    # standard error per median, 2.1 mN on the difference; 5 % is 3.6 of those
    assert step.height == pytest.approx(0.15, rel=0.05)


@settings(max_examples=80, deadline=None)
@given(
    size=st.integers(4, 400),
    period=st.integers(2, 60),
    seed=st.integers(0, 2**32 - 1),
    steps=st.lists(st.tuples(st.floats(0.0, 1.0), st.floats(-3.0, 3.0)), max_size=4),
    lobe=st.floats(0.0, 1.0),
    start=st.floats(0.0, 1.0),
    band=st.tuples(st.floats(-1.0, 1.0), st.floats(0.0, 2.0)),
)
def test_the_rise_taken_at_once_is_the_loops(size, period, seed, steps, lobe, start, band):
    """``step_ringing.rise`` (every sample's test at once) against the loop over the
    samples it replaced (``tests/support/rise_reference.py``): the same index on noise
    with level steps, a lobe and bands anywhere, NaN samples included."""
    rng = np.random.default_rng(seed)
    x = rng.normal(0.0, 0.1, size)
    for where, height in steps:
        x[int(where * size) :] += height
    x += 5.0 * np.exp(-(((np.arange(size) - lobe * size) / max(period, 2)) ** 2))
    if seed % 7 == 0:
        x[rng.integers(0, size)] = np.nan
    low, width = band
    first = int(start * (size - 1))
    assert rise(x, first, (low, low + width), period) == loop_rise(
        x, first, (low, low + width), period
    )


@settings(max_examples=80, deadline=None)
@given(
    rows=st.integers(1, 60),
    width=st.integers(1, 40),
    nan_share=st.floats(0.0, 1.0),
    scale=st.floats(-3.0, 3.0),
    seed=st.integers(0, 2**32 - 1),
)
def test_row_medians_are_nanmedians_to_the_last_bit(rows, width, nan_share, scale, seed):
    """``window_medians.nan_medians`` (one sort of the rows) against
    ``numpy.nanmedian(..., axis=1)``, which it replaced: rows of any width, NaN anywhere,
    whole rows of NaN (nan, as numpy gives with its warning)."""
    rng = np.random.default_rng(seed)
    values = rng.normal(size=(rows, width)) * 10.0**scale
    values[rng.random(values.shape) < nan_share] = np.nan
    with warnings.catch_warnings():  # numpy warns of an all-NaN row; nan_medians does not
        warnings.simplefilter("ignore", RuntimeWarning)
        expected = np.nanmedian(values, axis=1)
    assert np.array_equal(nan_medians(values), expected, equal_nan=True)


def test_a_linear_drift_across_a_masked_impact_is_no_step():
    # seed 281 of bench_weak_impacts.py, its drift alone: 6 ms at 2 MHz (50-sample periods),
    # 0.172 N/ms, white noise 0.03 N, the strong impact's 1.18 ms masked. A window of 16
    # period means across the mask holds 7 blocks before it and 9 after: its median is a
    # level after it, 0.56 ms later than the mean of its blocks' centres; read at that mean,
    # the drift made a 0.10 N change (9.5 sigmas on the record)
    n, period, dt, rate = 12000, 50, 0.5e-6, 0.172e3  # rate [N/s]
    x = np.random.default_rng(281).normal(0.0, 0.03, n) + rate * np.arange(n) * dt
    masked = np.zeros(n, dtype=bool)
    masked[1899:4255] = True
    assert find_steps(x, period, masked) == []
    # the drift's slope (the median rate of the level changes): within 0.6 % of the rate
    # on 20 noise draws (read at the windows' mean centres: 4.9-6.9 % low on each)
    assert np.median(drift_slopes(x, period, masked)) / dt == pytest.approx(rate, rel=0.02)
