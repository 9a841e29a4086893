"""A box of offset steps over an impact at a record's first sample (issue 22,
:mod:`dem_check.campaign.edge_boxes`): the lobe and up to two steps fitted at once,
adopted only where each step beats the noise and the lobe model's own error.

The records are the exact two-mass solver's (:func:`dem_check.campaign.realistic_record`:
a grain on the sensor, not the lobe model's rigid wall); the steps are the records'
``offsets`` (a level that changes between two samples).
"""

import itertools

import numpy as np
import pytest

from contactlab.inverse.noise_colour import ARNoise
from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.edge_boxes import _place_steps, _steps, _white_steps
from dem_check.campaign.edge_models import _Projector

NOISE = 0.03
"""White noise of the records [N] (as the hard mix's)."""

MATCH = 60e-6
"""Largest distance of a detected onset or step row from the truth [s] (as the hard mix
counts them)."""


def _brute_force(y, noise, fixed, count):
    """Chi-squared and places of ``count`` steps by least squares on every place (pair),
    numpy's solver on the whitened design."""
    n = y.size
    line = np.column_stack([np.ones(n), np.arange(n) - 0.5 * (n - 1), fixed])
    best = (np.inf, None)
    for places in itertools.combinations(range(1, n), count):
        steps = [(np.arange(n) >= p).astype(float) for p in places]
        design = noise.whiten(np.column_stack([line, *steps]))
        rss = np.linalg.lstsq(design, noise.whiten(y), rcond=None)[1]
        chi2 = float(rss[0]) / noise.innovation**2
        if chi2 < best[0]:
            best = (chi2, list(places))
    return best


@pytest.mark.parametrize("count", [1, 2])
def test_the_step_places_are_least_squares(count):
    # every place (pair) at once from the whitened columns' inner products, against
    # numpy's least squares on each place (pair) in turn; AR(2) noise, a fixed column
    rng = np.random.default_rng(5)
    n = 48
    noise = ARNoise(np.array([0.9, -0.2]), 0.05, 1000)
    fixed = np.exp(-np.arange(n) / 9.0) * np.sin(np.arange(n) / 3.0)
    y = 0.3 * fixed + 0.4 * (np.arange(n) >= 17) - 0.3 * (np.arange(n) >= 31)
    y += rng.normal(0.0, 0.05, n)
    chi2, places = _place_steps(y, 16, noise, fixed[:, None], count)  # grid of 1 sample
    expected, truth = _brute_force(y, noise, fixed, count)
    assert places == truth
    assert chi2 == pytest.approx(expected, rel=1e-8)  # exact linear algebra: rounding


def test_the_whitened_steps_are_one_whitened_step_shifted():
    # the whitened unit step at every place (and at a few), one whitened step sampled,
    # against each column whitened on its own: the same operations on the same values
    noise = ARNoise(np.array([0.9, -0.2, 0.05]), 0.05, 1000)
    projector = _Projector(np.random.default_rng(1).normal(0.0, 0.05, 200), 25, noise)
    for places in (np.arange(1, 200), np.arange(5, 180, 7), np.array([50])):
        assert np.array_equal(
            _white_steps(projector, 200, places), noise.whiten(_steps(200, places))
        )


def _record(hard_setup, velocity, offsets, effects, rate, seed):
    effects = Effects(**{**effects, "offsets": offsets})
    sampling = {"length": 3e-3, "sample_rate": rate, "noise": NOISE, "seed": seed}
    return realistic_record(*hard_setup, [velocity], [0.0], **sampling, effects=effects)


@pytest.mark.parametrize("rate", [1e6, 5e6])
def test_a_box_over_an_impact_at_the_first_sample_is_two_steps(hard_setup, rate):
    # seed 15 of the hard mix without its other effects: -0.72 and +0.85 N steps at
    # 0.091 and 0.167 ms over a 0.54 m/s impact at the first sample, 1/f noise of one
    # sigma; before, a 'negative' impact was read at the first step, the true one missed
    offsets = ((0.0914e-3, -0.723), (0.1665e-3, 0.853))
    record = _record(hard_setup, 0.536, offsets, {"pink": NOISE}, rate, seed=2)
    found = find_impacts(record.trace, hard_setup[1])
    assert [w.status for w in found.impacts] == ["short pre-trigger"]
    assert abs(found.impacts[0].onset) <= MATCH
    assert len(found.steps) == 2
    for step, (at, height) in zip(found.steps, offsets, strict=True):
        assert abs(step.onset - at) <= 1.0 / rate + 1e-9  # placed at every sample: one off
        # read with the rigid wall's lobe, whose error on the grain's lobe moves the
        # first step (inside the contact): measured within 0.08 N at 1 and 5 MHz
        assert step.peak == pytest.approx(height, abs=0.1)


@pytest.mark.parametrize("rate", [1e6, 2e6, 5e6])
@pytest.mark.parametrize("velocity", [1.5, 2.5])
def test_a_strong_impact_at_the_first_sample_draws_no_box(hard_setup, rate, velocity):
    # every effect of the hard mix but steps (1/f noise of one sigma, hum, crosstalk,
    # drift): the lobe model's error on a strong lobe, which two free steps absorb
    # (0.2-0.3 N boxes inside the lobe, at most 0.0098 of its whitened energy per step
    # measured on 48 such impacts), stays under MODEL_ERROR: no step row
    largest = 1.5 * velocity
    effects = Effects.everything(
        NOISE, largest, drift=10 * NOISE, full_scale=1.2 * largest + 20 * NOISE, steps=0
    )
    sampling = {"length": 3e-3, "sample_rate": rate, "noise": NOISE, "seed": 4}
    record = realistic_record(*hard_setup, [velocity], [0.0], **sampling, effects=effects)
    found = find_impacts(record.trace, hard_setup[1])
    assert found.steps == []
    assert found.impacts[0].status == "short pre-trigger"
    assert abs(found.impacts[0].onset) <= MATCH
