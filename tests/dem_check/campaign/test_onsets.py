"""Onsets on realistic records (issue 22): the fitted first touch (dem_check.campaign.onsets)
against the forward model's, and against the detector's 5-sigma crossing it replaces.

Records as ``benchmarks/bench_onsets.py`` builds them: the paper's grain on the 40 kHz
sensor, four impacts of 0.6-2.4 m/s and their bounces (40 % of the velocity, 2 ms later),
every effect of ``Effects.everything`` but crosstalk, clipping and offset steps (1/f noise
as large as the 1 % white noise, drift of 20 sigma, hum of 1.5 sigma), with a linear
contact (its force steps at the touch) and a Hertz one (its force grows as t**1.5). The
truth is the model's first touch (the exact two-mass solver's), the fit's force shapes
are a rigid wall's (contactlab.inverse.lobe_onset), so this checks the fit's timing and
its families against the solver.
"""

import itertools

import numpy as np
import pytest
from four_impacts import NOISE, four_impact_record

import contactlab as cl
from contactlab.errors import ParameterError
from dem_check.campaign import Effects, find_impacts, onsets
from dem_check.campaign.detection import ANALYSED

MATCH = 100e-6
"""A detected crossing this close to a true onset is that impact [s] (impacts and their
bounces are 1-2 ms apart; a 4-sigma Hertz bounce crosses 5 sigma up to 52 us late)."""


_DETECTED = {}
"""Fitted detections of the records of :func:`_detected`, by ``(law, rate, seed)``: the
tests of this module share them (the files of a module run in one worker)."""


def _detected(hard_setup, law, rate, seed=5):
    """A record of the benchmark's kind (four impacts of 0.6-2.4 m/s and their bounces)
    and its impacts with fitted onsets."""
    key = (law, rate, seed)
    if key not in _DETECTED:
        grain, sensor, linear = hard_setup
        contact = linear if law == "linear" else cl.laws.Hertz(k_hertz=1.5e6)
        effects = Effects.everything(NOISE, 3.0, crosstalk=0.0, full_scale=None, steps=0)
        record = four_impact_record(
            grain, sensor, contact, [2.4, 0.6, 1.8, 1.2], effects, sample_rate=rate, seed=seed
        )
        _DETECTED[key] = (record, find_impacts(record.trace, sensor).impacts)
    return _DETECTED[key]


def _errors(hard_setup, law, rate):
    """Onset errors [samples] of the analysed impacts of one record, fitted and crossing
    (the same impacts, matched by their crossing), and their significances (peak over
    random noise) [-]."""
    sensor = hard_setup[1]
    record, fitted = _detected(hard_setup, law, rate)
    truth = record.truth
    onsets = truth["onset [s]"].to_numpy()
    crossing = find_impacts(record.trace, sensor, fit_onsets=False).impacts
    rows = []
    for w, c in zip(fitted, crossing, strict=True):
        gap = np.abs(onsets - c.onset)
        if w.status in ANALYSED and gap.min() <= MATCH:
            k = int(gap.argmin())
            significance = truth["peak_sensor_force [N]"].iloc[k] / record.noise
            rows.append(((w.onset - onsets[k]) * rate, (c.onset - onsets[k]) * rate, significance))
    return np.array(rows)


@pytest.mark.parametrize(
    ("law", "rate"),
    [
        ("linear", 1e6),  # measured 0.06 samples at 37-92 sigma (the crossing 5.7)
        ("linear", 2e6),  # measured 0.10 (the crossing 10)
        ("linear", 5e6),  # measured 0.20 (the crossing 42)
        ("hertz", 1e6),  # measured 0.79 at 43-60 sigma (the crossing 52)
        ("hertz", 2e6),  # measured 0.66 (the crossing 89)
        ("hertz", 5e6),  # measured 0.98 (the crossing 165)
    ],
)
def test_fitted_onsets_are_closer_than_the_crossing(hard_setup, law, rate):
    """From 30 sigma the fitted onsets hold the issue's 2 samples, and over every analysed
    impact (bounces of 4-30 sigma included) the largest error is below the crossing's."""
    errors = _errors(hard_setup, law, rate)
    assert len(errors) >= 7  # the four impacts and most bounces analysed
    strong = errors[:, 2] >= 30.0
    assert strong.sum() >= 2  # the two fastest impacts at least
    assert np.abs(errors[strong, 0]).max() <= 2.0, errors  # the target
    assert np.abs(errors[:, 0]).max() < np.abs(errors[:, 1]).max()


def test_the_stated_onset_uncertainty_is_honest(hard_setup):
    """Over 8 records (linear and Hertz contacts, 2 and 5 MHz, two seeds each; 1/f noise
    as large as the white noise, drift, hum) the fitted onsets' errors over their stated
    ``onset_uncertainty`` (the fit's standard deviation under the record's white and 1/f
    noise, with the error of the damping ratio read on the record) spread as a standard
    normal would: an independent check, against the forward model's first touch, that
    the number is neither too small nor padded."""
    ratios = []
    for law, rate, seed in itertools.product(("linear", "hertz"), (2e6, 5e6), (5, 6)):
        record, impacts = _detected(hard_setup, law, rate, seed)
        onsets = record.truth["onset [s]"].to_numpy()
        for w in impacts:
            gap = np.abs(onsets - w.onset)
            if w.status in ANALYSED and gap.min() <= MATCH:
                assert w.onset_uncertainty > 0.0, w  # every analysed impact was fitted
                ratios.append((w.onset - onsets[gap.argmin()]) / w.onset_uncertainty)
    ratios = np.abs(ratios)
    assert len(ratios) >= 56  # 8 records of 8 impacts, a few weak bounces not analysed
    # a standard normal holds 95.4 % within 2; 90 % leaves 2.4 binomial standard
    # deviations for 60 impacts (measured 98 %, 60 of 61). Stated too small, it fails:
    # counting the noise alone with the record's damping taken as known gave 90 % (one
    # Hertz record at 2 MHz read damping 0.015 for 0: onsets 3-12 samples late, up to
    # 5.7 of those uncertainties); the white-noise bound is 2-4 times smaller still
    assert np.mean(ratios <= 2.0) >= 0.9, np.sort(ratios)
    # not padded either: a root-mean-square ratio near 1 (measured 0.97 over all, 0.56
    # to 1.28 per contact and rate; the damping counted as unknown per impact gave 0.22
    # to 0.64 on Hertz); 0.6-1.4 allows 60 draws' spread and the rigid-wall shapes' bias
    assert 0.6 <= np.sqrt(np.mean(ratios**2)) <= 1.4, np.sqrt(np.mean(ratios**2))


def test_an_impact_whose_fit_fails_keeps_its_crossing_and_says_so(hard_setup, monkeypatch):
    """Where an impact's lobe fit fails (forced here after the family was read), its
    onset is the 5-sigma crossing and its reason says why."""
    grain, sensor, law = hard_setup
    effects = Effects.everything(NOISE, 3.0, crosstalk=0.0, full_scale=None, steps=0)
    record = four_impact_record(
        grain, sensor, law, [2.4, 0.6, 1.8, 1.2], effects, sample_rate=1e6, seed=5
    )

    def fails(*args, **kwargs):
        raise ParameterError("forced by the test")

    crossing = find_impacts(record.trace, sensor, fit_onsets=False).impacts
    monkeypatch.setattr(onsets, "fit_lobe", fails)
    kept = find_impacts(record.trace, sensor).impacts
    analysed = [k for k, w in enumerate(kept) if w.status in ANALYSED]
    assert analysed
    for k in analysed:
        assert kept[k].onset == crossing[k].onset
        assert "5-sigma crossing" in kept[k].reason and "forced by the test" in kept[k].reason


def test_a_crossing_that_leads_the_touch_still_finds_the_family_and_the_touch(hard_setup):
    """At 5 MHz the smoothed signal of a linear contact's force step crosses five sigmas
    up to 3 samples before the touch (the Gaussian kernel's reach). A search that ended at
    the crossing made the linear family's fit fail on the strongest impacts, the record
    read ``hertz`` with damping 0.34, and every onset was 3.4-4.7 samples early (measured
    on this record before the fix; the benchmark's 3.6-4.0 at 5 MHz with 2 % crosstalk)."""
    grain, sensor, law = hard_setup
    effects = Effects.everything(NOISE, 3.0, pink=0.3 * NOISE, full_scale=None, steps=0)
    record = four_impact_record(
        grain, sensor, law, [2.4, 0.6, 1.8, 1.2], effects, sample_rate=5e6, seed=5
    )
    found = find_impacts(record.trace, sensor, fit_onsets=False)
    analysed = [w for w in found.impacts if w.status in ANALYSED]
    fitted, notes, family, damping, _, _ = onsets.record_onsets(found, analysed, sensor)
    truth = record.truth["onset [s]"].to_numpy()
    true = np.array([truth[np.abs(truth - w.onset).argmin()] for w in analysed])
    crossing = (np.array([w.onset for w in analysed]) - true) * 5e6
    assert crossing.min() < 0.0  # the case: a crossing before the touch (-2.75 measured)
    assert family == "linear"
    # the hard grain's c2 / (2 sqrt(k2 m2)) = 0.177: read 0.1735 here, 0.1716-0.1727 on
    # the benchmark's records (rigid-wall shapes against the two-mass solver, noise);
    # 0.01 is twice the refinement's tolerance (lobe_onset.DAMPING_TOLERANCE)
    assert damping == pytest.approx(0.177, abs=0.01)
    assert not any(notes)
    errors = (np.asarray(fitted) - true) * 5e6
    assert np.abs(errors).max() <= 2.0, errors  # the target (measured 0.76 at 12 sigma)
