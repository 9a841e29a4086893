"""The realistic record model: each effect alone, against what it must be (spectra of
known lines and slopes, the ADC's grid and rails, step heights, bounce rows)."""

import numpy as np
import pytest
from scipy import signal

from contactlab.errors import ParameterError
from dem_check.campaign import Effects, realistic_record

RATE = 1e5  # [Hz]: the slow effects need long records, not fast sampling
LENGTH = 0.2  # [s]: ten mains periods at 50 Hz


def _background(hard_setup, effects, length=LENGTH, rate=RATE, seed=0, noise=0.0):
    grain, sensor, law = hard_setup
    rec = realistic_record(
        grain,
        sensor,
        law,
        [],
        [],
        length=length,
        sample_rate=rate,
        noise=noise,
        effects=effects,
        seed=seed,
    )
    return np.asarray(rec.trace.t), np.asarray(rec.trace.values), rec


def test_nothing_is_added_by_default(hard_setup):
    _, y, rec = _background(hard_setup, Effects())
    assert not y.any() and rec.noise == 0.0 and rec.truth.empty


def test_pink_noise_falls_as_one_over_f(hard_setup):
    _, y, rec = _background(hard_setup, Effects(pink=0.05), length=2.0)
    f, psd = signal.welch(y, fs=RATE, nperseg=2**14)
    band = (f > 20.0) & (f < 20e3)
    slope = np.polyfit(np.log(f[band]), np.log(psd[band]), 1)[0]
    # 1/f: slope -1; Welch's averaging of 12 segments leaves a few per cent of scatter
    assert slope == pytest.approx(-1.0, abs=0.1)
    assert y.std() == pytest.approx(0.05, rel=1e-9)  # scaled to the asked sigma
    assert rec.noise == pytest.approx(0.05)


@pytest.mark.parametrize("mains", [50.0, 60.0])
def test_hum_is_the_mains_line_and_its_harmonics(hard_setup, mains):
    effects = Effects(hum=0.2, mains=mains)
    _, y, _ = _background(hard_setup, effects, length=0.5)  # whole periods at 50 and 60 Hz
    amplitude = np.abs(np.fft.rfft(y)) * 2.0 / y.size
    f = np.fft.rfftfreq(y.size, 1.0 / RATE)
    expected = {mains * k: 0.2 * a for k, a in enumerate((1.0, *effects.harmonics), start=1)}
    for line, a in expected.items():
        # whole periods: each line falls on one FFT bin, exactly (rounding only)
        assert amplitude[np.argmin(np.abs(f - line))] == pytest.approx(a, rel=1e-9)
    others = ~np.isin(np.round(f, 6), list(expected))
    assert amplitude[others].max() < 1e-9


def test_drift_is_slow_and_as_large_as_asked(hard_setup):
    _, y, _ = _background(hard_setup, Effects(drift=0.3), length=2.0)
    assert y[0] == 0.0 and np.max(np.abs(y)) == pytest.approx(0.3, rel=1e-12)
    power = np.abs(np.fft.rfft(y)) ** 2
    f = np.fft.rfftfreq(y.size, 1.0 / RATE)
    # the drift's sines lie at 0.2-5 Hz (plus a trend): above 50 Hz only the leakage of
    # the record's unequal ends, falling as 1/f**2 (under 1e-3 of the power)
    assert power[f > 50.0].sum() < 1e-3 * power.sum()


def test_crosstalk_rings_at_the_plate_modes_after_each_impact(hard_setup):
    grain, sensor, law = hard_setup
    effects = Effects(crosstalk=0.05)
    plain = realistic_record(
        grain, sensor, law, [2.0], [0.02], length=LENGTH, sample_rate=RATE, noise=0.0
    )
    rec = realistic_record(
        grain,
        sensor,
        law,
        [2.0],
        [0.02],
        length=LENGTH,
        sample_rate=RATE,
        noise=0.0,
        effects=effects,
    )
    t = np.asarray(rec.trace.t)
    ringing = np.asarray(rec.trace.values) - np.asarray(plain.trace.values)
    assert not ringing[t < 0.02].any()
    peak = rec.truth["peak_sensor_force [N]"][0]
    # each mode starts at 0.5-1 times crosstalk * peak; three modes add up to at most 3
    assert 0.02 * peak < np.abs(ringing).max() < 3 * 0.05 * peak
    f, psd = signal.periodogram(ringing, fs=RATE)
    for frequency, _ in effects.plate_modes:
        near = np.abs(f - frequency) < 50.0
        assert psd[near].max() > 100.0 * np.median(psd)  # a line at each mode


def _one_mode_ringing(hard_setup, mode, rate=2e6, onset=2e-3, length=12e-3):
    """The crosstalk of one 2 m/s impact with one plate mode, its clean record [N] and
    the record's time [s] (no noise)."""
    grain, sensor, law = hard_setup
    common = {"length": length, "sample_rate": rate, "noise": 0.0}
    plain = realistic_record(grain, sensor, law, [2.0], [onset], **common)
    effects = Effects(crosstalk=0.05, plate_modes=(mode,))
    rec = realistic_record(grain, sensor, law, [2.0], [onset], **common, effects=effects)
    clean = np.asarray(plain.trace.values)
    return np.asarray(rec.trace.values) - clean, clean, np.asarray(rec.trace.t), rec.truth


def test_crosstalk_is_the_plate_s_response_to_the_impact_s_force(hard_setup):
    # the sensor stands on the plate: its force drives the plate's mode, whose answer is
    # the convolution of that force with the mode's impulse response. Independent
    # method: the convolution summed by FFT (trapezoidal rule, its end terms zero since
    # the response starts at 0 and the force before the touch is 0), not the model's
    # first-order-hold recursion
    frequency, zeta = 1890.0, 0.02
    ringing, clean, t, truth = _one_mode_ringing(hard_setup, (frequency, zeta))
    dt = t[1] - t[0]
    w = 2.0 * np.pi * frequency
    response = np.exp(-zeta * w * t) * np.sin(w * t)
    reference = signal.fftconvolve(clean, response)[: t.size] * dt
    scale = float(ringing @ reference / (reference @ reference))
    # the trapezoidal rule's error is (w dt)**2 / 12 = 3e-6 of the response at 2 MHz,
    # and the first-order hold is exact for the sampled force: 1e-4 of the ringing's
    # largest value is far above both and far below any other model
    assert np.max(np.abs(ringing - scale * reference)) < 1e-4 * np.max(np.abs(ringing))
    # scaled by the force's first lobe (its impulse): the response to that impulse at
    # once starts at 0.5-1 times crosstalk * peak (the drawn weight)
    first = int(np.flatnonzero(clean > 0.0)[0])
    end = first + int(np.flatnonzero(clean[first:] <= 0.0)[0])
    weight = scale * float(np.sum(clean[first:end]) * dt)
    peak = truth["peak_sensor_force [N]"][0]
    assert 0.5 * 0.05 * peak <= weight <= 0.05 * peak


def test_crosstalk_starts_with_the_force_not_at_the_touch(hard_setup):
    # a ringing started at full amplitude at the touch (sin(w s)) would reach 12 % of
    # its amplitude 10 us in at 1890 Hz; the response to a force that grows from zero
    # over the 100 us contact is still under 1 % of it there (about w s**2 F / (2 J),
    # 0.2 %)
    onset = 2e-3
    ringing, _, t, _ = _one_mode_ringing(hard_setup, (1890.0, 0.02), onset=onset)
    early = (t >= onset) & (t <= onset + 10e-6)
    later = t > onset + 0.3e-3  # after the contact: the free ringing
    assert np.max(np.abs(ringing[early])) < 0.01 * np.max(np.abs(ringing[later]))
    assert not ringing[t < onset].any()


def test_the_adc_quantises_and_clips_at_its_rails(hard_setup):
    grain, sensor, law = hard_setup
    effects = Effects(full_scale=2.0, bits=12)
    rec = realistic_record(
        grain,
        sensor,
        law,
        [1.0, 2.5],
        [0.01, 0.05],
        length=0.1,
        sample_rate=2e6,
        noise=0.01,
        effects=effects,
    )
    y = np.asarray(rec.trace.values)
    lsb = 4.0 / 2**12
    assert np.allclose(y / lsb, np.round(y / lsb), atol=1e-9)  # on the ADC's grid
    assert y.max() == 2.0 and (y == 2.0).sum() > 3  # held at the rail, never beyond
    assert rec.truth["clipped"].tolist() == [False, True]  # 1.6 N fits, 4 N does not
    assert rec.noise == pytest.approx(np.hypot(0.01, lsb / np.sqrt(12.0)))


def test_offset_steps_have_the_asked_height(hard_setup):
    t, y, rec = _background(hard_setup, Effects(steps=3, step_size=0.4), noise=0.001)
    assert rec.step_times.size == 3
    for at in rec.step_times:
        before = np.median(y[(t < at) & (t > at - 2e-4)])
        after = np.median(y[(t > at) & (t < at + 2e-4)])
        # 20 samples each side of noise 0.001: medians to a few 1e-4
        assert abs(after - before) == pytest.approx(0.4, abs=2e-3)


def test_placed_offset_steps_have_their_time_and_signed_height(hard_setup):
    placed = ((2e-3, 0.3), (6e-3, -0.5))
    t, y, rec = _background(hard_setup, Effects(offsets=placed), noise=0.001)
    assert rec.step_times == pytest.approx([t[0] + 2e-3, t[0] + 6e-3])
    for at, (_, height) in zip(rec.step_times, placed, strict=True):
        before = np.median(y[(t < at) & (t > at - 2e-4)])
        after = np.median(y[(t >= at) & (t < at + 2e-4)])
        # medians of 20 samples of noise 0.001 each side: to a few 1e-4
        assert after - before == pytest.approx(height, abs=2e-3)


def test_bounces_are_rows_of_the_truth(hard_setup):
    grain, sensor, law = hard_setup
    effects = Effects(bounce=0.4, bounce_delay=3e-3)
    rec = realistic_record(
        grain, sensor, law, [2.0, 1.0], [0.01, 0.05], length=0.1, sample_rate=1e6, effects=effects
    )
    truth = rec.truth
    assert truth["onset [s]"].tolist() == pytest.approx([0.01, 0.013, 0.05, 0.053], abs=1e-7)
    assert truth["velocity [m/s]"].tolist() == pytest.approx([2.0, 0.8, 1.0, 0.4])


def test_a_trigger_shifts_the_time_axis(hard_setup):
    grain, sensor, law = hard_setup
    rec = realistic_record(
        grain, sensor, law, [2.0], [1e-4], length=2e-3, sample_rate=1e6, trigger=1e-4
    )
    assert rec.trace.t[0] == pytest.approx(-1e-4) and rec.trace.metadata["trigger_time"] == 0.0
    assert rec.truth["onset [s]"][0] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    "changes, name",
    [
        ({"pink": -1.0}, "pink"),
        ({"bits": 1}, "bits"),
        ({"full_scale": 0.0}, "full_scale"),
        ({"mains": 0.0}, "mains"),
        ({"harmonics": (0.3, float("nan"))}, "harmonics"),
        ({"plate_modes": ((730.0,),)}, "plate_modes"),
        ({"plate_modes": ((730.0, 1.5),)}, "plate_modes damping ratio"),
        ({"offsets": ((1e-3,),)}, "offsets"),
        ({"offsets": ((-1e-3, 0.1),)}, "offsets time"),
        ({"offsets": ((1e-3, float("inf")),)}, "offsets height"),
    ],
)
def test_bad_effects_are_refused_naming_the_field(changes, name):
    with pytest.raises(ParameterError, match=name):
        Effects(**changes)


def test_effects_that_are_no_effects_are_refused(hard_setup):
    grain, sensor, law = hard_setup
    with pytest.raises(ParameterError, match="effects"):
        realistic_record(
            grain, sensor, law, [2.0], [1e-3], length=2e-3, sample_rate=1e6, effects="loud"
        )
