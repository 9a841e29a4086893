"""The compiled oblique solver against an independent reference: scipy's solve_ivp on the
same equations, written in Python from the laws' methods (``oblique_reference.py``)."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import contactlab as cl

sys.path.insert(0, str(Path(__file__).parent))
from oblique_reference import ObliqueReference

GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
HERTZ = cl.laws.Hertz.from_material(GRAIN.material())
DAMPED = cl.laws.HertzDamped(HERTZ.k_hertz, 0.3 * math.sqrt(HERTZ.k_hertz * GRAIN.mass))
SENSOR = cl.Sensor(mass=1e-3, stiffness=1e7, damping=2.0)
SPEED, RTOL = 3.9, 1e-10


@pytest.mark.parametrize("sensor", [cl.Sensor.rigid(), SENSOR], ids=["flat", "sensor"])
@pytest.mark.parametrize("normal", [HERTZ, DAMPED], ids=["hertz", "damped"])
@pytest.mark.parametrize("history", ["total", "incremental_rescaled"])
@pytest.mark.parametrize(("degrees", "spin"), [(5.0, 0.0), (20.0, 300.0)])
def test_rebound_and_phases_match_solve_ivp(sensor, normal, history, degrees, spin):
    """Chung & Ooi's alumina grain: stick-slip-stick at 5 deg, with spin at 20 deg."""
    law = cl.laws.Mindlin.from_material(
        cl.analytic.Material(3.8e11, 0.23, GRAIN.radius), 0.092, history=history
    )
    angle = math.radians(degrees)
    res = cl.simulate_oblique(GRAIN, sensor, normal, law, SPEED, angle, spin=spin, rtol=RTOL)
    length = SPEED * 1e-6
    history_scale = length if law.history_kind == "displacement" else GRAIN.mass * SPEED / 1e-6
    scales = np.array([length, SPEED, length, SPEED, SPEED, SPEED / GRAIN.radius, history_scale])
    reference = ObliqueReference(GRAIN, sensor, normal, law)
    y, phases = reference.solve(SPEED, angle, spin, RTOL, 1e-3 * RTOL * scales)
    # both at rtol 1e-10 over ~100 steps a contact: measured worst 9e-10 of V (48 cases)
    tolerance = 1e-8
    assert abs(res.tangential_velocity - y[4]) < tolerance * SPEED
    assert abs(res.angular_velocity - y[5]) * GRAIN.radius < tolerance * SPEED
    assert abs(res.rebound_normal_velocity + y[3]) < tolerance * SPEED
    assert [name for *_, name in res.phases] == [
        {0: "stick", 1: "slide+", -1: "slide-"}[code] for *_, code in phases
    ]
    ends = np.array([t1 for _, t1, _ in res.phases])
    # event times: the same 1e-8 as the states, of the contact time
    np.testing.assert_allclose(ends, [t1 for _, t1, _ in phases], rtol=0, atol=1e-8 * ends[-1])
