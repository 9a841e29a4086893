"""Offset steps right before an impact and in its ringing (issue 22): the failing records
of the hard mix of ``benchmarks/bench_steps.py`` rebuilt small (one impact, its bounce,
the same steps, every effect on at the mix's levels), read as the impact and its steps.

A step found across an impact (the level after its ringing less the level before it) is
placed with the sensor's free ringing fitted (:mod:`dem_check.campaign.step_ringing`);
two steps on either side of the impact's main lobe are one level change there, their
sum, and each is placed and read with the other fitted.
"""

import numpy as np
import pytest

from dem_check.campaign import Effects, find_impacts, realistic_record

NOISE = 0.03
"""White noise of the records [N], as in the hard mix."""

MATCH = 60e-6
"""Largest distance of a detected onset or step row from the truth [s], as the hard mix
and the sweep count them (two and a half periods of the 40 kHz sensor)."""


def _record(hard_setup, velocity, offsets, *, rate, seed):
    """An impact of ``velocity`` [m/s] at 1 ms and its bounce 2 ms later, every effect of
    the hard mix on (1/f noise 1 sigma, hum 1.5, crosstalk 2 %, drift 20 sigma, 16-bit
    ADC), and the offset steps ``(time [s], height [N])``; 5 ms."""
    largest = 1.5 * velocity  # the hard grain's peak signal [N]
    rails = 1.2 * largest + 20 * NOISE + sum(abs(h) for _, h in offsets)
    effects = Effects.everything(
        NOISE, largest, full_scale=rails, steps=0, offsets=offsets, bounce_delay=2e-3
    )
    sampling = {"length": 5e-3, "sample_rate": rate, "noise": NOISE, "seed": seed}
    return realistic_record(*hard_setup, [velocity], [1e-3], **sampling, effects=effects)


def _read(record, sensor):
    found = find_impacts(record.trace, sensor)
    onsets = np.array([w.onset for w in found.impacts])
    truth = record.truth["onset [s]"].to_numpy()
    return found, onsets, truth


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_step_in_the_ringing_of_a_lobe_less_than_twice_its_height(hard_setup, seed):
    # seed 83 of the hard mix: a 0.77 m/s impact (1.25 N) at 5 MHz and a 0.65 N step 147
    # us after its onset. The lobe lies only 0.6 N beyond the new level, less than the
    # step's height: it was not found as a lobe, the step was placed at the onset and
    # the impact read as a 'negative' one (-0.83 N) 70 us later, the true one missed
    record = _record(hard_setup, 0.769, ((1.147e-3, 0.653),), rate=5e6, seed=seed)
    found, onsets, truth = _read(record, hard_setup[1])
    (step,) = found.steps
    assert abs(step.onset - 1.147e-3) <= MATCH
    # read as a level change across the impact (medians of period means): within 10 %
    assert step.peak == pytest.approx(0.653, rel=0.1)
    assert [w.status for w in found.impacts] == ["ok", "ok"]  # the impact and its bounce
    assert np.abs(onsets - truth).max() <= MATCH


@pytest.mark.parametrize(
    "seed",
    [1, 2, 3, 4],
)
def test_a_step_before_an_impact_and_one_in_its_ringing(hard_setup, seed):
    # seed 33 of the hard mix: a 1.03 m/s impact (1.66 N) at 5 MHz, steps of 0.181 N 73 us
    # before its onset and 0.254 N 163 us after it. Their sum was read as one step in
    # the ringing; the first was left and read as the impact's onset, 73 us early
    offsets = ((1e-3 - 73e-6, 0.181), (1.163e-3, 0.254))
    record = _record(hard_setup, 1.026, offsets, rate=5e6, seed=seed)
    found, onsets, truth = _read(record, hard_setup[1])
    assert len(found.steps) == 2
    for step, (at, height) in zip(found.steps, offsets, strict=True):
        assert abs(step.onset - at) <= MATCH
        # fitted together with the free ringing; the level between the first step and
        # the onset is read on 58 us and the levels around on 0.4 ms, which 1/f noise and
        # hum of 1-1.5 sigma move by a few hundredths of a newton (measured over seeds
        # 1-8: 0.155-0.218 N for 0.181, 0.203-0.274 N for 0.254; the record's level
        # changes over such windows spread 0.034 N on seed 4, its two steps taken out):
        # 0.06 N, under two of those spreads
        assert step.peak == pytest.approx(height, abs=0.06)
    assert [w.status for w in found.impacts] == ["ok", "ok"]
    assert np.abs(onsets - truth).max() <= MATCH


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_a_step_just_before_an_onset_is_placed_before_it(hard_setup, seed):
    # seed 14 of the hard mix: a 1.52 m/s impact (2.46 N) at 1 MHz and a 0.614 N step 19
    # us before its onset. The main lobe was taken to start a period and a half before
    # the onset (period means, a period's margin), the step could not be told from the
    # impact and was placed at the lobe's middle, 63 us off; the sensor is at rest
    # before its impact, so the samples there place it
    record = _record(hard_setup, 1.517, ((1e-3 - 19e-6, 0.614),), rate=1e6, seed=seed)
    found, onsets, truth = _read(record, hard_setup[1])
    (step,) = found.steps
    assert abs(step.onset - (1e-3 - 19e-6)) <= 3e-6  # three samples: a split's error
    assert "main lobe" not in step.reason  # told from the impact
    # read on the samples around the impact with its free ringing fitted, under drift,
    # hum and 1/f noise of 1-1.5 sigma: measured 0.579-0.648 N on seeds 1-4 (0.449 N on
    # seed 3 and 0.535-0.675 N on 1, 2, 4 from the period means' medians alone)
    assert step.peak == pytest.approx(0.614, abs=0.1)
    assert [w.status for w in found.impacts] == ["ok", "ok"]
    assert np.abs(onsets - truth).max() <= MATCH


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_step_that_starts_the_run_of_an_impact(hard_setup, seed):
    # seed 14 of the hard mix: a 0.275 N step 0.12 ms before a 1.27 m/s impact (2.07 N)
    # at 1 MHz. The level change across the impact read 5.5 sigmas under drift and hum
    # (not a step), the run of the first pass started at the step and the impact was
    # read there, 0.12 ms early, the true onset missed
    record = _record(hard_setup, 1.274, ((1e-3 - 0.12e-3, 0.275),), rate=1e6, seed=seed)
    found, onsets, truth = _read(record, hard_setup[1])
    (step,) = found.steps
    assert abs(step.onset - (1e-3 - 0.12e-3)) <= 3e-6  # three samples: a split's error
    # two periods of the head against the quiet samples before the run: medians of 50
    # and 250 samples under 1/f noise and hum of 1-1.5 sigma, a few hundredths of a newton
    assert step.peak == pytest.approx(0.275, abs=0.05)
    assert [w.status for w in found.impacts] == ["ok", "ok"]
    assert np.abs(onsets - truth).max() <= MATCH


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_a_weak_impact_between_two_steps(hard_setup, seed):
    # seed 27 of the hard mix: a 0.22 m/s impact (0.36 N, under the 10 sigmas that must
    # be found) between a 0.417 N step 0.18 ms before it and a -0.825 N step 0.26 ms
    # after it, 1 MHz. The run held both steps and the lobe; their sum was read as one
    # step and the first step as an 'ok' impact 0.18 ms early
    offsets = ((1e-3 - 0.184e-3, 0.417), (1e-3 + 0.258e-3, -0.825))
    record = _record(hard_setup, 0.223, offsets, rate=1e6, seed=seed)
    found, onsets, truth = _read(record, hard_setup[1])
    assert len(found.steps) == 2
    for step, (at, height) in zip(found.steps, offsets, strict=True):
        assert abs(step.onset - at) <= MATCH
        assert step.peak == pytest.approx(height, abs=0.1)  # as in the cases above
    # nothing invented: every row is the impact or its bounce (a weak one may be missed)
    assert all(np.abs(truth - at).min() <= MATCH for at in onsets)
