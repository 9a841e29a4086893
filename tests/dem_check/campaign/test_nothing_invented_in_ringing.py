"""Rows invented on records without steps (issue 22: "no invented impact", "nothing
lost").

The records are ``benchmarks/bench_weak_impacts.py``'s
(:func:`dem_check.campaign.drawn_records.weak_in_ringing`: a strong impact and a weak one
in its ringing, every effect but offset steps). Before, seed 11 listed a -0.012 N step: a
step read across the strong impact on one pass (+0.112 N) was taken back on the next
(-0.124 N at one place) and the remainder listed (the seeds' step rows:
``test_no_invented_steps.py``). Seed 109 listed an ``ok`` impact at 7.25 local sigmas
(threshold 7.0) where the lobe fit finds no contact.
"""

import numpy as np
import pytest

from contactlab.inverse import lobe_onset
from contactlab.inverse.lobe_onset import NoContact, fit_lobe
from dem_check.campaign import find_impacts
from dem_check.campaign.drawn_records import weak_in_ringing
from dem_check.campaign.onsets import CONFIRM_SIGMAS, NO_CONTACT
from dem_check.campaign.steps import LEAST_HEIGHT, OffsetStep, settle_steps

MATCH = 60e-6
"""Largest distance of a detected onset from the true one [s], as the benchmarks count
them (two and a half periods of the 40 kHz sensor)."""


def test_a_weak_candidate_without_a_contact_is_listed_not_an_impact(hard_setup):
    record, _ = weak_in_ringing(109, *hard_setup)  # 2 MHz, 6 ms
    found = find_impacts(record.trace, hard_setup[1])
    truth = record.truth["onset [s]"].to_numpy()
    onsets = np.array([w.onset for w in found.impacts])
    assert onsets.size == truth.size and np.abs(onsets - truth).max() <= MATCH
    (bump,) = found.unconfirmed  # listed with why, 0.6 ms before the record's end
    assert bump.status == NO_CONTACT
    assert bump.significance < CONFIRM_SIGMAS
    assert abs(bump.onset - 5.386e-3) < MATCH
    assert "no contact fitted" in bump.reason


def test_steps_a_later_pass_took_back_are_dropped_and_stop_the_search():
    period, noise = 40, 0.03
    least = LEAST_HEIGHT * noise
    there = OffsetStep(725, 0.112, 17.0, (0, 1000))
    back = OffsetStep(727, -0.124, 9.0, (0, 1000))  # within an eighth of a period
    elsewhere = OffsetStep(3000, 0.25, 12.0, (2000, 4000))
    kept, taken_back = settle_steps([there, elsewhere, back], period, least)
    assert taken_back
    assert kept == [elsewhere]  # the remainder, -0.012 N, is under 3 sample sigmas
    kept, taken_back = settle_steps([there, elsewhere], period, least)
    assert not taken_back and kept == [there, elsewhere]


def test_a_fit_on_noise_alone_finds_no_contact(hard_setup):
    _, sensor, _ = hard_setup
    rng = np.random.default_rng(3)
    dt, noise = 5e-7, 0.03
    t = np.arange(4000) * dt
    y = rng.normal(0.0, noise, t.size)
    guess = (1.0e-3, 1.0e-4)  # a crossing at 1 ms, a 100 us contact
    with pytest.raises(NoContact, match="no contact fitted"):
        fit_lobe(t, y, sensor, guess, noise, "linear", 0.0)
    assert issubclass(NoContact, lobe_onset.ParameterError)  # callers catching it still do


def test_a_no_contact_row_is_listed_in_the_campaign_and_not_counted(tmp_path, hard_setup):
    from contactlab.traces import write_trace
    from dem_check.campaign import run_campaign

    record, _ = weak_in_ringing(109, *hard_setup)
    write_trace(tmp_path / "bump.csv", record.trace, "generic")
    result = run_campaign(tmp_path / "bump.csv", hard_setup[1], hard_setup[0], gallery=0)
    assert result.impacts["status"].tolist() == ["ok", "ok", NO_CONTACT]
    assert "no contact fitted" in result.impacts.iloc[2]["reason"]
    (row,) = result.files.to_dict("records")
    assert row["impacts"] == 2 and row["impacts_ok"] == 2  # the bump is no impact
