"""Run-time and memory limits of simulate_impact (issue 24): refused before any work."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.solver.impact import MAX_OUTPUT_SAMPLES

GRAIN = cl.Grain(diameter=5e-3, density=765.0)
SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
LAW = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)


def test_a_window_that_would_take_terabytes_is_refused_naming_both_parameters():
    # 1e4 s at 1 MHz: 1e10 samples, 80 GB per array
    with pytest.raises(ParameterError, match=r"duration = 1e\+04 s at sample_rate = 1e\+06 Hz"):
        cl.simulate_impact(GRAIN, SENSOR, LAW, 2.0, duration=1e4, sample_rate=1e6)


def test_just_past_the_limit_is_refused():
    rate = 1e6  # [Hz]; 0.1 % past the limit (at it, 1.6 GB would be allocated)
    duration = (MAX_OUTPUT_SAMPLES - 1) / rate
    with pytest.raises(ParameterError, match="output samples"):
        cl.simulate_impact(GRAIN, SENSOR, LAW, 2.0, duration=duration * 1.001, sample_rate=rate)


@settings(max_examples=40, deadline=None, derandomize=True)  # fixed budget, < 1 s
@given(
    duration=st.floats(1e-2, 1e308, allow_nan=False, allow_infinity=False),
    sample_rate=st.floats(1e10, 1e308, allow_nan=False, allow_infinity=False),
)
def test_huge_grids_raise_parameter_error_not_memory_or_overflow_errors(duration, sample_rate):
    # every drawn pair asks for >= 1e8 samples (overflowing to inf for the largest)
    with pytest.raises(ParameterError, match="output samples"):
        cl.simulate_impact(GRAIN, SENSOR, LAW, 2.0, duration=duration, sample_rate=sample_rate)
