"""ObliqueResult holds data: arrays and numbers the solver computed, read with the compiled
sampler below it; its names are the vocabulary's (issue 25)."""

import math

import numpy as np
import pytest

import contactlab as cl
from contactlab.kernels.oblique_sample import ContactPhases
from contactlab.oblique_result import HEADLINE, SIGNALS
from contactlab.quantities import column, columns

GRAIN = cl.Grain(diameter=5e-3, density=2500.0, youngs_modulus=7e10, poisson_ratio=0.25)
SENSOR = cl.Sensor(mass=2e-3, stiffness=5e7, damping=2.0)


def _kratos_like():
    """Damped Hertz and a tied-damping Mindlin law with Kratos' elastic Coulomb cap (its
    own compiled phase loop), at an angle that sticks, then slides."""
    normal = cl.laws.HertzDamped.from_material(GRAIN.material(), 0.6, GRAIN.mass)
    tangential = cl.laws.Mindlin.from_material(
        GRAIN.material(), 0.3, history="incremental", damping="tied", coulomb_cap="elastic"
    )
    return cl.simulate_oblique(GRAIN, SENSOR, normal, tangential, 1.0, math.radians(20.0))


@pytest.fixture(scope="module")
def elastic_cap():
    return _kratos_like()


def _plain(value):
    """Whether ``value`` is data: a number, string, array, law, body, the solved contact's
    arrays (:class:`ContactPhases`, evaluated below the result) or a tuple of them."""
    if isinstance(value, (tuple, list)):
        return all(_plain(v) for v in value)
    data = (cl.laws.ContactLaw, cl.laws.TangentialLaw, ContactPhases)
    return not callable(value) or isinstance(value, data)


def test_the_result_holds_no_solver_object_or_closure(elastic_cap):
    module = {name: type(value).__module__ for name, value in vars(elastic_cap).items()}
    assert not [name for name, where in module.items() if where.startswith("contactlab.solver")]
    assert all(_plain(value) for value in vars(elastic_cap).values())
    assert isinstance(elastic_cap._contact, ContactPhases)


def test_the_elastic_cap_contact_samples_as_the_law_says(elastic_cap):
    """The elastic cap's compiled phases, read by the sampler, give the tangential force
    the law's own Python methods give on the same states."""
    res, law = (
        elastic_cap,
        elastic_cap.tangential_law.for_contact(elastic_cap.normal_law, GRAIN.mass),
    )
    phases = res.phases
    assert {code for _, _, code in phases} >= {"stick"} and len(phases) > 1
    for t0, t1, code in phases:
        times = np.linspace(t0, t1, 41)[1:-1]
        states, _, normal, tangential, slip = res._contact(times)
        d = states[:, 2] - states[:, 0]
        if code == "stick":
            expected = law.trial_force(states[:, 6], d, slip)
        else:
            expected = (1.0 if code == "slide+" else -1.0) * law.friction * normal
        scale = res.peak_tangential_force
        # the same formula in numba and in numpy: rounding only (measured 0: equal bits)
        np.testing.assert_allclose(tangential, expected, rtol=0.0, atol=1e-12 * scale)


def test_frame_and_summary_use_the_vocabulary(elastic_cap):
    frame = elastic_cap.to_frame()
    assert tuple(frame.columns) == columns(*SIGNALS)
    np.testing.assert_array_equal(
        frame[column("tangential_velocity")], elastic_cap.tangential_velocity_signal
    )
    summary = elastic_cap.summary()
    assert {column(name) for name in HEADLINE} <= set(summary)
    assert summary[column("angle")] == elastic_cap.angle
