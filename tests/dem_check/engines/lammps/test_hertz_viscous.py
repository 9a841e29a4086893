"""LAMMPS' ``hertz`` with ``damping velocity`` holds HertzViscous exactly, step by step,
and its drop test agrees with the reduced model."""

import numpy as np
import pytest

import contactlab as cl
from contactlab.config import ImpactConfig
from contactlab.laws import HertzViscous
from dem_check.engines.lammps import drop_test

pytestmark = pytest.mark.lammps

V0 = 2.0  # impact speed [m/s]


def test_hertz_viscous_runs_in_lammps(grain):
    law = HertzViscous(1.5e6, 0.01)
    res = drop_test(ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": V0}))
    half_step_rate = res.v2 + 0.5 * res.time_step * res.contact_force / grain.mass
    expected = law.force(res.overlap, half_step_rate)
    # rounding only, as for the other mapped laws (test_drop.py: measured 2e-16 to 4e-16)
    assert np.max(np.abs(res.contact_force - expected)) < 1e-13 * res.peak_contact_force
    reference = cl.wall_impact(law, grain.mass, V0)
    # velocity Verlet at the default step, damping at the half-step velocity (first
    # order): measured 5e-6 (contact time) and 3e-7 (restitution) on a sensor, c = 0.01
    assert res.contact_time == pytest.approx(reference.contact_time, rel=5e-5)
    assert res.restitution == pytest.approx(reference.restitution, rel=5e-5)
