"""The first lobe of an impact's segment (``dem_check.campaign.segment_lobe``): read
against the line through both sides where the signal does not come back to the
baseline window's mean (issue 22, xtlobe: 2 % crosstalk Hertz records)."""

from types import SimpleNamespace

import numpy as np
import pytest

import contactlab as cl
from contactlab.metrics import first_lobe
from dem_check.campaign import find_impacts
from dem_check.campaign.analysis import read_impact
from dem_check.campaign.detection import ONSET_SIGMAS
from dem_check.campaign.drawn_records import accuracy_record
from dem_check.campaign.local import record_noise
from dem_check.campaign.segment_lobe import NoLobe, main_lobe_start, segment_lobe
from dem_check.campaign.structure import record_modes

RATE = 2e6  # [Hz]


def _segment(slope, seed=0):
    """A 100 us half-sine lobe of 0.5 N from 0.5 ms on a 1.2 ms segment, smoothed white
    noise of 0.01 N and a ramp of ``slope`` [N/s] from the segment's start."""
    t = np.arange(0.0, 1.2e-3, 1.0 / RATE)
    onset, duration = 0.5e-3, 100e-6
    lobe = np.where((t > onset) & (t < onset + duration), np.sin(np.pi * (t - onset) / duration), 0)
    noise = np.random.default_rng(seed).normal(0.0, 0.01, t.size)
    noise = np.convolve(noise, np.ones(8) / np.sqrt(8), mode="same")  # smoothed, same sigma
    window = SimpleNamespace(baseline_window=(0.0, 0.45e-3), onset=onset, end=0.8e-3)
    return t, 0.5 * lobe + noise + slope * t, window


def test_a_level_that_moved_between_the_sides_still_ends_the_lobe():
    """A ramp that lifts the signal after the lobe 0.056 N (5.6 noise sigmas) above the
    baseline window's mean: no dip reaches that mean, the line through both sides' means
    takes the ramp off, and the lobe is the one read on the signal less the exact ramp
    at the same onset level."""
    slope = 150.0  # [N/s]
    t, ramped, window = _segment(slope)
    held = np.zeros(t.size, dtype=bool)
    in_base = t < window.baseline_window[1]
    level = ONSET_SIGMAS * np.std(ramped[in_base], ddof=1)
    less = ramped - slope * t - np.mean(ramped[in_base] - slope * t[in_base])
    first = main_lobe_start(less, level)
    expected = first_lobe(t[first:], less[first:], level, hysteresis=level)
    # the line's error is the two sides' noise means (0.01 N over about 100 and 50
    # independent samples: 0.001-0.0015 N) over the lobe's slope at the level (about
    # 15000 N/s): 0.1 us; a sample (0.5 us) bounds it
    assert segment_lobe(t, ramped, window, held) == pytest.approx(expected, abs=0.5e-6)
    short = SimpleNamespace(**{**vars(window), "end": t[-1]})  # no decayed ringing after it
    with pytest.raises(NoLobe, match="does not return to"):
        segment_lobe(t, ramped, short, held)


def test_the_2_mhz_crosstalk_hertz_impact_without_a_lobe_is_read(hard_setup):
    """``bench_realistic.py --accuracy --law hertz``, "2 MHz, crosstalk 2 %", seed 0: the
    13 sigma impact at 13.84 ms was ``reconstruction failed`` (its smoothed signal,
    crosstalk removed, stayed 0.02-0.06 N above the baseline window's mean after the
    lobe, the onset level 0.155 N). Now read within the issue's targets."""
    grain, sensor, _ = hard_setup
    record = accuracy_record(0, grain, sensor, cl.laws.Hertz(k_hertz=1.5e6), RATE, crosstalk=0.02)
    found = find_impacts(record.trace, sensor)
    noise = record_noise(found, sensor)
    modes = record_modes(found, sensor, noise=noise)
    truth = record.truth.iloc[int(np.argmin(np.abs(record.truth["onset [s]"] - 13.84e-3)))]
    (window,) = [w for w in found.impacts if abs(w.onset - truth["onset [s]"]) < 60e-6]
    row, _, _ = read_impact(found, window, sensor, grain, modes=modes, noise=noise)
    assert row["status"] == "ok", row["reason"]
    # measured -1.8 %, -2.8 %, -2.9 %, -3.0 %; the targets are 2 % for the peak
    # signal and 5 % for the others; the peak signal's bound at 13 sigma is 38 sigma
    # (bench_bounds.py --law hertz), so it is held to the 5 % of the others
    for column in ("peak_sensor_force", "impulse", "peak_contact_force", "contact_time"):
        unit = {"impulse": "[N*s]", "contact_time": "[s]"}.get(column, "[N]")
        error = row[f"{column} {unit}"] / truth[f"{column} {unit}"] - 1.0
        assert abs(error) < 0.05, (column, error)


def test_a_contact_that_reaches_its_window_s_end_has_no_contact_time(hard_setup):
    """The same configuration, seed 3, without the record's structure modes (as
    ``record_modes`` read it until session 17, the crosstalk left in): the 16.5 sigma
    impact at 18.12 ms read a contact time of 485 us for 216 us (+124 %): the regularised
    force, ringing left in, stayed above its threshold past the window it is
    reconstructed on, and the family's fit failed. No contact end is read there: the row
    says so instead of a contact time (the modes found now:
    ``test_weak_crosstalk_modes.py``)."""
    grain, sensor, _ = hard_setup
    record = accuracy_record(3, grain, sensor, cl.laws.Hertz(k_hertz=1.5e6), RATE, crosstalk=0.02)
    found = find_impacts(record.trace, sensor)
    noise = record_noise(found, sensor)
    (window,) = [w for w in found.impacts if abs(w.onset - 18.12e-3) < 60e-6]
    row, _, _ = read_impact(found, window, sensor, grain, modes=[], noise=noise)
    assert row["status"] == "reconstruction failed"
    assert "no contact end to read" in row["reason"], row["reason"]
