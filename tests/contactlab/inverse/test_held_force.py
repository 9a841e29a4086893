"""The compiled held force (:mod:`contactlab.kernels.held_force`) against the numpy and
scipy calls it replaced in :meth:`contactlab.inverse.lobe_model.LobeModel.unit`: equal to
the last bit, over the families, dampings, sampling steps, sensors and durations the
onset and family fits meet."""

import math

import numpy as np
import pytest
from held_reference import numpy_unit
from hypothesis import given, settings
from hypothesis import strategies as st

from contactlab.inverse.lobe_model import FAMILIES, FINE_PERIODS, _sensor_filter, force_shape
from contactlab.kernels.held_force import held_signal


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
