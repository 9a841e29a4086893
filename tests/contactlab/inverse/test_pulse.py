"""The pulse's local baseline on a single trace (contactlab.inverse.pulse): a known line
under an impact of the forward model is found, and the status says what it saw."""

import numpy as np
import pytest

import contactlab as cl
from contactlab.inverse import synthetic_trace
from contactlab.inverse.pulse import DRIFT_SIGMAS, pulse_baseline

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
GRAIN = cl.Grain(diameter=5e-3, density=765.0)
LAW = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)


def _trace(pre_trigger=200e-6, noise=0.002):
    return synthetic_trace(
        GRAIN, SENSOR, LAW, 2.0, duration=800e-6, pre_trigger=pre_trigger, noise=noise
    )


@pytest.mark.parametrize("slope", [0.0, 300.0, -2000.0], ids=["flat", "slow", "fast"])
def test_the_line_under_the_pulse_is_the_drift(slope):
    """A drift ``0.1 + slope t`` [N] added to an impact: the fitted baseline is that line
    wherever it was fitted, and it is flagged when it moves by more than the noise."""
    t, signal, _ = _trace()
    drift = 0.1 + slope * t
    found = pulse_baseline(t, signal + drift, SENSOR)
    fitted = (t >= found.window[0]) & (t <= found.post[1])
    # 0.2 % noise (of the 5.6 N peak: 0.011 N) on 1000 baseline and 2000 ringing
    # samples: measured 6.7e-4 N at most over the fitted span; 2e-3 N is 3 times that
    np.testing.assert_allclose(found.values[fitted], drift[fitted], atol=2e-3)
    # the change across the pulse (contact window to the ringing) is the slope's
    span = found.post[0] - found.contact[0]
    assert found.drift == pytest.approx(slope * span, abs=2e-3)  # measured 1e-4 N off
    drifting = abs(slope * span) > DRIFT_SIGMAS * found.noise
    assert ("drifting baseline" in found.status) == drifting
    assert slope == 0.0 or drifting  # 300 N/s over ~110 us: 0.032 N, 2.9 noise sigmas


def test_a_record_without_samples_before_zero_finds_its_pulse():
    """The same impact with its time axis starting at 0 (no samples before t = 0): the
    pulse is found on the running baseline and the baseline window lies before it."""
    t, signal, _ = _trace()
    shifted = t - t[0]
    found = pulse_baseline(shifted, signal + 0.3, SENSOR)
    touch = -t[0]  # the first touch on the shifted axis
    assert found.window[1] <= touch  # the baseline window holds no force
    # the onset is the 5-sigma crossing: measured 0.87 us after the touch (the sensor's
    # rise to 5 sigma); 2 us allows the noise's scatter of the crossing
    assert touch <= found.onset < touch + 2e-6
    # the offset is removed to the noise's standard error over ~1000 samples (measured
    # 5e-4 N off)
    assert np.interp(touch, shifted, found.values) == pytest.approx(0.3, abs=2e-3)
    assert found.status == "ok" and found.notes == ()


def test_structural_ringing_after_the_contact_is_named():
    """A 4.1 kHz mode (a plate's) ringing after the hit at 3 % of the peak: the sensor's
    free ringing does not explain the post-contact window."""
    t, signal, _ = _trace()
    after = t > 0.0
    mode = np.where(after, 0.03 * 5.6 * np.sin(2 * np.pi * 4100.0 * t), 0.0)
    found = pulse_baseline(t, signal + mode, SENSOR)
    assert "not free ringing" in found.status
    assert any("crosstalk" in note for note in found.notes)
