"""The campaign's crosstalk removal (``dem_check.campaign.structure.impact_crosstalk``)
against the record model's crosstalk (``dem_check.campaign.records``), through the pulse.

Both now model the plate's ringing as the response to the force on it (issue 22,
reconpeak): the removal convolves the measured pulse with each mode's damped cosine and
sine, the record model drives each mode with the impact's clean force. Before, the
record model rang at full amplitude from the touch, and under the pulse the removal
left up to 1.4 % of the peak (5 MHz, docs/campaign.md, "The reconstructed peaks that
miss 5 %, traced"). The modes given are the model's (the identification is tested in
``tests/contactlab/inverse/test_crosstalk.py``).
"""

import numpy as np
import pytest

from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.analysis import analyse_impact
from dem_check.campaign.drawn_records import NOISE as BENCH_NOISE
from dem_check.campaign.drawn_records import accuracy_record
from dem_check.campaign.local import record_noise
from dem_check.campaign.structure import impact_crosstalk, record_modes

NOISE = 0.003  # [N]: 0.1 % of the 3 N peak, so that the removal's model, not the noise, is read


@pytest.mark.parametrize("rate", [1e6, 5e6])
def test_the_removal_takes_the_model_s_crosstalk_out_through_the_pulse(hard_setup, rate):
    grain, sensor, law = hard_setup
    common = {"length": 9e-3, "sample_rate": rate, "noise": NOISE, "seed": 1}
    effects = Effects(crosstalk=0.02)
    record = realistic_record(grain, sensor, law, [2.0], [3e-3], **common, effects=effects)
    # the same draws without the crosstalk (it is drawn last): their difference is it
    plain = realistic_record(grain, sensor, law, [2.0], [3e-3], **common)
    ringing = np.asarray(record.trace.values) - np.asarray(plain.trace.values)
    truth = record.truth.iloc[0]
    found = find_impacts(record.trace, sensor)
    (window,) = found.impacts
    onset = float(truth["onset [s]"])
    contact_end = onset + 1.5 * float(truth["contact_time [s]"])  # past the first lobe
    part = slice(window.first, window.stop)
    removed = impact_crosstalk(found, window, sensor, contact_end, part, list(effects.plate_modes))
    t = np.asarray(record.trace.t)[part]
    pulse = (t >= onset) & (t <= contact_end)
    residual = np.max(np.abs(removed.values - ringing[part])[pulse])
    peak = float(truth["peak_sensor_force [N]"])
    # the crosstalk is 2 % of the peak, 1.4 % of it was left before; what remains is the
    # noise of the fitted amplitudes and of the pulse read as the force (0.1 % of the
    # peak on each sample) and the modes' own ringing inside that read force (2 % of
    # 2 %): 0.2 % of the peak bounds both
    assert residual < 0.002 * peak, residual / peak
    assert len(removed.modes) >= 2  # the 1890 and 4100 Hz modes are significant here


def test_a_mode_the_pencil_reads_overdamped_is_refined_and_kept(hard_setup):
    # benchmarks/bench_realistic.py's record of seed 3 at 1 MHz with 1/f noise of 0.3
    # sigma and 2 % crosstalk: the joint pencil read the plate's 730 Hz mode (damping
    # 0.01) at 719 Hz, damping 0.061, over MAX_DAMPING, and the record lost the mode
    # (its impulse +5.7 % on a 30 sigma impact); START_DAMPING lets it start the
    # refinement, which brings it to 727 Hz, damping 0.037
    grain, sensor, law = hard_setup
    record = accuracy_record(3, grain, sensor, law, 1e6, crosstalk=0.02, pink=0.3 * BENCH_NOISE)
    modes = record_modes(find_impacts(record.trace, sensor), sensor)
    # every plate mode found, each within 2 % (measured 727, 1887 and 4097 Hz: the
    # 1/f noise on windows of one to three periods of the 730 Hz mode)
    for frequency, _ in Effects().plate_modes:  # the record model's, as drawn
        assert any(abs(f / frequency - 1.0) < 0.02 for f, _ in modes), modes


def test_a_mode_the_weaker_impacts_ring_under_the_noise_is_kept_and_the_impulse_holds(
    hard_setup,
):
    # benchmarks/bench_realistic.py's record of seed 2 at 2 MHz with 2 % crosstalk (1/f
    # noise as large as the white noise): the joint pencil's 4053 Hz pole was significant
    # after 2 of 8 windows, so the record kept 1987 Hz alone, and the plate's 4100 Hz
    # mode, left in, read the 33.5 sigma impact at 13.1 ms +5.12 % (the target: 5
    # %). Its coupling to every impact, shared by the windows, is 8.4 standard errors
    # under the record's noise (contactlab.inverse.crosstalk_driven)
    grain, sensor, law = hard_setup
    record = accuracy_record(2, grain, sensor, law, 2e6, crosstalk=0.02)
    found = find_impacts(record.trace, sensor)
    noise = record_noise(found, sensor)
    modes = record_modes(found, sensor, noise=noise)
    # the pencil's 4053 Hz for the model's 4100 Hz: within 2 % (1/f noise on windows of
    # 5-16 periods)
    assert any(abs(f / 4100.0 - 1.0) < 0.02 for f, _ in modes), modes
    truth = record.truth.iloc[int(np.argmin(np.abs(record.truth["onset [s]"] - 13.1e-3)))]
    (window,) = [w for w in found.impacts if abs(w.onset - truth["onset [s]"]) < 60e-6]
    row, _ = analyse_impact(found, window, sensor, grain, modes=modes, noise=noise)
    error = row["impulse [N*s]"] / truth["impulse [N*s]"] - 1.0
    # within the 5 %: the impulse's bound at 33.5 sigma is 1.9 % rms with 1/f
    # noise as large as the white noise (bench_bounds.py), and the same impact without
    # crosstalk reads +2.9 %, with the model's three modes removed +3.3 %
    assert abs(error) < 0.05, error
