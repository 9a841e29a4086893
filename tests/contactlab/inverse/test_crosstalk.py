"""Structural crosstalk (contactlab.inverse.crosstalk) against signals built here from
closed forms: damped sinusoids, a half-sine pulse and its exact convolution."""

import math

import numpy as np
import pytest
from plate_windows import PLATE, SENSOR, damped, mode_error, plate_windows

from contactlab.errors import ParameterError
from contactlab.inverse.crosstalk import fit_crosstalk, joint_structure_modes, structure_modes

RATE = 2e6
MODES = [(1890.0, 0.02), (4100.0, 0.015)]


def test_structure_modes_finds_the_modes_beside_the_sensors_ringing():
    t = np.arange(round(4e-3 * RATE)) / RATE
    rng = np.random.default_rng(1)
    sensor_ringing = 2.0 * damped(t + 1e-4, SENSOR.resonance, SENSOR.damping_ratio)
    modes = sum(0.05 * damped(t + 3e-4, f, z) for f, z in MODES)
    y = sensor_ringing + modes + 0.3 + 5.0 * t + rng.normal(0.0, 0.01, t.size)
    found = structure_modes(t, y, SENSOR)
    for frequency, zeta in MODES:
        near = [(f, z) for f, z in found if abs(f / frequency - 1.0) < 0.01]
        # 4 ms holds 7.6 and 16 periods at 20 noise sigmas: the pencil's frequency to
        # 1 %, the damping ratio (a decay over a few periods) to 25 %
        assert near, found
        assert near[0][1] == pytest.approx(zeta, rel=0.25)


def test_a_window_too_short_for_the_pencil_is_refused():
    t = np.arange(200) / RATE
    with pytest.raises(ParameterError, match="too short"):
        structure_modes(t, np.sin(2e4 * t), SENSOR)


def test_fit_crosstalk_recovers_the_response_to_the_pulse():
    # the structure answers the contact force: its ringing is the pulse convolved with
    # the mode's damped sine (computed here by numpy's direct convolution)
    dt = 1.0 / RATE
    t = np.arange(round(5e-3 * RATE)) * dt
    onset, duration = 2e-3, 1e-4
    pulse = np.where(
        (t >= onset) & (t < onset + duration), np.sin(math.pi * (t - onset) / duration), 0.0
    )
    pulse *= 3.0
    truth = np.zeros(t.size)
    for (frequency, zeta), weight in zip(MODES, (200.0, 300.0), strict=True):
        kernel = damped(t, frequency, zeta)
        truth += weight * np.convolve(pulse, kernel)[: t.size] * dt  # 1.3-2 % of the peak
    rng = np.random.default_rng(2)
    y = pulse + truth + 0.1 + rng.normal(0.0, 0.01, t.size)
    contact_end = onset + 2 * duration
    fitted = (t < onset - 5e-6) | (t > contact_end + SENSOR.period)
    found = fit_crosstalk(
        t, y, SENSOR, onset, (t >= onset) & (t < contact_end), fitted, contact_end, MODES
    )
    assert len(found.modes) == 2
    # read through the pulse to 5 % of its largest value: noise 0.01 over 6000 fitted
    # samples, and the pulse (read as the force the structure answers) holds the
    # crosstalk itself, 2 % of it
    inside = (t >= onset) & (t < contact_end + 1e-3)
    assert np.max(np.abs(found.values - truth)[inside]) < 0.05 * np.max(np.abs(truth))
    for mode, weight in zip(found.modes, (200.0, 300.0), strict=True):
        # the response's amplitude: weight times the half-sine's Fourier transform at the
        # mode, |F(f)| = I cos(pi f T) / (1 - (2 f T)**2) for impulse I and length T;
        # 5 %: the damping (exp(a T / 2), 0.2 %) and the noise on the pulse read as force
        x = mode.frequency * duration
        spectrum = 3.0 * 2.0 / math.pi * duration * math.cos(math.pi * x) / (1 - (2 * x) ** 2)
        assert mode.amplitude == pytest.approx(weight * spectrum, rel=0.05)
    assert "1890 Hz" in found.describe() and "4100 Hz" in found.describe()


def _short_windows(count, length, amplitudes, rng, noise=0.005):
    """``count`` windows of ``length`` [s] after a contact: the sensor's ringing, a 730 Hz
    plate mode (damping ratio 0.01) of each amplitude at a random phase, an offset and
    white noise."""
    t = np.arange(round(length * RATE)) / RATE
    windows = []
    for amplitude in amplitudes[:count]:
        lag = rng.uniform(0.0, 1.4e-3)  # the mode's phase: it rang from before the window
        ringing = 1.0 * damped(t + 1e-4, SENSOR.resonance, SENSOR.damping_ratio)
        mode = amplitude * damped(t + lag, 730.0, 0.01)
        windows.append((t, ringing + mode + rng.normal(0.1, noise, t.size)))
    return windows


def test_joint_pencil_finds_a_mode_on_windows_too_short_for_one():
    rng = np.random.default_rng(4)
    windows = _short_windows(8, 1.5e-3, [0.04, 0.06, 0.03, 0.05, 0.04, 0.07, 0.05, 0.03], rng)
    # 1.5 ms, 1.1 periods of the 730 Hz mode (as between a hit and its bounce): no
    # window is long enough for the pencil on its own (1.6 ms for a 40 kHz sensor)
    with pytest.raises(ParameterError, match="too short"):
        structure_modes(*windows[0], SENSOR)
    candidates, significant = joint_structure_modes(windows, SENSOR)
    near = [k for k, (f, _) in enumerate(candidates) if abs(f / 730.0 - 1.0) < 0.02]
    # eight windows of 1.1 periods at 6-14 noise sigmas: the stacked pencil's frequency
    # to 2 % (1 % measured), significant after every window (5 standard errors)
    assert len(near) == 1, candidates
    assert significant[:, near[0]].all()
    assert significant.shape == (8, len(candidates))


def test_joint_pencil_keeps_no_mode_on_noise():
    rng = np.random.default_rng(5)
    windows = _short_windows(8, 2e-3, [0.0] * 8, rng)
    candidates, significant = joint_structure_modes(windows, SENSOR)
    # white noise and the sensor's ringing only: whatever poles the pencil fits to the
    # noise are not significant after half of the windows (the campaign's rule)
    assert significant.shape == (8, len(candidates))
    assert (significant.sum(axis=0) < 4).all(), (candidates, significant.sum(axis=0))


def test_joint_pencil_refuses_what_is_not_windows():
    with pytest.raises(ParameterError, match="windows must hold"):
        joint_structure_modes([1.0, 2.0], SENSOR)
    with pytest.raises(ParameterError, match=">= 16 samples"):
        joint_structure_modes([(np.arange(4.0), np.zeros(4))], SENSOR)


def test_refined_joint_poles_under_1f_noise():
    # damped sinusoids at known frequencies in white and 1/f noise (not the record
    # model): the stacked pencil reads the 730 Hz mode growing (dropped) or biased, the
    # variable projection on the windows finds it (docs/campaign.md, "Crosstalk")
    pencil, refined = [], []
    for seed in range(6):
        windows = plate_windows(seed)
        for out, refine in ((pencil, False), (refined, True)):
            candidates, significant = joint_structure_modes(windows, SENSOR, refine=refine)
            out.append([mode_error(candidates, significant, f) for f, _ in PLATE])
    pencil, refined = np.array(pencil), np.array(refined)
    # measured on these six: the pencil found 730 Hz twice (errors 20 % and 1.2 %) and
    # 1890 Hz three times (up to 2.7 %); refined, 730 Hz five times (up to 3.1 %), 1890
    # Hz six times (up to 1.2 %)
    assert (np.isfinite(refined).sum(axis=0) >= [5, 6]).all(), refined
    assert (np.isfinite(refined) >= np.isfinite(pencil)).all()
    # 4 % and 1.5 %: the largest errors over 12 seeds were 3.6 % and 1.2 % (the
    # pencil's 20 % and 7 %); ~30 decimated samples per period of 1/f noise the line
    # of each window does not follow
    assert np.nanmax(refined[:, 0]) < 0.04 and np.nanmax(refined[:, 1]) < 0.015


def test_a_pole_held_at_the_damping_bound_is_refined_away_from_the_modes():
    # 1/f noise alone at 1 MHz, seed 10: refined once with every pencil pole, a noise
    # pole left at the 0.06 damping bound had taken part of the 1890 Hz mode, which came
    # out at 1939 Hz, damping 1e-4 (the bound below); refined again without the held
    # pole (ringdown.refine_unheld), 1896 Hz. 1.5 %: the largest 1890 Hz error of the
    # refined poles over 12 seeds (test above)
    windows = plate_windows(10, white=0.0, flicker_sigma=0.01)
    candidates, significant = joint_structure_modes(windows, SENSOR)
    assert mode_error(candidates, significant, 1890.0) < 0.015
    # 4 %: as for the 730 Hz mode above (0.1 % here)
    assert mode_error(candidates, significant, 730.0) < 0.04


def _single_window(seed, length):
    """The ringing after one contact in closed form (not the record model): an offset and
    a line, the sensor's ringing, the plate's 730 Hz and 1890 Hz modes at 0.04 N, white
    noise of 0.03 N (the single-trace benchmark's)."""
    t = np.arange(round(length * RATE)) / RATE
    rng = np.random.default_rng(seed)
    y = 0.1 + 2.0 * t + 0.5 * damped(t + 1e-4, SENSOR.resonance, SENSOR.damping_ratio)
    y = y + 0.04 * damped(t + 2e-4, 730.0, 0.01) + 0.04 * damped(t + 1e-4, 1890.0, 0.02)
    return t, y + rng.normal(0.0, 0.03, t.size)


def _scipy_frequency(t, y, frequency, zeta):
    """The mode near ``frequency`` [Hz] fitted by scipy's ``curve_fit`` on the whole
    window: a line, the sensor's free ringing and both plate modes, each mode's amplitude,
    phase, frequency and damping ratio free, started from the truth (an independent
    fit, not the pencil's or the variable projection's)."""
    from scipy.optimize import curve_fit

    def model(t, c0, c1, s, r, a1, p1, f1, z1, a2, p2, f2, z2):
        ringing = s * damped(t + r, SENSOR.resonance, SENSOR.damping_ratio)
        return c0 + c1 * t + ringing + a1 * damped(t + p1, f1, z1) + a2 * damped(t + p2, f2, z2)

    start = [0.1, 2.0, 0.5, 1e-4, 0.04, 2e-4, frequency, zeta, 0.04, 1e-4, 1890.0, 0.02]
    fitted, _ = curve_fit(model, t, y, p0=start)
    return fitted[6]


@pytest.mark.parametrize("seed", range(4))
def test_a_single_window_s_growing_pencil_pole_is_refined_into_the_mode(seed):
    # 2.8 ms after a contact (a 4 ms record that starts 1 ms before its impact), two
    # periods of the 730 Hz mode: the pencil reads it growing and drops it (seeds 1, 2)
    # or 3-6 % low (696-707 Hz); refined on the window's block means, 725-734 Hz over 12
    # seeds, and 1888-1899 Hz for the 1890 Hz mode
    t, y = _single_window(seed, 2.8e-3)
    pencil = structure_modes(t, y, SENSOR)
    refined = structure_modes(t, y, SENSOR, refine=True)
    assert not any(abs(f / 730.0 - 1.0) < 0.02 for f, _ in pencil), pencil
    near = [f for f, z in refined if abs(f / 730.0 - 1.0) < 0.02 and 0.0 < z < 0.06]
    # 1 %: the largest error over 12 seeds was 0.7 %
    assert len(near) == 1 and near[0] == pytest.approx(730.0, rel=0.01), refined
    # against scipy's least squares of the whole model on the same samples: the same
    # mode to 1 % (both are least squares on these samples; the refinement's on block
    # means of the band less a line, so they differ by the noise of what each fits)
    assert near[0] == pytest.approx(_scipy_frequency(t, y, 730.0, 0.01), rel=0.01)
    assert any(abs(f / 1890.0 - 1.0) < 0.01 for f, _ in refined), refined  # 0.5 % measured
