"""Kratos' elastic Coulomb cap (``Mindlin(coulomb_cap="elastic")``) on the compiled phase
loop (:mod:`contactlab.kernels.elastic_cap`, issue 25): closed forms and invariants, and
the outputs of the Python phase loop it replaced, recorded before the change
(``tests/golden/elastic_cap_python_loop.json``). The fixed-step replica of Kratos' law is
the independent method (``test_conventions.py``)."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import contactlab as cl
from contactlab import analytic
from contactlab.solver.conventions import DEM_CONVENTIONS

GOLDEN = json.loads(
    (Path(__file__).resolve().parents[2] / "golden" / "elastic_cap_python_loop.json").read_text()
)["cases"]

GRAIN = cl.Grain(diameter=5e-3, density=2500.0, youngs_modulus=7e10, poisson_ratio=0.25)
SENSOR = cl.Sensor(mass=2e-3, stiffness=5e7, damping=2.0)
T4 = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
"""Chung & Ooi's test-4 aluminium oxide sphere."""
ELASTIC = cl.laws.Hertz.from_material(*T4.material())
DAMPED = cl.laws.HertzDamped(  # e = 0.98, Kratos' own test-4 input
    ELASTIC.k_hertz,
    analytic.tsuji_damping_coefficient(ELASTIC.k_hertz, T4.mass, 0.98, "force"),
)
BASE = cl.laws.Mindlin.from_material(*T4.material(), 0.092)
KRATOS = DEM_CONVENTIONS["kratos"]


def _case(name):
    """The impact of the recorded case ``name`` (the recording script's set-ups)."""
    if name.startswith("test4_kratos_"):
        degrees = float(name.split("_")[-1].removesuffix("deg"))
        laws = (DAMPED, KRATOS.mindlin(BASE))
        return (T4, cl.Sensor.rigid(), *laws, 3.9, math.radians(degrees)), {"lever_arm": "contact"}
    normal = cl.laws.HertzDamped.from_material(*GRAIN.material(), 0.6, GRAIN.mass)
    tangential = cl.laws.Mindlin.from_material(
        *GRAIN.material(), 0.3, history="incremental", damping="tied", coulomb_cap="elastic"
    )
    if name == "kratos_like_sensor_20deg":
        return (GRAIN, SENSOR, normal, tangential, 1.0, math.radians(20.0)), {}
    return (GRAIN, SENSOR, normal, tangential, 1.0, math.radians(15.0)), {"spin": -300.0}


@pytest.fixture(scope="module")
def solved():
    return {name: cl.simulate_oblique(*args, **kw) for name, (args, kw) in map(
        lambda name: (name, _case(name)), GOLDEN)}


@pytest.mark.parametrize("name", sorted(GOLDEN))
def test_the_compiled_loop_gives_the_python_loops_rebound(solved, name):
    """The same equations, events and switch rules at rtol 1e-9, in numba instead of the
    Python DOP853 stepper: the rebound within the integration's tolerance."""
    res, old = solved[name], GOLDEN[name]
    vt = res.incident_tangential_velocity or res.velocity
    # two roundings of one method may take other steps: measured below, bound 100 rtol
    assert res.tangential_velocity == pytest.approx(old["tangential_velocity"], abs=1e-7 * vt)
    assert T4.radius * res.angular_velocity == pytest.approx(
        T4.radius * old["angular_velocity"], abs=1e-7 * vt
    )
    np.testing.assert_allclose(res._final, old["final_state"], rtol=1e-7, atol=1e-12)
