"""Accuracy of the analysed impacts on realistic records (issue 22), where it is reachable.

One 2 MHz record of the hard grain (contact 100 us: 200 samples per contact) with drift of
20 noise sigmas, hum of 1.5 sigma, 1/f noise of 0.3 sigma and bounces at 40 % of the
velocity 2 ms later (``Effects.everything`` without crosstalk, clipping and offset steps;
``docs/campaign.md`` gives the measured envelope for the others). The issue's targets are
asserted where ``benchmarks/bench_realistic.py --accuracy`` measured them to hold:

- every target (onset within 2 samples, peak signal within 2 %, impulse within 5 %,
  reconstructed peak and contact time within 5 %) from a significance (peak over random
  noise) of :data:`ALL_TARGETS`;
- impulse, reconstructed peak and contact time within 5 % from :data:`FORCE_TARGETS`.

The truth is the forward model's (the exact first touch and the noise-free numbers), so
this checks that the analysis undoes the laboratory effects, not the model itself.
"""

import numpy as np
import pytest
from four_impacts import NOISE, four_impact_record

from contactlab.inverse.contact_edges import family_flanks
from dem_check.campaign import Effects, find_impacts
from dem_check.campaign.analysis import analyse_impact
from dem_check.campaign.structure import record_modes

RATE = 2e6
"""Sample rate [Hz]."""

ALL_TARGETS = 100.0
"""Significance from which every target holds [-] (measured: onsets within 1.1 samples,
peak signal 0.7 %, impulse 0.5 %, reconstructed peak 1.1 %, contact time 2.5 %)."""

FORCE_TARGETS = 30.0
"""Significance from which impulse, reconstructed peak and contact time hold [-]
(measured at 30-100: 3.5 %, 3.0 %, 4.2 %; the peak signal reaches 2.2 % and the onset 4.6
samples there; with the local baseline read up to the onset, impulse 2.0 % and peak
signal 1.6 %, which the bound allows only from 35 sigma: docs/campaign.md, "What
accuracy is possible")."""


def _record(hard_setup, crosstalk):
    grain, sensor, law = hard_setup
    effects = Effects.everything(
        NOISE, 3.0, pink=0.3 * NOISE, crosstalk=crosstalk, full_scale=None, steps=0
    )
    return four_impact_record(
        grain, sensor, law, [2.5, 1.0, 2.2, 1.6], effects, sample_rate=RATE, seed=11
    )


@pytest.fixture(scope="module")
def analysed(hard_setup):
    grain, sensor, _ = hard_setup
    record = _record(hard_setup, 0.0)
    found = find_impacts(record.trace, sensor)
    rows = []
    for window in found.impacts:
        row, _ = analyse_impact(found, window, sensor, grain)
        gap = np.abs(record.truth["onset [s]"] - window.onset)
        rows.append((row, record.truth.iloc[int(gap.argmin())]))
    return rows, record, found.contact_family


def test_the_records_contact_family_has_the_grains_flanks(analysed, hard_setup):
    # the onset fit's family, which the reconstruction reads its edges with, against the
    # hard grain's linear spring-dashpot (zeta = c2 / (2 sqrt(k2 m)) = 0.177): its force
    # jumps at the touch and leaves at a finite slope. On this record the onset fit reads
    # Hertz with Tsuji's damping 0.34 (measured; the families' rigid-wall shapes are
    # near each other once damped), whose flanks are the same kind: the start at half a
    # jump of 41 % of the peak (the grain's: 48 %, both read 2 % of the contact after
    # the touch), the end a line
    grain, _, law = hard_setup
    zeta = law.damping / (2.0 * np.sqrt(law.stiffness * grain.mass))
    read = family_flanks(*analysed[2])
    grains = family_flanks("linear", zeta)
    assert read["end_exponent"] == grains["end_exponent"] == 1.0
    # 0.1 of the peak: half of it moves the start by a twentieth of the rounded jump's
    # rise (a few grid steps), under 0.2 us (0.2 % of the contact)
    assert read["step"] == pytest.approx(grains["step"], abs=0.1), (analysed[2], read, grains)


def test_every_impact_and_bounce_is_analysed(analysed):
    rows, record, _ = analysed
    assert len(rows) == len(record.truth) == 8  # four impacts, four bounces
    assert [row["status"] for row, _ in rows] == ["ok"] * 8


def _errors(row, true):
    def relative(column):
        return abs(row[column] / true[column] - 1.0)

    return {
        "onset": abs(row["onset [s]"] - true["onset [s]"]) * RATE,
        "peak_signal": relative("peak_sensor_force [N]"),
        "impulse": relative("impulse [N*s]"),
        "peak_force": relative("peak_contact_force [N]"),
        "contact_time": relative("contact_time [s]"),
    }


def test_the_issues_targets_where_the_signal_is_strong(analysed):
    rows, record, _ = analysed
    strong = [(r, t) for r, t in rows if t["peak_sensor_force [N]"] >= ALL_TARGETS * record.noise]
    assert len(strong) == 2  # 2.5 and 2.2 m/s
    for row, true in strong:
        errors = _errors(row, true)
        assert errors["onset"] <= 2.0, errors  # the issue's targets, not loosened
        assert errors["peak_signal"] <= 0.02, errors
        assert errors["impulse"] <= 0.05, errors
        assert errors["peak_force"] <= 0.05, errors
        assert errors["contact_time"] <= 0.05, errors


def test_impulse_and_force_from_thirty_sigma(analysed):
    rows, record, _ = analysed
    clear = [(r, t) for r, t in rows if t["peak_sensor_force [N]"] >= FORCE_TARGETS * record.noise]
    assert len(clear) >= 5  # the four impacts and the strongest bounces
    for row, true in clear:
        errors = _errors(row, true)
        assert errors["impulse"] <= 0.05, errors  # the issue's targets, not loosened
        assert errors["peak_force"] <= 0.05, errors
        assert errors["contact_time"] <= 0.05, errors


@pytest.fixture(scope="module")
def with_crosstalk(hard_setup):
    """The same record with crosstalk of 2 % of each peak (the structure's three modes),
    analysed with and without its removal."""
    grain, sensor, _ = hard_setup
    record = _record(hard_setup, 0.02)
    found = find_impacts(record.trace, sensor)
    modes = record_modes(found, sensor)
    rows = {True: [], False: []}
    for window in found.impacts:
        gap = np.abs(record.truth["onset [s]"] - window.onset)
        true = record.truth.iloc[int(gap.argmin())]
        for removed in rows:
            row, _ = analyse_impact(found, window, sensor, grain, crosstalk=removed, modes=modes)
            rows[removed].append((row, true))
    return rows, record, modes


def test_crosstalk_is_removed_to_the_issues_targets_from_thirty_sigma(with_crosstalk):
    rows, record, modes = with_crosstalk
    # the structure's 1890 and 4100 Hz modes are found on the record (the 730 Hz mode,
    # 1.4 ms a period, rings too slowly for the 2 ms between an impact and its bounce)
    assert any(abs(f / 4100.0 - 1.0) < 0.02 for f, _ in modes), modes
    clear = [
        (r, t) for r, t in rows[True] if t["peak_sensor_force [N]"] >= FORCE_TARGETS * record.noise
    ]
    assert len(clear) >= 5
    for row, true in clear:
        assert row["status"] == "ok" and row["crosstalk [N]"] > 0.0, row
        errors = _errors(row, true)
        assert errors["impulse"] <= 0.05, errors  # the issue's targets, not loosened
        assert errors["peak_force"] <= 0.05, errors
        assert errors["contact_time"] <= 0.05, errors
    # without the removal the targets are not all met, so the test above is not
    # trivial: peak signal up to 3.7 % (target 2 %), impulse 5.0 %, contact time 4.1 %
    # here (6.1 % while the contact was read at 2 % of the peak). The crosstalk holds the
    # reconstructed force up after the contact (the benchmark measured contact times up
    # to +100 %); the dip rule (contact_edges.DIP_FRACTION) and now the significance
    # rule (docs/campaign.md, "Contact edges") cut most of that (19.7 % here before)
    kept = [_errors(r, t) for r, t in rows[False] if r["status"] == "ok"]
    assert max(e["peak_signal"] for e in kept) > 0.02, kept
