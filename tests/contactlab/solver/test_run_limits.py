"""Run-time and memory limits of simulate_impact (issue 24): refused before any work."""

import math

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


def test_a_mode_too_fast_to_follow_is_refused_not_run_for_hours(monkeypatch):
    """Linear damping 1e6 N*s/m on a 50 mg grain: 1.3 million scan points before the
    contact ends (its time grows with the damping; 1e9 N*s/m ran half an hour). With the
    limit lowered to 1e5 points, the refusal comes at once and says why, from the compiled
    loop and from the Python pieces (the same law seen as a history law, which the loop
    does not take)."""
    from contactlab.kernels import rules

    class PythonPieces(cl.laws.LinearViscoelastic):
        has_history = True  # its force ignores the history: the same law

    monkeypatch.setattr(rules, "MAX_SCAN_POINTS", 100_000)
    law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1e6)
    for each in (law, PythonPieces(stiffness=1e5, damping=1e6)):
        with pytest.raises(ParameterError, match="too fast to follow"):
            cl.simulate_impact(GRAIN, SENSOR, each, 2.0)
    monkeypatch.setattr(rules, "MAX_SCAN_POINTS", 2_000_000)
    assert cl.simulate_impact(GRAIN, SENSOR, law, 2.0).contact_time > 0  # under the limit


@pytest.mark.parametrize("kappa", [0.0, 1e-12, 9e-4, 0.67, 1.0, math.nan])
def test_an_impossible_inertia_factor_is_refused(kappa):
    """Outside [1e-3, 2/3]: no sphere has more than a thin shell's 2/3; 1e-12 hung the
    oblique solver (a spin mode too fast to follow)."""
    normal = cl.laws.HertzDamped(1.5e6, 4.0)
    tangential = cl.laws.Mindlin.from_material(
        cl.analytic.Material(21.6e6, 0.2, GRAIN.radius), friction=0.5
    )
    with pytest.raises(ParameterError, match="inertia_factor"):
        cl.simulate_oblique(GRAIN, SENSOR, normal, tangential, 2.0, 0.5, inertia_factor=kappa)
