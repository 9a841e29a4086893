"""The compiled held force (:mod:`contactlab.kernels.held_force`) against the numpy and
scipy calls it replaced in :meth:`contactlab.inverse.lobe_model.LobeModel.unit`: equal to
the last bit, over the families, dampings, sampling steps, sensors and durations the
onset and family fits meet."""

import math

import numpy as np
import pytest
from held_reference import numpy_response, numpy_unit
from hypothesis import given, settings
from hypothesis import strategies as st

from contactlab.inverse.lobe_model import FAMILIES, FINE_PERIODS, _sensor_filter, force_shape
from contactlab.kernels.held_force import held_signal, sampled_signal


@settings(max_examples=60, deadline=None)
@given(
    family=st.sampled_from(sorted(FAMILIES)),
    damping=st.sampled_from([0.0, 0.05, 0.34]),
    rate=st.sampled_from([1e6, 2e6, 5e6, 20e6]),
    resonance=st.floats(5e3, 200e3),
    zeta=st.floats(0.001, 0.2),
    tau=st.floats(2e-6, 2e-3),
    samples=st.integers(4, 600),
)
def test_equal_to_interp_and_lfilter_to_the_last_bit(
    family, damping, rate, resonance, zeta, tau, samples
):
    dt = 1.0 / rate
    fine = math.ceil(max(2.0, dt * resonance / FINE_PERIODS))  # as LobeModel sets it
    step = dt / fine
    b, a = _sensor_filter(2.0 * np.pi * resonance, zeta, step)
    u, h = force_shape(family, damping)
    count = fine * (samples + 2)
    times, values = held_signal(step, count, tau, u, h, b, a)
    s, r = numpy_unit(step, count, tau, u, h, b, a)
    assert np.array_equal(times, s)
    assert np.array_equal(values, r)  # same operations in the same order: bitwise


@pytest.mark.parametrize("tau", [0.0, np.nan])
def test_a_zero_or_nan_duration_gives_what_interp_gives(tau):
    # zero: every point at -inf or +inf, outside the shape (0); NaN: NaN everywhere
    u, h = force_shape("linear", 0.0)
    b, a = _sensor_filter(2.0 * np.pi * 40e3, 0.02, 1e-7)
    _, values = held_signal(1e-7, 20, tau, u, h, b, a)
    with np.errstate(divide="ignore", invalid="ignore"):  # numpy's warnings, no error
        _, reference = numpy_unit(1e-7, 20, tau, u, h, b, a)
    assert np.array_equal(values, reference, equal_nan=True)
    assert np.isnan(values).all() == np.isnan(tau)


@settings(max_examples=80, deadline=None)
@given(
    rate=st.sampled_from([1e6, 2e6, 5e6]),
    fine=st.integers(2, 8),
    samples=st.integers(2, 300),
    tau=st.floats(2e-6, 2e-3),
    zeta=st.floats(0.001, 0.2),
    shift=st.floats(-1.5, 1.5),
    on_grid=st.booleans(),
    backwards=st.booleans(),
)
def test_sampled_signal_equal_to_interp_to_the_last_bit(
    rate, fine, samples, tau, zeta, shift, on_grid, backwards
):
    # the onsets the fits try: inside, before and after the window, on a grid point
    # (numpy's exact-hit branch) or between; times in order and reversed (the bisection)
    dt = 1.0 / rate
    step = dt / fine
    b, a = _sensor_filter(2.0 * np.pi * 40e3, zeta, step)
    u, h = force_shape("linear", 0.1)
    s, r = held_signal(step, fine * (samples + 2), tau, u, h, b, a)
    t = 1e-3 + np.arange(samples) * dt
    t0 = 1e-3 + shift * samples * dt
    if on_grid:  # t[k] - t0 lands on a grid point
        t0 = t[samples // 2] - s[min(fine * (samples // 2), s.size - 1)]
    t = t[::-1].copy() if backwards else t
    assert np.array_equal(sampled_signal(t, t0, s, r), numpy_response(t, t0, s, r))


@pytest.mark.parametrize("t0", [0.0, np.nan])
def test_sampled_signal_at_nan_onsets_and_signals_gives_what_interp_gives(t0):
    # a NaN onset: NaN everywhere; a NaN signal (a NaN duration): numpy's fall-backs
    u, h = force_shape("linear", 0.0)
    b, a = _sensor_filter(2.0 * np.pi * 40e3, 0.02, 1e-7)
    s, r = held_signal(1e-7, 40, np.nan, u, h, b, a)
    r_half = np.where(np.arange(r.size) < 20, 0.5, r)  # finite, then NaN
    t = np.linspace(-1e-6, 5e-6, 37)
    for signal_ in (r, r_half):
        expected = numpy_response(t, t0, s, signal_)
        assert np.array_equal(sampled_signal(t, t0, s, signal_), expected, equal_nan=True)
