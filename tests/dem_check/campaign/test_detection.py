"""Finding impacts in one record: false alarms, overlaps, edges, polarity, overrange."""

import re

import numpy as np
import pytest

from contactlab.errors import ParameterError
from contactlab.traces import Trace
from dem_check.campaign import find_impacts, synthetic_record

RATE = 2e6
NOISE = 0.03  # [N], about 1 % of the hard grain's peaks


def _record(hard_setup, onsets, length, velocities=None, seed=0, noise=NOISE):
    velocities = [2.0] * len(onsets) if velocities is None else velocities
    sampling = {"length": length, "sample_rate": RATE, "noise": noise, "seed": seed}
    return synthetic_record(*hard_setup, velocities, onsets, **sampling)


def test_noise_alone_gives_no_impact(hard_setup):
    """A million samples of noise: the Bonferroni threshold expects 1e-3 false alarms."""
    sensor = hard_setup[1]
    for seed in range(3):
        trace, _ = _record(hard_setup, [], 0.5, seed=seed)
        found = find_impacts(trace, sensor)
        assert found.impacts == []
        assert found.floor.sigmas > 6.0  # 6.1 sigma for 1e6 samples
        # the quiet window's noise is the generator's, to its sampling error
        assert found.floor.noise == pytest.approx(NOISE, rel=0.05)


def test_separated_impacts_are_ok_and_timed(hard_setup):
    sensor = hard_setup[1]
    onsets = [1e-3, 3.5e-3, 6e-3]
    trace, truth = _record(hard_setup, onsets, 8.5e-3, velocities=[1.5, 2.0, 2.5])
    found = find_impacts(trace, sensor)
    assert [w.status for w in found.impacts] == ["ok"] * 3
    errors = [w.onset - t for w, t in zip(found.impacts, truth["onset [s]"], strict=True)]
    assert np.abs(errors).max() < 10e-6  # the onset requirement
    for window, onset in zip(found.impacts, truth["onset [s]"], strict=True):
        start, end = window.baseline_window
        assert end < onset  # the local baseline holds no part of the impact
        assert trace.t[window.first] == start


@pytest.mark.parametrize("gap", [150e-6, 400e-6, 600e-6])
def test_overlapping_impacts_are_flagged_not_merged(hard_setup, gap):
    """A second impact while the first one's ringing (about 1 ms) is still up."""
    sensor = hard_setup[1]
    trace, truth = _record(hard_setup, [1e-3, 1e-3 + gap, 4e-3], 6e-3)
    found = find_impacts(trace, sensor)
    statuses = [w.status for w in found.impacts]
    assert statuses == ["overlap", "overlap", "ok"]
    first, second, _ = found.impacts
    assert abs(first.onset - truth["onset [s]"][0]) < 10e-6  # the onset requirement
    # the later impact is placed where the ringing envelope grew: within a period
    assert abs(second.onset - truth["onset [s]"][1]) < sensor.period
    assert f"{second.onset:.6g} s" in first.reason
    assert f"{first.onset:.6g} s" in second.reason


def test_a_second_contact_right_after_the_first_lobe_is_flagged(hard_setup):
    """120 us after a 100 us contact: too early for the ringing check, caught by the
    impulse check of the analysis (the segment holds twice the contact's impulse: read
    to a period past the second contact's end, which the reconstruction shows; 1.77
    when the post-contact window started inside the second contact)."""
    from dem_check.campaign.analysis import analyse_impact

    grain, sensor, _ = hard_setup
    trace, _ = _record(hard_setup, [1e-3, 1.12e-3], 4e-3)
    found = find_impacts(trace, sensor)
    (window,) = found.impacts
    assert window.status == "ok"
    row, traces = analyse_impact(found, window, sensor, grain)
    assert row["status"] == "overlap" and traces is None
    ratio = float(re.search(r"impulse is ([0-9.]+) times", row["reason"]).group(1))
    assert 1.8 < ratio < 2.2  # two equal impacts: twice the first contact's impulse


def test_a_segment_without_a_whole_first_lobe_is_a_failed_row_not_an_error(hard_setup):
    """A segment that ends before the signal returns to its onset level (here the
    window's last sample moved to the first lobe's top) is a ``reconstruction failed``
    row that says why: it was a ParameterError on a NaN contact end, which cost
    ``run_campaign`` every row of the file (found on a Hertz record of
    ``bench_realistic.py``)."""
    import dataclasses

    from dem_check.campaign.analysis import analyse_impact

    grain, sensor, _ = hard_setup
    trace, _ = _record(hard_setup, [1e-3], 3e-3)
    found = find_impacts(trace, sensor)
    (window,) = found.impacts
    smoothed = np.asarray(found.smoothed.values[window.first : window.stop])
    cut = dataclasses.replace(window, stop=window.first + int(np.argmax(smoothed)))
    row, traces = analyse_impact(found, cut, sensor, grain, crosstalk=False)
    assert row["status"] == "reconstruction failed" and traces is None
    assert "does not return to" in row["reason"], row["reason"]


def test_impacts_after_the_ringing_decayed_are_separate(hard_setup):
    """1 ms later the first ringing is under the noise floor: two ok impacts (at 900 us
    it is in 4 of 8 seeds: the local noise, read without the impacts, sets a lower floor
    than the quietest stretch's did)."""
    sensor = hard_setup[1]
    trace, truth = _record(hard_setup, [1e-3, 2e-3], 4e-3)
    found = find_impacts(trace, sensor)
    assert [w.status for w in found.impacts] == ["ok", "ok"]
    start, end = found.impacts[1].baseline_window
    assert found.impacts[0].onset < start and end < truth["onset [s]"][1]


def test_impact_at_the_record_edges(hard_setup):
    sensor = hard_setup[1]
    trace, _ = _record(hard_setup, [2e-6, 3e-3], 3.3e-3)
    statuses = [w.status for w in find_impacts(trace, sensor).impacts]
    # no quiet samples before the first (its baseline is read after its ringing); the
    # second still rings when the record ends
    assert statuses == ["short pre-trigger", "truncated"]


def test_negative_polarity_is_flagged(hard_setup):
    sensor = hard_setup[1]
    trace, _ = _record(hard_setup, [1e-3], 3e-3)
    flipped = trace.derive({"step": "negate"}, values=-np.asarray(trace.values))
    (window,) = find_impacts(flipped, sensor).impacts
    assert window.status == "negative" and "polarity" in window.reason


def test_overrange_samples_are_flagged(hard_setup):
    sensor = hard_setup[1]
    trace, _ = _record(hard_setup, [1e-3, 3.5e-3], 6e-3)
    values = np.array(trace.values)
    top = int(np.argmax(values[: int(3e-3 * RATE)]))  # the first impact's peak
    values[top - 2 : top + 3] = np.inf
    clipped = Trace(trace.t, values, "N", {"sample_interval": 1.0 / RATE})
    first, second = find_impacts(clipped, sensor).impacts
    assert first.status == "overrange" and "5 overrange samples" in first.reason
    assert second.status == "ok"


def test_a_record_without_noise_is_refused(hard_setup):
    sensor = hard_setup[1]
    trace = Trace(np.arange(4000) / RATE, np.zeros(4000), "N")
    with pytest.raises(ParameterError, match="no noise"):
        find_impacts(trace, sensor)
