"""Peak signal and impulse read by the campaign on a record built without the toolkit's
forward model or noise generator: a half-sine contact force passed through the sensor's
transfer function by ``scipy.signal.lsim``, with white and 1/f noise (random phases),
a drifting baseline and mains hum drawn here. The truth is exact: the impulse of a
half-sine ``F0 sin(pi t / T)`` is ``2 F0 T / pi``, the peak signal the largest value of
``lsim``'s output on a grid 16 times finer than the record's."""

import math

import numpy as np
import pytest
from pink_noise import pink_by_phases
from scipy.signal import lsim

from contactlab.traces import Trace
from dem_check.campaign import find_impacts
from dem_check.campaign.analysis import analyse_impact

RATE = 2e6
"""Sample rate of the record [Hz] (200 samples per contact)."""

CONTACT = 1e-4
"""Half-sine duration [s] (the hard grain's contact time)."""

NOISE = 0.02
"""White noise and 1/f noise standard deviations, each [N]."""

SIGNIFICANCE = 100.0
"""Peak signal over ``sqrt(2) NOISE`` [-]."""


def _sensor_signal(sensor, dt, count):
    """The sensor's signal for a unit half-sine force starting at sample 0, on ``count``
    samples of ``dt`` [s] (transfer function ``(c1 s + k1) / (m1 s**2 + c1 s + k1)``)."""
    t = np.arange(count) * dt
    force = np.where(t < CONTACT, np.sin(math.pi * t / CONTACT), 0.0)
    system = ([sensor.damping, sensor.stiffness], [sensor.mass, sensor.damping, sensor.stiffness])
    return lsim(system, force, t)[1]


def _errors(sensor, seed):
    """Relative errors of the peak signal and impulse read on one record."""
    fine = 16
    dt = 1.0 / RATE
    unit = _sensor_signal(sensor, dt / fine, round(2e-3 * RATE) * fine)
    amplitude = SIGNIFICANCE * math.sqrt(2.0) * NOISE / unit.max()
    rng = np.random.default_rng(seed)
    count = round(8e-3 * RATE)
    t = np.arange(count) * dt
    onset = 3e-3 + rng.integers(0, fine) * dt / fine  # anywhere between two samples
    first = math.ceil(onset / dt)
    clean = np.zeros(count)
    shift = round((first * dt - onset) / (dt / fine))
    clean[first : first + unit[shift::fine].size] = amplitude * unit[shift::fine]
    baseline = 0.3 + 60.0 * NOISE * t / t[-1] + 1.5 * NOISE * np.sin(2 * math.pi * 50.0 * t + 1.0)
    noise = rng.normal(0.0, NOISE, count) + pink_by_phases(rng, count, NOISE)
    trace = Trace(t, clean + baseline + noise, "N", {"format": "synthetic"})
    detection = find_impacts(trace, sensor)
    ok = [w for w in detection.impacts if w.status == "ok"]
    assert len(detection.impacts) == 1 and len(ok) == 1
    row, _ = analyse_impact(detection, ok[0], sensor, crosstalk=False)
    exact_impulse = 2.0 * amplitude * CONTACT / math.pi
    return (
        row["peak_sensor_force [N]"] / (amplitude * unit.max()) - 1.0,
        row["impulse [N*s]"] / exact_impulse - 1.0,
    )


def test_lsim_reference_is_exact_on_a_rigid_limit(hard_setup):
    """The reference itself: its impulse (the signal's integral once the sensor is at
    rest) is the half-sine's ``2 T / pi`` (the transfer function's gain at 0 is 1)."""
    _, sensor, _ = hard_setup
    dt = 1.0 / (16 * RATE)
    signal = _sensor_signal(sensor, dt, round(2e-3 / dt))  # 2 ms: ringing down to 4e-5
    # trapezoid at 31 ns on a signal ringing at 40 kHz, and the 2 ms cut: measured 8e-7
    assert np.trapezoid(signal, dx=dt) == pytest.approx(2.0 * CONTACT / math.pi, rel=1e-4)


def test_peak_and_impulse_of_a_half_sine_under_coloured_noise(hard_setup):
    """Six records at a significance of 100, 1/f noise as large as the white noise: each
    peak signal and impulse within 4 standard deviations of what the campaign's readers
    scatter there, and no bias beyond what six draws allow."""
    _, sensor, _ = hard_setup
    errors = np.array([_errors(sensor, seed) for seed in range(6)])
    peak, impulse = errors[:, 0], errors[:, 1]
    # bench_realistic at 2 MHz, 1/f as large as the white noise: rms 2.06 % (peak) and
    # 2.86 % (impulse) at 30 sigma, i.e. 0.62 % and 0.86 % at 100; 4 of those (measured
    # here: at most 1.06 % and 0.87 % with the noise under the pulse predicted, 1.1 %
    # and 0.9 % with the ordinary line)
    assert np.abs(peak).max() < 0.025
    assert np.abs(impulse).max() < 0.034
    # a bias (e.g. the peak read on a noise maximum, or a tail lost) beyond 3 standard
    # errors of the mean of six (measured +0.32 % and +0.23 %; +0.34 % and +0.33 % with
    # the ordinary line)
    assert abs(peak.mean()) < 3.0 * 0.0062 / math.sqrt(6.0)
    assert abs(impulse.mean()) < 3.0 * 0.0086 / math.sqrt(6.0)
