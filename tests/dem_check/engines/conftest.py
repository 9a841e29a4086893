"""Fixtures the DEM engines' tests share: the paper's grain and one law of each kind the
engines map exactly."""

import pytest

import contactlab as cl
from contactlab import analytic

E_STAR = 21.6e6  # the paper's grain on a rigid flat, E* [Pa]


@pytest.fixture(scope="module")
def grain():
    """The paper's 5 mm grain (5.007e-5 kg)."""
    return cl.Grain(diameter=5e-3, density=765.0)


@pytest.fixture(scope="module")
def laws(grain):
    """One law of each mapped kind, at the paper's scale (Kratos holds all but
    Kuwabara-Kono)."""
    k_hertz = analytic.hertz_stiffness(E_STAR, grain.radius)
    return {
        "linear": cl.laws.LinearViscoelastic(1e5, 1.0),
        "hertz": cl.laws.Hertz(k_hertz),
        "hertz_damped": cl.laws.HertzDamped.from_material(
            cl.analytic.Material(E_STAR, 0.2, grain.radius), 0.5, grain.mass
        ),
        "kuwabara_kono": cl.laws.KuwabaraKono(k_hertz, 2e-6),
    }
