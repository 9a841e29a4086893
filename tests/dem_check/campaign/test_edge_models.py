"""A run at a record's edge: a level step or an impact's lobe (issue 22,
:mod:`dem_check.campaign.edge_models`).

The records are the exact two-mass solver's (:func:`dem_check.campaign.realistic_record`:
a grain on the sensor, not the lobe model's rigid wall) with 1/f noise as large as
twice the white noise and a 12-bit ADC, at 1 and 2 MHz; the steps are the records'
``offsets`` (a level that changes between two samples). What must hold, as the sweep of
``test_realistic_detection.py`` asserts it: no impact invented, every impact found,
every step row within :data:`MATCH` of a true step.
"""

import numpy as np
import pytest

from contactlab.inverse.noise_colour import ARNoise
from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.edge_models import EDGE_FAMILIES, _Lobes, _Projector, judge_edge

NOISE = 0.03
"""White noise of the records [N] (as the sweep's)."""

MATCH = 60e-6
"""Largest distance of a detected onset or step row from the truth [s] (as the sweep's:
two and a half periods of the 40 kHz sensor)."""

RATES = (1e6, 2e6)


def _record(hard_setup, velocities, onsets, effects, rate, seed, length=6e-3):
    return realistic_record(
        *hard_setup,
        velocities,
        np.asarray(onsets, dtype=float),
        length=length,
        sample_rate=rate,
        noise=NOISE,
        effects=effects,
        seed=seed,
    )


def _rows(record, sensor):
    """Impact rows and step rows, each checked against the truth (nothing invented)."""
    found = find_impacts(record.trace, sensor)
    truth = record.truth["onset [s]"].to_numpy()
    for w in found.impacts:
        assert truth.size and np.min(np.abs(truth - w.onset)) <= MATCH, f"invented: {w}"
    for step in found.steps:
        distance = np.min(np.abs(record.step_times - step.onset), initial=np.inf)
        assert distance <= MATCH, f"invented step: {step}"
    return found


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("velocity", [0.25, 1.5], ids=["weak", "strong"])
@pytest.mark.parametrize("seed", [0, 3])
def test_a_lobe_at_the_first_sample_is_no_step(hard_setup, rate, velocity, seed):
    # before: a 0.25 m/s impact (0.37 N, 12 noise sigmas) at the first sample at 1 MHz,
    # 1/f noise of 2 sigma, read as a step of -0.242 N at 75 us (its lobe flat to the
    # 1/f noise beside it)
    effects = Effects(pink=2 * NOISE, full_scale=3.75, bits=12)
    record = _record(hard_setup, [velocity], [0.0], effects, rate, seed)
    found = _rows(record, hard_setup[1])
    assert found.steps == []
    assert [w.status for w in found.impacts][:1] == ["short pre-trigger"]


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("at", [0.03e-3, 0.1e-3])
@pytest.mark.parametrize("sign", [1.0, -1.0], ids=["up", "down"])
def test_a_step_near_the_start_is_a_step(hard_setup, rate, at, sign):
    # 12 noise sigmas, 1/f noise of 2 sigma, an impact 1 ms in: the samples before the
    # step are a level, not a lobe (a level change within one sample is no sensor's
    # response); 8 sigmas are not always a first-pass run there (nor a row: nothing
    # invented either)
    height = sign * 12 * NOISE
    effects = Effects(pink=2 * NOISE, full_scale=3.75, bits=12, offsets=((at, height),))
    record = _record(hard_setup, [1.0], [1e-3], effects, rate, seed=7)
    found = _rows(record, hard_setup[1])
    assert len(found.steps) == 1
    assert [w.status for w in found.impacts] == ["ok"]


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("before", [3e-6, 6e-6, 12e-6])
@pytest.mark.parametrize("sign", [1.0, -1.0], ids=["up", "down"])
def test_a_step_in_the_last_samples_is_a_step_row(hard_setup, rate, before, sign):
    # before: a -0.15 N step 3-12 us before the end was listed as a 'negative'
    # candidate in 2-6 of 12 records (1/f noise of 1 sigma); here 5 noise sigmas under
    # 1/f noise of 2 sigma
    length = 6e-3
    effects = Effects(
        pink=2 * NOISE, full_scale=3.75, bits=12, offsets=((length - before, sign * 5 * NOISE),)
    )
    record = _record(hard_setup, [1.0], [1e-3], effects, rate, seed=11, length=length)
    found = _rows(record, hard_setup[1])
    assert [w.status for w in found.impacts] == ["ok"]
    for step in found.steps:  # a step too small for the detection leaves no row
        assert "fewer than a sensor period" in step.reason


@pytest.mark.parametrize("rate", RATES)
@pytest.mark.parametrize("before", [8e-6, 15e-6])
def test_an_impact_in_the_last_samples_is_no_step(hard_setup, rate, before):
    # the start of a lobe follows the sensor's response (a quarter period to rise): a
    # 1 m/s impact 8-15 us before the end stays an impact (truncated), not a step
    length = 6e-3
    effects = Effects(pink=2 * NOISE, full_scale=3.75, bits=12)
    record = _record(hard_setup, [1.0, 1.0], [1e-3, length - before], effects, rate, 13, length)
    found = _rows(record, hard_setup[1])
    assert found.steps == []
    assert [w.status for w in found.impacts] == ["ok", "truncated"]


def test_the_projection_is_generalised_least_squares():
    # the chi-squared, amplitude and standard error of one column against numpy's
    # least squares on the whitened design (line + column), AR(2) noise
    rng = np.random.default_rng(0)
    n, period = 200, 25
    noise = ARNoise(np.array([1.2, -0.3]), 0.05, 1000)
    y = rng.normal(0.0, 1.0, n).cumsum() * 0.01 + (np.arange(n) >= 120)
    column = np.sin(np.arange(n) / 7.0)
    chi2, amplitude, error = _Projector(y, period, noise).fit(column[:, None])
    line = np.column_stack([np.ones(n), (np.arange(n) - 0.5 * (n - 1)) / period, column])
    design, data = noise.whiten(line), noise.whiten(y)
    beta, rss, *_ = np.linalg.lstsq(design, data, rcond=None)
    covariance = np.linalg.inv(design.T @ design) * noise.innovation**2
    # both are exact linear algebra: equal to rounding
    assert chi2[0] == pytest.approx(rss[0] / noise.innovation**2, rel=1e-9)
    assert amplitude[0] == pytest.approx(beta[2], rel=1e-9)
    assert error[0] == pytest.approx(np.sqrt(covariance[2, 2]), rel=1e-9)


@pytest.mark.parametrize("rate", [1e6, 5e6])
def test_the_grid_columns_are_one_whitened_signal_shifted(hard_setup, rate):
    # the lobe grid's whitened columns, one whitened signal sampled at each onset,
    # against each onset's signal interpolated on its own and whitened (AR(3) noise;
    # onsets from before the lead to after the window's first sample)
    n, lead, period = 300, 200, round(hard_setup[1].period * rate)
    lobes = _Lobes(n, lead, (hard_setup[1], 1.0 / rate))
    y = np.random.default_rng(1).normal(0.0, 0.03, n)
    projector = _Projector(y, period, ARNoise(np.array([0.9, -0.2, 0.05]), 0.03, 1000))
    starts = np.arange(-198, 13, 3)
    for spec in EDGE_FAMILIES:
        tau = 1.4 * hard_setup[1].period
        one_by_one = projector.whiten(lobes.columns(spec, starts / rate, tau))
        shifted = lobes.white_columns(spec, starts, tau, projector)
        # the same signal at times dt * (i - k) instead of dt * i - dt * k: rounding
        # (measured 1.2e-14 of the largest value)
        assert shifted == pytest.approx(one_by_one, abs=1e-12 * np.abs(one_by_one).max())


@pytest.mark.parametrize("rate", RATES)
def test_a_step_and_a_lobe_are_each_their_own_model(hard_setup, rate):
    # the exact solver's impact (a grain on the sensor) against an exact step, white
    # noise only: each window's better model is its own, the step placed at its sample
    sensor = hard_setup[1]
    dt = 1.0 / rate
    impact = _record(hard_setup, [0.5], [0.0], Effects(), rate, seed=2, length=1e-3)
    y = np.asarray(impact.trace.values)
    n = round(0.25e-3 / dt)
    ring = (sensor, dt)
    period = round(sensor.period / dt)
    lobe = judge_edge(y, (0, n), round(60e-6 / dt), ring, NOISE, (-8 * period, period))
    assert not lobe.step
    # the onset fitted where the solver's force starts, within two samples: the lobe
    # model's damping grid (0.25 nearest the contact's 0.177) moved it by 1.5 samples
    # at 2 MHz (measured 0.74 us)
    assert abs(lobe.lobe[2]) <= 2 * dt
    rng = np.random.default_rng(3)
    at = round(40e-6 / dt)
    stepped = rng.normal(0.0, NOISE, n) + 0.24 * (np.arange(n) < at)
    step = judge_edge(stepped, (0, n), at + 3, ring, NOISE, (-8 * period, at))
    assert step.step and step.index == at
    # the height within three of its standard errors (Gaussian)
    assert abs(step.height + 0.24) <= 3.0 * 0.24 / step.significance
