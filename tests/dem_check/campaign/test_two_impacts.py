"""Two impacts close together (issue 22): the impulse read next to another impact, against
the truth of the record model (dem_check.campaign.realistic_record, one truth row per
impact).

The hard grain (100 us contact) on the 40 kHz sensor at 2 MHz, white noise of 1 % of the
3 N peak and 1/f noise as large as it; a second impact 0.12, 0.2 or 0.5 ms after the
first, as strong or at half its velocity (for this linear contact the impulse is
proportional to the velocity). The model superposes the two responses (exact for the
signal, not for the physics of a sensor hit while it rings: docs/campaign.md, Limits), so
the segment's impulse is the two truths' sum.
"""

import dataclasses
import re

import numpy as np
import pytest
from scipy import signal

from contactlab.inverse.local_baseline import local_baseline
from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.analysis import ONSET_MARGIN, analyse_impact
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.local import record_noise
from dem_check.campaign.overlaps import HELD_OUT, SUBTRACTED, UNRELIABLE, separate_overlaps
from dem_check.campaign.structure import record_modes

NOISE = 0.03
"""White noise [N] (and 1/f noise of the same standard deviation)."""


def _pair(hard_setup, gap, ratio, seed=0):
    grain, sensor, law = hard_setup
    return realistic_record(
        grain,
        sensor,
        law,
        [2.0, 2.0 * ratio],
        [1e-3, 1e-3 + gap],
        length=4e-3,
        sample_rate=2e6,
        noise=NOISE,
        effects=Effects(pink=NOISE),
        seed=seed,
    )


@pytest.mark.parametrize("ratio", [1.0, 0.5])
@pytest.mark.parametrize("gap", [120e-6, 200e-6, 500e-6])
def test_a_close_pair_is_never_read_as_one_impact(hard_setup, gap, ratio):
    """Flagged ``overlap`` either way: by the ringing check (0.2 and 0.5 ms: both listed,
    each naming the other's onset) or, for a second contact that begins within a period
    of the first lobe's end (0.12 ms), by the impulse check of the analysis, whose stated
    ratio is the truth's: the segment's impulse (both contacts) over the first's."""
    grain, sensor, _ = hard_setup
    record = _pair(hard_setup, gap, ratio)
    truth = record.truth["impulse [N*s]"].to_numpy()
    found = find_impacts(record.trace, sensor)
    rows = []
    for window in found.impacts:
        if window.status in ANALYSED:
            rows.append(analyse_impact(found, window, sensor, grain)[0])
        else:
            rows.append({"status": window.status, "reason": window.reason})
    assert [r["status"] for r in rows] == ["overlap"] * (1 if gap < 150e-6 else 2)
    if gap < 150e-6:
        stated = float(re.search(r"impulse is ([0-9.]+) times", rows[0]["reason"]).group(1))
        # measured 2.00 and 1.52 on this seed (2.0 and 1.5 true), 1.97-2.17 and
        # 1.47-1.53 over 3 seeds and gaps of 110-130 us; 0.1 is twice the impulse
        # reader's spread at this significance under 1/f noise, doubled for two contacts.
        # Before the post-contact window moved past the second contact: 1.77 and 1.41
        assert stated == pytest.approx(truth.sum() / truth[0], abs=0.1)
    else:
        first, second = found.impacts
        assert f"{second.onset:.6g} s" in first.reason
        assert f"{first.onset:.6g} s" in second.reason


@pytest.mark.parametrize("ratio", [1.0, 0.5])
@pytest.mark.parametrize("gap", [200e-6, 500e-6])
def test_the_first_impulse_with_the_neighbour_held_out(hard_setup, gap, ratio):
    """The first impact's local baseline (a line before it and the free ringing after its
    contact, with the noise under the pulse predicted from both sides) with the second
    impact's samples held out (a period before its onset to its decayed ringing, as the
    campaign holds out every other impact's): its impulse is the first truth's. Fitted on
    them, the post-contact window reads the second impact's force as the first one's
    ringing."""
    sensor = hard_setup[1]
    record = _pair(hard_setup, gap, ratio)
    true = float(record.truth["impulse [N*s]"].iloc[0])
    found = find_impacts(record.trace, sensor)
    first, second = found.impacts
    part = slice(first.first, first.stop)
    t = np.asarray(found.record.t[part])
    y = np.asarray(found.record.values[part], dtype=float)
    start = first.onset - ONSET_MARGIN * sensor.period  # the campaign's integral start
    base = (first.baseline_window[0], start)
    contact_end = first.onset + 100e-6 + sensor.period  # a period past the true contact
    held = (t >= second.onset - sensor.period) & (t <= second.end)
    noise = record_noise(found, sensor)

    def impulse(exclude):
        return local_baseline(
            t, y, base, start, contact_end, first.end, sensor, noise, exclude
        ).impulse

    # measured -0.4 % (0.2 ms) and -0.3 % (0.5 ms) on this seed, within 1.1 % over 3
    # seeds and gaps of 0.2-0.5 ms: the reader's spread at about 100 sigma under 1/f
    # noise as large as the white noise is about 1 % (docs/campaign.md); 2.5 % is 2.5 of it
    assert impulse(held) == pytest.approx(true, rel=0.025)
    if gap < 300e-6:  # the second impact inside the post-contact window: read with it
        # measured -13 % (equal impacts) and -6.6 % (half the velocity) on this seed
        assert abs(impulse(None) / true - 1.0) > 0.05


TARGETS = {
    "peak_sensor_force [N]": 0.02,
    "impulse [N*s]": 0.05,
    "peak_contact_force [N]": 0.05,
    "contact_time [s]": 0.05,
}
"""Issue 22's targets for one impact, relative [-] (onsets: 2 samples)."""


@pytest.mark.parametrize(
    ("gap", "ratio"),
    [
        (200e-6, 1.0),
        (200e-6, 0.5),
        (300e-6, 1.0),
        (300e-6, 0.5),
        (500e-6, 1.0),
        (500e-6, 0.5),
    ],
)
def test_a_pair_in_the_ringing_is_read_apart(hard_setup, gap, ratio):
    """Both impacts of a pair the ringing check flags are analysed: the first with the
    second held out (from two periods before its onset the record is the first one's
    line and free ringing, fitted from a period after its lobe together with the second
    impact's contact family's lobe), the second on the record less that ringing, its
    peak signal, impulse, contact force and contact time read from that joint fit. Each
    meets the issue's targets against its own truth (the model's impact alone); at 0.2
    ms the first's reconstruction would read mostly held-out samples, and it gives its
    signal's numbers only."""
    grain, sensor, _ = hard_setup
    record = _pair(hard_setup, gap, ratio)
    found = find_impacts(record.trace, sensor)
    assert [w.status for w in found.impacts] == ["overlap", "overlap"]
    modes = record_modes(found, sensor)
    read = separate_overlaps(found, sensor, grain, None, True, modes, record_noise(found, sensor))
    rows = [read[k][0] for k in range(2)]
    assert [r["status"] for r in rows] == [HELD_OUT, SUBTRACTED]
    assert all(status in ANALYSED for status in (HELD_OUT, SUBTRACTED))
    assert f"the impact at {found.impacts[1].onset:.6g} s held out" in rows[0]["reason"]
    assert "free ringing of the impact at" in rows[1]["reason"]
    reconstructed = gap > 250e-6
    if not reconstructed:
        assert "no contact force or contact time" in rows[0]["reason"]
    dt = 1.0 / 2e6
    for k, (row, (_, true)) in enumerate(zip(rows, record.truth.iterrows(), strict=True)):
        # the targets (onset 2 samples, peak signal 2 %, the rest 5 %); measured
        # over 3 seeds: onsets within 0.21 samples, the first impact's peak signal and
        # impulse within 1.2 and 1.1 %, the second's within 1.8 and 1.9 %, contact
        # forces within 3.6 %, contact times within 3.5 % (docs/campaign.md, "Overlaps
        # read apart"); before the joint fit the second at half the velocity 0.2 ms
        # after the first missed them: peak signal +6.2 %, impulse +8.0 % on this seed
        assert abs(row["onset [s]"] - true["onset [s]"]) <= 2.0 * dt
        for column, target in TARGETS.items():
            if (
                k == 0
                and not reconstructed
                and column in ("peak_contact_force [N]", "contact_time [s]")
            ):
                assert column not in row
                continue
            assert row[column] == pytest.approx(true[column], rel=target), column


@pytest.mark.parametrize("gap", [200e-6, 300e-6])
def test_a_misread_family_is_caught_by_the_joint_fit(hard_setup, gap):
    """The record's contact family misread (Hertz, damping 0.25, for this linear
    contact): the joint fit with it disagrees with the record's noise, is refitted with
    every family, and the second impact (half the velocity) is read with the family that
    agrees, within the issue's targets; its reason says what was rejected and what kept."""
    grain, sensor, _ = hard_setup
    record = _pair(hard_setup, gap, 0.5)
    found = find_impacts(record.trace, sensor)
    misread = dataclasses.replace(found, contact_family=("hertz", 0.25))
    modes = record_modes(found, sensor)
    noise = record_noise(found, sensor)
    read = separate_overlaps(misread, sensor, grain, None, True, modes, noise)
    row = read[1][0]
    assert row["status"] == SUBTRACTED
    assert "family (hertz, damping ratio 0.25) was rejected" in row["reason"]
    assert "the linear contact" in row["reason"]
    true = record.truth.iloc[1]
    for column, target in TARGETS.items():
        assert row[column] == pytest.approx(true[column], rel=target), column


def test_a_merged_pair_read_as_a_short_contact_is_flagged(hard_setup):
    """Two equal impacts 110 us apart (seed 1): the reconstruction reads the merged lobe
    as a 6-sample spike, which passed for a record too coarse to reconstruct and printed
    the segment's impulse (both contacts, +74 %) as an ``ok`` impact's. A first lobe
    longer than the reconstructed contact and a sensor period is not a short contact:
    the row is an ``overlap`` without numbers, its reason saying why."""
    grain, sensor, _ = hard_setup
    record = _pair(hard_setup, 110e-6, 1.0, seed=1)
    found = find_impacts(record.trace, sensor)
    assert len(found.impacts) == 1
    row = analyse_impact(found, found.impacts[0], sensor, grain)[0]
    assert row["status"] == "overlap"
    assert "one contact does not explain it" in row["reason"]
    assert "impulse [N*s]" not in row


def test_a_second_force_no_family_has_is_flagged_unreliable(hard_setup):
    """One impact of the record model and, 0.2 ms later, a rectangular force of 1.2 N for
    100 us pushed through the sensor by :func:`scipy.signal.lsim` (no contact family's
    shape): the joint fit is rejected with every family, the second impact's row is
    ``overlap, unreliable`` (not analysed) and both reasons say why."""
    grain, sensor, law = hard_setup
    record = realistic_record(
        grain,
        sensor,
        law,
        [2.0],
        [1e-3],
        length=4e-3,
        sample_rate=2e6,
        noise=NOISE,
        effects=Effects(pink=NOISE),
    )
    t = np.asarray(record.trace.t)
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    system = signal.lti([2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w])
    fine = np.linspace(0.0, t[-1], 10 * (t.size - 1) + 1)
    force = np.where((fine >= 1.2e-3) & (fine <= 1.3e-3), 1.2, 0.0)
    extra = np.interp(t, fine, signal.lsim(system, force, fine)[1])
    values = np.asarray(record.trace.values) + extra
    found = find_impacts(record.trace.derive({"step": "rectangle added"}, values=values), sensor)
    assert [w.status for w in found.impacts] == ["overlap", "overlap"]
    modes = record_modes(found, sensor)
    read = separate_overlaps(found, sensor, grain, None, True, modes, record_noise(found, sensor))
    first, second = read[0][0], read[1][0]
    assert first["status"] == HELD_OUT
    assert second["status"] == UNRELIABLE and UNRELIABLE not in ANALYSED
    for row in (first, second):
        assert "no family agrees" in row["reason"]
    assert "unreliable" in second["reason"]
