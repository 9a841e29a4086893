"""contactlab.signals on arrays, against closed forms: baseline statistics of known
samples, onsets of ramps and steps, the digital Butterworth response of the low-pass."""

import math

import numpy as np
import pytest

from contactlab import signals
from contactlab.errors import ParameterError

DT = 2.0**-20
"""Sample interval [s] (about 0.95 us), a power of two so that sample times and windows
on them are exact."""


def _alternating(n_base, n_after, a=1e-3):
    """``n_base`` samples of +-a before t = 0, then zeros: a baseline of known statistics."""
    t = np.arange(-n_base, n_after) * DT
    y = np.where(t < 0, np.where(np.arange(t.size) % 2 == 0, a, -a), 0.0)
    return t, y


def test_baseline_of_alternating_samples():
    n, a = 1000, 1e-3
    t, y = _alternating(n, 500, a)
    y = y + 0.25
    mean, noise, samples = signals.baseline(t, y, (t[0], 0.0))
    assert samples == n  # [start, end): t = 0 is excluded
    # +-a in equal numbers: mean 0.25, std a sqrt(n / (n - 1)); rounding only (~1e-16).
    assert mean == pytest.approx(0.25, rel=1e-14)
    assert noise == pytest.approx(a * math.sqrt(n / (n - 1)), rel=1e-13)
    assert signals.noise_level(t, y, (t[0], 0.0)) == noise
    # the window's start is included: from the second sample, n - 1 samples
    assert signals.baseline(t, y, (t[1], 0.0)).samples == n - 1


def test_noise_level_of_gaussian_noise():
    sigma, n = 0.01, 20_000
    rng = np.random.default_rng(3)
    t = np.arange(-n, 0) * DT
    noise = signals.noise_level(t, rng.normal(0.5, sigma, n), (t[0], 0.0))
    # The standard error of a sample std is sigma / sqrt(2 (n - 1)) (0.5 %); allow 5 of them.
    assert noise == pytest.approx(sigma, rel=5 / np.sqrt(2 * (n - 1)))


def test_onset_of_a_ramp_is_exact():
    a, slope, t_start = 1e-3, 50.0, 2e-5  # [V], [V/s], [s]
    t, y = _alternating(1000, 2000, a)
    y = np.where(t < t_start, y, slope * (t - t_start))
    sigma = a * math.sqrt(1000 / 999)
    expected = t_start + 5 * sigma / slope
    # A linear ramp is interpolated exactly; only rounding of t and y remains.
    assert signals.detect_onset(t, y, (t[0], 0.0), k=5) == pytest.approx(expected, abs=1e-15)


@pytest.mark.parametrize("height", [0.5, -0.5])
def test_onset_of_a_step_interpolates_between_its_samples(height):
    a, j = 1e-3, 1300  # the step's first sample
    t, y = _alternating(1000, 1000, a)
    y[j:] = height
    k = 5.0
    level = k * a * math.sqrt(1000 / 999)
    onset = signals.detect_onset(t, y, (t[0], 0.0), k=k)
    # |y - mean| goes from 0 to |height| over one sample: crossing of the level on that line
    expected = t[j - 1] + level / abs(height) * DT
    assert onset == pytest.approx(expected, abs=1e-18)  # rounding of t (~1e-20 s)
    assert t[j - 1] < onset < t[j]


def test_onset_at_the_first_sample_and_at_an_overrange_sample():
    t, y = _alternating(1000, 1000)
    first = y.copy()
    first[0] = 1.0  # outside the window below, above the threshold
    assert signals.detect_onset(t, first, (t[10], 0.0)) == t[0]
    clipped = y.copy()
    clipped[1500] = np.inf  # an overrange sample has no value to interpolate
    assert signals.detect_onset(t, clipped, (t[0], 0.0)) == t[1500]


def test_baseline_errors_name_the_window():
    t, y = _alternating(100, 100)
    with pytest.raises(ParameterError, match=r"holds 1 samples; need at least 2 \(pass pre="):
        signals.baseline(t, y, (t[0], t[1]), name="pre")
    # a reversed window holds nothing
    with pytest.raises(ParameterError, match=r"holds 0 samples.*\(pass window=\(start, end\)"):
        signals.noise_level(t, y, (0.0, t[0]))
    for window in (1e-5, (0.0, 1e-5, 2e-5), ("a", 0.0), (True, 0.0)):
        with pytest.raises(ParameterError, match=r"baseline_window must be \(start, end\) \[s\]"):
            signals.baseline(t, y, window, name="baseline_window")
    overrange = y.copy()
    overrange[3] = -np.inf
    with pytest.raises(ParameterError, match="holds overrange samples"):
        signals.baseline(t, overrange, (t[0], 0.0))
    with pytest.raises(ParameterError, match="1-D arrays of equal length"):
        signals.baseline(t, y[:-1], (t[0], 0.0))


def test_onset_errors():
    t, y = _alternating(100, 100)
    with pytest.raises(ParameterError, match="k must be a finite number > 0"):
        signals.detect_onset(t, y, (t[0], 0.0), k=0.0)
    # the alternating baseline is the whole deviation: nothing exceeds 2 sigma
    with pytest.raises(ParameterError, match=r"no sample deviates .* more than 2\.0 sigma"):
        signals.detect_onset(t, y, (t[0], 0.0), k=2.0)


def _sine_response(f, cutoff, order, n=20_000):
    """In-phase and quadrature amplitudes of the low-passed ``sin(2 pi f t)``, fitted over
    the middle half of the record (away from the filter's edge transients)."""
    t = np.arange(n) * DT
    out = signals.lowpass(np.sin(2 * np.pi * f * t), DT, cutoff, order)
    middle = slice(n // 4, 3 * n // 4)
    basis = np.column_stack([np.sin(2 * np.pi * f * t[middle]), np.cos(2 * np.pi * f * t[middle])])
    (in_phase, quadrature), *_ = np.linalg.lstsq(basis, out[middle], rcond=None)
    return in_phase, quadrature


@pytest.mark.parametrize("order", [1, 2, 4, 7])
@pytest.mark.parametrize("ratio", [0.1, 0.25, 1.0, 3.0])
def test_lowpass_gain_is_the_squared_digital_butterworth_response(ratio, order):
    cutoff = 20e3  # [Hz]
    f = ratio * cutoff
    in_phase, quadrature = _sine_response(f, cutoff, order)
    # Bilinear transform prewarped at the cutoff, applied twice: |H|^2 in closed form,
    # exactly 1/2 at the cutoff whatever the order.
    warp = math.tan(math.pi * f * DT) / math.tan(math.pi * cutoff * DT)
    gain = 1.0 / (1.0 + warp ** (2 * order))
    if ratio == 1.0:
        assert gain == 0.5
    # Least squares over 10^4 samples of a sine: rounding only (observed ~1e-14); the
    # edge transients have decayed below it by the middle of the record.
    assert in_phase == pytest.approx(gain, abs=1e-12)
    assert quadrature == pytest.approx(0.0, abs=1e-12)  # zero phase, same rounding


def test_lowpass_keeps_a_symmetric_pulse_in_place():
    n = 3000
    t = np.arange(n) * DT
    centre = t[1500]
    pulse = np.exp(-(((t - centre) / 20e-6) ** 2))
    smooth = signals.lowpass(pulse, DT, 20e3)
    # Zero phase: a pulse symmetric about a sample keeps its peak on that sample.
    assert t[np.argmax(smooth)] == centre
    assert smooth.max() < pulse.max()  # and the filter did act on it


def test_lowpass_errors():
    y = np.zeros(100)
    nyquist = 0.5 / DT
    for cutoff in (nyquist, -1.0, np.nan):
        with pytest.raises(ParameterError, match=rf"cutoff .*< {nyquist:g} \[Hz\]"):
            signals.lowpass(y, DT, cutoff)
    with pytest.raises(ParameterError, match="interval must be a finite number > 0"):
        signals.lowpass(y, 0.0, 1e3)
    with pytest.raises(ParameterError, match="order must be an integer >= 1"):
        signals.lowpass(y, DT, 1e3, order=2.0)
    with pytest.raises(ParameterError, match="overrange"):
        signals.lowpass(np.where(np.arange(100) == 50, np.inf, 0.0), DT, 1e3)
    # order 4: two second-order sections, edge padding 3 (2 * 2 + 1) = 15 samples
    with pytest.raises(ParameterError, match="order 4 needs more than 15 samples"):
        signals.lowpass(y[:15], DT, 1e3)
    assert signals.lowpass(y[:16], DT, 1e3).shape == (16,)
    with pytest.raises(ParameterError, match="1-D array"):
        signals.lowpass(y.reshape(10, 10), DT, 1e3)


def test_robust_noise_of_gaussian_noise_with_pulses():
    sigma, n = 0.02, 40_000
    y = np.random.default_rng(5).normal(0.3, sigma, n)
    # the MAD estimate's relative standard error is 1.17 / sqrt(n) (efficiency 37 %)
    assert signals.robust_noise(y) == pytest.approx(sigma, rel=5 * 1.17 / math.sqrt(n))
    y[::20] += 50 * sigma  # 5 % of the samples in pulses: the std is ten times off
    assert y.std() > 10 * sigma
    # a 5 % contamination moves the median absolute deviation by about 7 % at most
    assert signals.robust_noise(y) == pytest.approx(sigma, rel=0.1)


def test_running_baseline_follows_drift_and_keeps_a_pulse_whole():
    sigma, n, width = 0.01, 20_000, 400
    rng = np.random.default_rng(6)
    t = np.arange(n) * DT
    drift = 2.0 * t / t[-1] + 0.3 * np.sin(2 * np.pi * t / t[-1])  # 230 sigma of wander
    pulse = np.zeros(n)
    pulse[10_000:10_020] = 50 * sigma  # 20 samples, a twentieth of a block
    found = signals.running_baseline(drift + pulse + rng.normal(0, sigma, n), width)
    # the block medians follow the drift to their own scatter, 1.25 sigma / sqrt(400),
    # plus the linear interpolation's error over a block of a slow sine (< 1e-5)
    assert np.max(np.abs(found.level - drift)[width:-width]) < 5 * sigma
    quiet = np.ones(n, dtype=bool)
    quiet[10_000:10_020] = False
    # the residual is the noise (its std to a few per cent) and the whole pulse
    assert found.residual[quiet].std() == pytest.approx(sigma, rel=0.05)
    assert np.mean(found.residual[10_000:10_020]) == pytest.approx(50 * sigma, abs=sigma)
    assert np.median(found.noise) == pytest.approx(sigma, rel=0.1)  # MAD of 400 samples


def test_running_baseline_leaves_no_residual_at_an_offset_step():
    sigma, n, width = 0.01, 12_000, 400
    y = np.random.default_rng(7).normal(0, sigma, n)
    y[5_130:] += 20 * sigma  # a step inside a block, away from the record's ends
    found = signals.running_baseline(y, width)
    # the samples on each side keep their own level: nothing reaches 6 sigma
    assert np.max(np.abs(found.residual)) < 6 * sigma


def test_quiet_window_finds_the_quietest_stretch():
    n = 16_000
    rng = np.random.default_rng(8)
    t = np.arange(n) * DT
    y = rng.normal(0, 0.05, n)
    y[9_000:10_000] = rng.normal(0, 0.005, 1000)  # ten times quieter, one block long
    start, end = signals.quiet_window(t, y, 1000)
    assert (start, end) == (t[9_000], t[10_000])


def test_running_baseline_refuses_bad_input():
    with pytest.raises(ParameterError, match="two blocks"):
        signals.running_baseline(np.zeros(30), 16)
    with pytest.raises(ParameterError, match="width"):
        signals.running_baseline(np.zeros(100), 4)
    with pytest.raises(ParameterError, match="finite"):
        signals.running_baseline(np.r_[np.zeros(99), np.inf], 16)


def _curved_drift_and_a_pulse_at_the_start(n=8000, sigma=0.01):
    """A drift that curves within the record (its slope falls from 0.5 to -5.5 over it)
    and a half-sine pulse of 50 sigma over the first 100 samples."""
    t = np.arange(n) / n
    pulse = np.zeros(n)
    pulse[:100] = 50 * sigma * np.sin(np.pi * np.arange(100) / 100)
    return 0.5 * t - 3.0 * t**2, pulse


def test_running_baseline_extrapolates_the_level_under_a_pulse_at_the_start():
    sigma, width, head = 0.01, 1000, 300
    drift, pulse = _curved_drift_and_a_pulse_at_the_start(sigma=sigma)
    y = drift + pulse + np.random.default_rng(9).normal(0, sigma, drift.size)
    found = signals.running_baseline(y, width, head=head)
    # a quadratic drift is the fitted model: the level under the pulse is off by the
    # fit's scatter alone (0.25 sigma at the first sample, measured below), and the
    # pulse is kept whole to that and the noise
    assert np.max(np.abs(found.level - drift)[:head]) < sigma
    assert np.max(np.abs(found.residual - pulse)[:100]) < 5 * sigma
    # the block levels alone extrapolate the outer slope (3.3 sigma off at sample 0)
    assert abs(signals.running_baseline(y, width).level[0] - drift[0]) > 2 * sigma


def test_head_level_reports_the_scatter_of_its_extrapolation():
    from contactlab._head_level import head_level

    sigma, width, head, seeds = 0.01, 1000, 300, 200
    drift, pulse = _curved_drift_and_a_pulse_at_the_start(sigma=sigma)
    levels, errors = [], []
    for seed in range(seeds):
        y = drift + pulse + np.random.default_rng(seed).normal(0, sigma, drift.size)
        level, residual = np.zeros(y.size), np.zeros(y.size)
        errors.append(head_level(y, head, width, None, level, residual)[0])
        levels.append(level[0] - drift[0])
    # over 200 seeds the scatter is read to 5 % (1 / sqrt(2 * 200)); the reported error
    # is least squares' (the soft_l1 loss is a few per cent less efficient on Gaussian
    # noise) with a MAD-read noise (scatters by 2 %): within 15 %, and unbiased to 3
    # standard errors of the mean
    assert np.mean(errors) == pytest.approx(np.std(levels), rel=0.15)
    assert abs(np.mean(levels)) < 3 * np.std(levels) / np.sqrt(seeds)


def test_running_baseline_refuses_a_head_without_quiet_samples_after_it():
    with pytest.raises(ParameterError, match="head"):
        signals.running_baseline(np.random.default_rng(0).normal(size=200), 64, head=190)
    with pytest.raises(ParameterError, match="head"):
        signals.running_baseline(np.zeros(200), 64, head=-1)
