"""The structure's modes of a record with weak crosstalk (issue 22, session 17, helper
xtmodes): ``bench_realistic.py --accuracy --law hertz``, "2 MHz, crosstalk 2 %", seed 3,
whose impacts are the configuration's weakest (peaks 0.18-1.43 N, so the plate's modes
ring at 0.005-0.03 N under white and 1/f noise of 0.03 N each). ``record_modes`` found no
mode there: the joint pencil's 1903 Hz pole (damping 0.035) and a 2850 Hz noise pole
(damping 0.097) were both held at the largest damping ratio by their refinement and
dropped together (``contactlab.inverse.ringdown.refine_unheld``)."""

import numpy as np

import contactlab as cl
from dem_check.campaign import find_impacts
from dem_check.campaign.analysis import read_impact
from dem_check.campaign.drawn_records import accuracy_record
from dem_check.campaign.local import record_noise
from dem_check.campaign.structure import FREQUENCY_TOLERANCE, record_modes

RATE = 2e6  # [Hz]
HERTZ = cl.laws.Hertz(k_hertz=1.5e6)  # bench_realistic.py's HERTZ


def test_the_plate_s_1890_hz_mode_is_found_and_the_impact_read(hard_setup):
    """The plate's 1890 Hz mode is found (1841 Hz, damping 0.022), and the 16.5 sigma
    impact at 18.12 ms, ``reconstruction failed`` without it (its contact did not end in
    its window, ``test_segment_lobe.py``), is read within the issue's targets. The
    730 and 4100 Hz modes are not found: fitted with their true poles, their shared
    coupling to the impacts is 4.9 and 3.8 standard errors, under the 5 of
    ``crosstalk.SIGNIFICANCE`` (``docs/campaign.md``)."""
    grain, sensor, _ = hard_setup
    record = accuracy_record(3, grain, sensor, HERTZ, RATE, crosstalk=0.02)
    found = find_impacts(record.trace, sensor)
    noise = record_noise(found, sensor)
    modes = record_modes(found, sensor, noise=noise)
    # one mode, within the tolerance after which the campaign pools poles of one mode
    # (1841 Hz: -2.6 % of the plate's 1890 Hz, read on 3-8 periods under 1/f noise)
    assert len(modes) == 1, modes
    assert abs(modes[0][0] / 1890.0 - 1.0) < FREQUENCY_TOLERANCE, modes
    truth = record.truth.iloc[int(np.argmin(np.abs(record.truth["onset [s]"] - 18.12e-3)))]
    (window,) = [w for w in found.impacts if abs(w.onset - truth["onset [s]"]) < 60e-6]
    row, _, _ = read_impact(found, window, sensor, grain, modes=modes, noise=noise)
    assert row["status"] == "ok", row["reason"]
    # the 5 % targets for the impulse, the reconstructed peak and the contact
    # time; bench_bounds.py --law hertz: a reader at the bound meets them from 16, 15 and
    # 6 sigma at 2 MHz (this impact: 16.5)
    for column in ("impulse", "peak_contact_force", "contact_time"):
        unit = {"impulse": "[N*s]", "contact_time": "[s]"}.get(column, "[N]")
        error = row[f"{column} {unit}"] / truth[f"{column} {unit}"] - 1.0
        assert abs(error) < 0.05, (column, error)


def test_the_same_record_without_crosstalk_has_no_mode(hard_setup):
    """The same draws with the crosstalk off ("2 MHz" of the benchmark, seed 3): the
    dropping order that finds the 1890 Hz mode above keeps none here."""
    grain, sensor, _ = hard_setup
    record = accuracy_record(3, grain, sensor, HERTZ, RATE, crosstalk=0.0)
    found = find_impacts(record.trace, sensor)
    assert record_modes(found, sensor, noise=record_noise(found, sensor)) == []
