"""The physics bounds of measured impacts: closed form, simulated impacts, unit slips."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.compare import compare_trace
from contactlab.compare.physics import (
    SIGNAL_OVERSHOOT,
    STIFFEST_CONTACT_MODULUS,
    impact_limits,
    physics_problems,
)
from contactlab.testing.strategies import grains, impact_velocities, sensors
from contactlab.traces import Trace

PAPER_GRAIN = cl.Grain(diameter=5e-3, density=765.0)


def test_peak_force_bound_is_twice_the_rigid_sphere_on_steel_by_energy_balance():
    """Independent of contactlab.analytic: m v**2 / 2 = (2/5) kH d**2.5, F = kH d**1.5."""
    k_hertz = 4.0 / 3.0 * STIFFEST_CONTACT_MODULUS * math.sqrt(PAPER_GRAIN.radius)
    overlap = (1.25 * PAPER_GRAIN.mass * 50.0**2 / k_hertz) ** 0.4
    limits = impact_limits(PAPER_GRAIN)
    # both are the same closed form evaluated two ways: a few ulp apart
    assert limits["peak_force [N]"] == pytest.approx(
        SIGNAL_OVERSHOOT * k_hertz * overlap**1.5, rel=1e-12
    )
    assert limits["velocity_change [m/s]"] == (0.05, 100.0)
    assert 3e3 < limits["peak_force [N]"] < 1e4  # 50 mg at 50 m/s on steel: kilonewtons


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    grain=grains(),
    sensor=sensors(rigid=True),
    velocity=impact_velocities(),
    stiffness=st.floats(1e3, 1e7),
    ratio=st.floats(0.0, 0.9),
)
def test_every_simulated_real_impact_passes(grain, sensor, velocity, stiffness, ratio):
    """Over the strategies' whole ranges (real grains, sensors, speeds; linear contacts of
    1 kN/m to 10 MN/m, damping up to 0.9 of critical), the true force and the sensor's
    signal of a simulated impact are never flagged."""
    damping = 2.0 * ratio * math.sqrt(stiffness * grain.mass)
    law = cl.laws.LinearViscoelastic(stiffness=stiffness, damping=damping)
    res = cl.simulate_impact(grain, sensor, law, velocity)
    velocity_change = res.impulse / grain.mass
    assert physics_problems(grain, res.peak_contact_force, velocity_change) == []
    assert physics_problems(grain, float(np.max(res.sensor_force)), velocity_change) == []


def test_a_sensitivity_given_in_mv_per_n_is_flagged():
    """The issue's case: 11.24 (mV/N) given as V/N divides the force by 1000."""
    law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
    res = cl.simulate_impact(PAPER_GRAIN, cl.Sensor.rigid(), law, 2.0)
    velocity_change = res.impulse / PAPER_GRAIN.mass / 1000  # (1 + e) v / 1000: 3 mm/s
    problems = physics_problems(PAPER_GRAIN, res.peak_contact_force / 1000, velocity_change)
    assert len(problems) == 1 and "velocity change 0.00" in problems[0]
    assert "sensitivity" in problems[0]


def test_a_grain_in_millimetres_given_as_metres_is_flagged_by_its_force():
    """A 50 mg grain whose force is that of a 50 t one (diameter 5.0 instead of 5e-3)."""
    limits = impact_limits(PAPER_GRAIN)
    problems = physics_problems(PAPER_GRAIN, 107e3, 3.0)  # the 107 kN
    assert problems and f"{limits['peak_force [N]']:.3g} N" in problems[0]


def test_compare_trace_fails_on_an_impossible_measurement(tmp_path):
    config = cl.config.load_preset("fig6")
    model = config.simulate()
    signal = np.concatenate([np.zeros(100), model.sensor_force])
    dt = model.t[1] - model.t[0]
    t = np.concatenate([-dt * np.arange(100, 0, -1), model.t])
    good = compare_trace(Trace(t, signal, "N", metadata={"trigger_time": 0.0}), config)
    assert good.physics == []
    slipped = Trace(t, signal / 1000.0, "N", metadata={"trigger_time": 0.0})
    bad = compare_trace(slipped, config)
    assert not bad.passed and "physics" in bad.failed
    assert any("velocity change" in p for p in bad.physics)
    assert bad.to_dict()["physics"] == bad.physics
    assert "physics: velocity change" in str(bad)
