"""Pulse metrics: lobe reading with and without hysteresis."""

import numpy as np
import pytest

from contactlab.errors import ParameterError
from contactlab.metrics import first_lobe, pulse_metrics

T = np.linspace(0.0, 1e-3, 10001)  # [s]
PULSE = np.where((T > 2e-4) & (T < 6e-4), np.sin(np.pi * (T - 2e-4) / 4e-4), 0.0)  # [N]
"""A 400 us half sine of 1 N starting at 200 us."""


def test_lobe_of_a_clean_half_sine_is_exact():
    start, end = first_lobe(T, PULSE, threshold=0.5)
    # half sine crosses 0.5 at 1/6 and 5/6 of its length; linear interpolation between
    # samples 0.1 us apart on a curve of radius ~ (400 us / pi)^2: error < 1e-10 s
    assert start == pytest.approx(2e-4 + 4e-4 / 6, abs=1e-10)
    assert end == pytest.approx(2e-4 + 5 * 4e-4 / 6, abs=1e-10)


def test_hysteresis_ignores_dips_that_do_not_reach_the_baseline():
    noisy = PULSE.copy()
    # two dips under the 0.5 level on the rise and on the fall, not down to 0.2
    for centre in (2.7e-4, 5.0e-4):
        noisy[np.abs(T - centre) < 2e-6] = 0.4
    plain = first_lobe(T, noisy, threshold=0.5)
    debounced = first_lobe(T, noisy, threshold=0.5, hysteresis=0.3)
    assert plain[1] < 2.8e-4  # cut short by the first dip
    # with hysteresis the lobe ends at the last crossing of 0.5, as on the clean pulse
    assert debounced == pytest.approx(first_lobe(T, PULSE, threshold=0.5), abs=1e-10)


def test_zero_hysteresis_is_the_plain_reading():
    rng = np.random.default_rng(1)
    noisy = PULSE + 0.05 * rng.standard_normal(T.size)
    assert first_lobe(T, noisy, 0.25) == first_lobe(T, noisy, 0.25, hysteresis=0.0)


def test_pulse_metrics_pass_hysteresis_and_reject_negative_values():
    noisy = PULSE.copy()
    noisy[np.abs(T - 5.0e-4) < 2e-6] = 0.4
    assert pulse_metrics(T, noisy, 0.5, hysteresis=0.3).duration == pytest.approx(
        4e-4 * 2 / 3, abs=1e-10
    )
    with pytest.raises(ParameterError, match="hysteresis"):
        first_lobe(T, PULSE, 0.5, hysteresis=-0.1)


@pytest.mark.parametrize("threshold", [np.nan, np.inf, "0.5", None])
def test_bad_threshold_is_named_not_read_as_no_pulse(threshold):
    # a NaN threshold compares false everywhere: it would report "no lobe" (nan, nan)
    with pytest.raises(ParameterError, match="threshold"):
        first_lobe(T, PULSE, threshold)
    with pytest.raises(ParameterError, match="threshold"):
        pulse_metrics(T, PULSE, threshold)


def test_first_lobe_passes_over_lobes_under_least_peak_of_the_largest_value():
    t = np.arange(40) * 1e-6
    y = np.zeros(40)
    y[5] = 0.4  # a pre-echo sample: 0.4 % of the hit
    y[20:25] = [20.0, 80.0, 100.0, 80.0, 20.0]  # the hit
    # every lobe counts by default: the pre-echo (crossings at 4.25 and 5.75 us) comes first
    assert first_lobe(t, y, 0.1) == pytest.approx((4.25e-6, 5.75e-6), rel=1e-12)
    # at half the largest value the pre-echo is passed over; the hit's crossings of 0.1 N
    # are linear between samples 19-20 and 24-25 (exact up to round-off)
    start, end = first_lobe(t, y, 0.1, least_peak=0.5)
    assert (start, end) == pytest.approx((19.005e-6, 24.995e-6), rel=1e-12)
    assert pulse_metrics(t, y, 0.1, least_peak=0.5).peak == 100.0


def test_first_lobe_least_peak_must_be_a_fraction_below_one():
    with pytest.raises(ParameterError, match="least_peak"):
        first_lobe([0.0, 1.0], [0.0, 1.0], least_peak=1.0)
