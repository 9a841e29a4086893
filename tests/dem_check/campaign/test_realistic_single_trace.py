"""The single-trace paths on a realistic record (issue 22): they find the hit, or say why not.

One impact of the hard grain (contact 100 us: 200 samples per contact at 2 MHz, far above
the 20 reconstruction needs) at 2 m/s, 1 ms into a 4 ms record or at its first sample,
white noise 1 % of the 3 N peak, with one laboratory effect at a time
(``dem_check.campaign.records``: the forward model's impact with what a laboratory adds).
Measured figures for every effect, over four seeds, are in ``docs/campaign.md``
("Single-trace paths"; ``benchmarks/bench_single_trace.py``).
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from contactlab.compare import compare_trace
from contactlab.config import load_config
from contactlab.errors import ParameterError
from contactlab.inverse import fit_contact, identify_sensor, reconstruct_force
from contactlab.inverse.fit_quality import FitQualityWarning
from dem_check.campaign import Effects, realistic_record

ROOT = Path(__file__).resolve().parents[3]

NOISE = 0.03
"""White noise [N], 1 % of the 3 N peak signal at 2 m/s."""

ONSETS = {"1 ms in": 1e-3, "at the start": 0.0}

EFFECTS = {
    "white": Effects(),
    "1/f 0.3 sigma": Effects(pink=0.3 * NOISE),
    "hum 1.5 sigma": Effects(hum=1.5 * NOISE),
    "drift 20 sigma": Effects(drift=20 * NOISE),
    "drift 100 sigma": Effects(drift=100 * NOISE),
    "bounce": Effects(bounce=0.4),
}
"""The levels of ``Effects.everything`` one at a time (and a drift five times larger);
1/f noise at 0.3 of the white noise, the campaign's envelope of the targets (1/f noise
as large as the white noise is tested below)."""


def _record(hard_setup, effects, onset=1e-3, seed=3):
    grain, sensor, law = hard_setup
    return realistic_record(
        grain,
        sensor,
        law,
        [2.0],
        [onset],
        length=4e-3,
        sample_rate=2e6,
        noise=NOISE,
        effects=effects,
        seed=seed,
    )


def _arrays(record):
    return np.asarray(record.trace.t), np.asarray(record.trace.values)


def _cases(effects):
    """Every effect 1 ms into the record and at its start."""
    return [
        pytest.param(effect, onset, id=f"{name}, {where}")
        for where, onset in ONSETS.items()
        for name, effect in effects.items()
    ]


@pytest.mark.parametrize(
    ("effects", "onset"), _cases({**EFFECTS, "crosstalk 2 %": Effects(crosstalk=0.02)})
)
def test_identify_sensor_reads_the_ringing_under_every_effect(hard_setup, effects, onset):
    _, sensor, _ = hard_setup
    found = identify_sensor(*_arrays(_record(hard_setup, effects, onset)))
    # the default window is 4 decay times (0.8 ms) of ringing at 1 % noise: measured over
    # two seeds f1 within 0.055 % and zeta within 1.9 % (drift, crosstalk and bounce
    # included; before, these three were refused); 0.2 % and 5 % leave a factor 2.5-4
    assert found.resonance == pytest.approx(sensor.resonance, rel=2e-3)
    assert found.damping_ratio == pytest.approx(sensor.damping_ratio, rel=0.05)
    # the structure's ringing is left in the residual (1.6-1.75 times the noise measured,
    # 0.94-0.98 without it): flagged, the rest not; 1/f noise leaves 1.1-1.2 times the
    # noise read on the sample differences, near the 1.3 limit, so it is not judged here
    if effects.pink == 0.0:
        crosstalk = effects.crosstalk > 0.0
        assert (found.status == "not free ringing") == crosstalk
        assert ("crosstalk" in " ".join(found.notes)) == crosstalk


@pytest.mark.parametrize(("effects", "onset"), _cases(EFFECTS))
def test_reconstruction_meets_the_targets_on_a_realistic_record(hard_setup, effects, onset):
    record = _record(hard_setup, effects, onset)
    truth = record.truth.iloc[0]
    rec = reconstruct_force(*_arrays(record), hard_setup[1])
    # the targets: 5 % where a contact holds at least 20 samples (here 200);
    # measured over four seeds at most 3.6 % (peak) and 2.4 % (contact time); before
    # the local baseline, drift of 20 sigma gave +103 % contact time
    assert rec.metrics.peak == pytest.approx(truth["peak_contact_force [N]"], rel=0.05)
    assert rec.metrics.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)
    flags = set(rec.status.split(", "))
    assert ("short pre-trigger" in flags) == (onset == 0.0)
    # a drift of 100 sigma over 4 ms moves the baseline by 4.5-6 noise sigmas across the
    # pulse (measured): said, although removed; 20 sigma moves it by about one
    if effects.drift >= 100 * NOISE and onset > 0.0:
        assert "drifting baseline" in flags
    assert "not free ringing" not in flags
    assert len(rec.notes) == len(flags - {"ok"})
    assert f"status={rec.status!r}" in repr(rec)  # what the command line prints


DRIFTS = {
    "line 20 sigma": (20 * NOISE, 1),
    "line 100 sigma": (100 * NOISE, 1),
    "quadratic 20 sigma": (20 * NOISE, 2),
    "quadratic 100 sigma": (100 * NOISE, 2),
}
"""Drifts added to a record that starts at its impact: their change over the 4 ms
record [N] and degree. The quadratic ``x (2 - x)`` (``x`` the time over the record's
length) starts twice as steep as the line and flattens, as a charge amplifier settles:
1500 N/s at 100 sigma, twice the realistic records' drift at its fastest."""


def _drifting_start(hard_setup, size, degree):
    """The record at its impact (white noise only), its arrays with the drift added, and
    the drift [N]."""
    record = _record(hard_setup, Effects(), onset=0.0)
    t, y = _arrays(record)
    x = (t - t[0]) / (t[-1] - t[0])
    drift = size * (x if degree == 1 else x * (2.0 - x))
    return record, t, y + drift, drift


@pytest.mark.parametrize(("size", "degree"), DRIFTS.values(), ids=DRIFTS.keys())
def test_the_four_commands_at_the_start_under_line_and_quadratic_drift(hard_setup, size, degree):
    grain, sensor, law = hard_setup
    record, t, y, drift = _drifting_start(hard_setup, size, degree)
    truth = record.truth.iloc[0]
    rec = reconstruct_force(t, y, sensor)
    # nothing before the impact: the baseline under it is the head level (a line or
    # quadratic fitted with the ringing after the contact), extrapolated back; the drift
    # is followed, so only the missing pre-trigger is said. Before (a constant after the
    # contact) the realistic drift of 100 sigma gave peak +11 % and contact time +86 %
    assert rec.status == "short pre-trigger"
    assert "extrapolated back" in rec.notes[0]
    # the baseline at the onset is the drift to a noise sigma (the extrapolation's
    # scatter, 0.1-0.3 sigma: tests/contactlab/inverse/test_head_baseline.py)
    assert rec.parameters["baseline [N]"] == pytest.approx(
        np.interp(rec.parameters["onset [s]"], t, drift), abs=NOISE
    )
    # the targets: 5 % where a contact holds at least 20 samples (here 200)
    assert rec.metrics.peak == pytest.approx(truth["peak_contact_force [N]"], rel=0.05)
    assert rec.metrics.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)
    # compare: the peak signal against the model's within the 2 %; the largest
    # sample near a noisy peak overshoots by up to 2-3 noise sigmas, so it is checked
    # against the same record without the drift as well: the drift adds under a sigma
    config = replace(load_config(ROOT / "data" / "traces" / "model_hard.toml"), law=law)
    result = compare_trace(record.trace.derive({"step": "drift"}, values=y), config)
    plain = compare_trace(record.trace, config)
    assert result.notes["baseline status"] == "short pre-trigger"
    row = result.table.set_index("quantity").loc["peak_sensor_force"]
    still = plain.table.set_index("quantity").loc["peak_sensor_force"]
    assert abs(row["rel_error"]) < 0.02
    assert abs(row["a"] - still["a"]) < NOISE
    # identify-sensor reads the ringing on a line: as under every effect above
    found = identify_sensor(t, y)
    assert found.resonance == pytest.approx(sensor.resonance, rel=2e-3)
    assert found.damping_ratio == pytest.approx(sensor.damping_ratio, rel=0.05)
    # fit: on the head level, its noise read after its window (before: refused); 1 % is
    # the campaign's figure for a linear fit at 1 % noise (docs/campaign.md)
    fit = fit_contact(t, y, grain, sensor, "linear", velocity=2.0)
    assert fit.baseline_status.startswith("short pre-trigger")
    assert fit.parameters["stiffness"].value == pytest.approx(law.stiffness, rel=0.01)
    assert fit.parameters["damping"].value == pytest.approx(law.damping, rel=0.01)


@pytest.mark.parametrize("onset", ONSETS.values(), ids=ONSETS.keys())
def test_reconstruction_removes_the_structure_s_crosstalk(hard_setup, onset):
    record = _record(hard_setup, Effects(crosstalk=0.02), onset)
    truth = record.truth.iloc[0]
    rec = reconstruct_force(*_arrays(record), hard_setup[1])
    # the 5 % target, reached: the modes found on the impact's own ringing and
    # their response to the pulse removed, measured over two seeds peak +0.8 to +2.2 %,
    # contact time -0.9 to +0.5 % (without the removal +4.1 % and +25 % at 1 ms, +2.5 %
    # and +15 % at the start, over four seeds); seed 3 with the contact's edges read
    # where the force is significant (contact_edges): contact time +0.1 % and +2.2 %
    assert rec.metrics.peak == pytest.approx(truth["peak_contact_force [N]"], rel=0.05)
    assert rec.metrics.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)
    assert "not free ringing" not in rec.status
    # the modes removed are named: the plate's 1890 Hz mode (2 % tolerance: the pencil's
    # frequency on 2 ms of ringing, +-0.5 % measured)
    removed = [note for note in rec.notes if note.startswith("structural crosstalk removed")]
    assert len(removed) == 1 and " Hz (zeta " in removed[0]
    found = [float(part.split(" Hz")[0]) for part in removed[0].split(": ", 1)[1].split("; ")]
    assert any(abs(f / 1890.0 - 1.0) < 0.02 for f in found), found
    # kept on request, the same record is flagged, with the numbers. 1 ms in, the
    # crosstalk held the reconstructed force above 2 % of its peak after the contact
    # (contact time +12 % to +25 %); the contact then ended at the force's first dip under
    # 5 % of its peak (contact_edges.DIP_FRACTION): +4.0 to +4.4 % measured; the edges
    # read where the force is significant above its noise: +2.0 to +3.7 % (seed 3)
    kept = reconstruct_force(*_arrays(record), hard_setup[1], crosstalk=False)
    assert "not free ringing" in kept.status
    assert any("crosstalk" in note and "times" in note for note in kept.notes)
    assert kept.metrics.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)


def test_reconstruction_says_when_no_structure_mode_explains_the_ringing(hard_setup):
    record = _record(hard_setup, Effects())
    t, y = _arrays(record)
    # a 12 kHz ringing (above a quarter of the 40 kHz sensor resonance, where modes are
    # not sought) after the contact: not free ringing, and nothing removed
    y = y + np.where(t > 1.3e-3, 0.06 * np.sin(2 * np.pi * 12e3 * t), 0.0)
    rec = reconstruct_force(t, y, hard_setup[1])
    assert rec.status == "not free ringing, no structure mode"
    assert "nothing removed" in rec.notes[-1]


@pytest.mark.parametrize("onset", ONSETS.values(), ids=ONSETS.keys())
def test_reconstruction_under_1_over_f_noise_as_large_as_the_white(hard_setup, onset):
    record = _record(hard_setup, Effects(pink=NOISE), onset)
    truth = record.truth.iloc[0]
    rec = reconstruct_force(*_arrays(record), hard_setup[1])
    # the 5 % target. 1 ms in, seed 3 was +7.0 % (a strict xfail) while GCV
    # assumed white noise; the noise's AR model read on the baseline window whitens the
    # problem: +0.6 % (contact time +3.2 %; seeds 3-6 at most +2.3 % and +3.2 %). At the
    # start it is read after the contact, on what the free ringing leaves: +2.0 % (white
    # model +3.0 %; seeds 0-6 at most 2.0 % and 1.6 %, docs/campaign.md)
    assert rec.parameters["noise_model"].startswith("AR(")
    assert rec.metrics.peak == pytest.approx(truth["peak_contact_force [N]"], rel=0.05)
    assert rec.metrics.duration == pytest.approx(truth["contact_time [s]"], rel=0.05)
    if onset > 0.0:
        # with the white model the same record gives the old +7.0 %: what the whitening
        # buys (over 5 % shows it)
        white = reconstruct_force(*_arrays(record), hard_setup[1], noise_model="white")
        assert white.metrics.peak > 1.05 * truth["peak_contact_force [N]"]


def test_compare_removes_a_drifting_baseline(hard_setup):
    law = hard_setup[2]
    config = replace(load_config(ROOT / "data" / "traces" / "model_hard.toml"), law=law)
    record = _record(hard_setup, Effects(drift=100 * NOISE))
    result = compare_trace(record.trace, config)
    assert result.notes["baseline status"] == "drifting baseline"
    assert "noise sigmas" in result.notes["baseline note 1"]
    row = result.table.set_index("quantity").loc["peak_sensor_force"]
    # the largest sample near a noisy peak overshoots by 2-3 noise sigmas (2-3 %): the
    # tolerance compare_trace gives a measured trace (1 % + 4 sigma / peak = 5 %) holds;
    # a constant baseline from the quietest stretch was off by up to the drift, 3 N
    assert row["passed"], row
    assert "baseline status: drifting baseline" in str(result)


def test_fit_recovers_the_law_under_drift(hard_setup):
    grain, sensor, law = hard_setup
    record = _record(hard_setup, Effects(drift=100 * NOISE))
    fit = fit_contact(*_arrays(record), grain, sensor, "linear", velocity=2.0)
    # measured 0.10 % (stiffness) and 0.33 % (damping), as without drift: the fit runs
    # on the record less the local line, up to the end of its post-contact window; 1 %
    # is the campaign's figure for a linear fit at 1 % noise (docs/campaign.md)
    assert fit.parameters["stiffness"].value == pytest.approx(law.stiffness, rel=0.01)
    assert fit.parameters["damping"].value == pytest.approx(law.damping, rel=0.01)
    assert fit.baseline_status == "drifting baseline"  # 4.5-6 noise sigmas (measured)
    assert "baseline: drifting baseline" in fit.summary()
    assert fit.to_dict()["baseline_notes"] == list(fit.baseline_notes)
    # the residuals are noise: chi-squared near 1 (0.95 measured; the noise is read on
    # 400 samples, its square known to 7 %: 0.8-1.2 is about three of those)
    assert 0.8 < fit.goodness["reduced_chi_squared [-]"] < 1.2


START_EFFECTS = {
    "drift 20 sigma": (Effects(drift=20 * NOISE), 0.01),
    "drift 100 sigma": (Effects(drift=100 * NOISE), 0.01),
    "crosstalk 2 %": (Effects(crosstalk=0.02), 0.01),
    "1/f 1 sigma": (Effects(pink=NOISE), 0.03),
}
"""Records that start at their pulse, for the fit, and the tolerance on k2 and c2 [-]:
1 % is the campaign's figure for a linear fit at 1 % noise (docs/campaign.md); measured
on seeds 3-6 (``benchmarks/bench_fit_start.py``) within 0.46 % (drift), 0.62 %
(crosstalk) and 3.0 % (1/f noise as large as the white noise; 1.5 % with a
pre-trigger), 0.34 %, 0.62 % and 2.1 % on the seed tested."""


@pytest.mark.parametrize(("effects", "tolerance"), START_EFFECTS.values(), ids=START_EFFECTS.keys())
def test_fit_recovers_the_law_on_a_record_that_starts_at_the_pulse(hard_setup, effects, tolerance):
    """No pre-trigger: the head level is the baseline and the noise the fit is judged
    against is read after its window, on what a line and the free ringing leave."""
    grain, sensor, law = hard_setup
    t, y = _arrays(_record(hard_setup, effects, onset=0.0))
    if effects.pink:  # judged against noise read after the fit: coloured, as it is
        with pytest.warns(FitQualityWarning, match="the noise itself is coloured"):
            fit = fit_contact(t, y, grain, sensor, "linear", velocity=2.0)
    else:
        fit = fit_contact(t, y, grain, sensor, "linear", velocity=2.0)
    assert fit.parameters["stiffness"].value == pytest.approx(law.stiffness, rel=tolerance)
    assert fit.parameters["damping"].value == pytest.approx(law.damping, rel=tolerance)
    assert fit.baseline_status.startswith("short pre-trigger")
    # the noise window follows the fit's window (the post-contact window's end)
    assert fit.quality.noise_window[0] >= fit.t[-1]
    # chi-squared against noise read on other samples: near 1 (measured 1.03-1.12 on
    # this seed; 800 noise samples, its square known to 5 %: 0.8-1.25 is about four
    # of those)
    assert 0.8 < fit.goodness["reduced_chi_squared [-]"] < 1.25


def test_fit_says_why_not_on_a_record_that_ends_after_its_pulse(hard_setup):
    """No pre-trigger and no samples after the fit's window: no noise to judge it on."""
    grain, sensor, _ = hard_setup
    t, y = _arrays(_record(hard_setup, Effects(), onset=0.0))
    # the post-contact window ends 0.586-0.589 ms after the touch (measured): 5 us more
    # leave 9-15 samples after it (20 needed: 16 and the ringing fit's four)
    keep = t <= 0.593e-3
    with pytest.raises(ParameterError, match="record a pre-trigger or a longer tail"):
        fit_contact(t[keep], y[keep], grain, sensor, "linear", velocity=2.0)


@pytest.mark.parametrize("seed", [1, 2])
def test_a_1_over_f_noise_pole_is_not_removed_as_a_mode(hard_setup, seed):
    from contactlab.inverse.crosstalk import structure_modes

    record = _record(hard_setup, Effects(pink=NOISE), seed=seed)
    t, y = _arrays(record)
    sensor = hard_setup[1]
    after, before = (t >= 1.25e-3) & (t <= 4e-3), t < 0.95e-3
    # without crosstalk, 1/f noise as large as the white noise: on seed 1 the pencil's
    # pole at 2090 Hz passes the white-noise test on the ringing after the contact...
    if seed == 1:
        alone = structure_modes(t[after], y[after], sensor)
        assert any(500.0 < f < 2500.0 for f, _ in alone), alone
    # ...and not the test against the pre-trigger's noise in the band (its
    # autocovariance), which the single-trace path applies; the reconstruction removed a
    # 2090 Hz (seed 1) and a 609 Hz (seed 2) "mode" without it (measured), none now
    assert structure_modes(t[after], y[after], sensor, noise=(t[before], y[before])) == []
    rec = reconstruct_force(t, y, sensor)
    assert not any(note.startswith("structural crosstalk removed") for note in rec.notes)
