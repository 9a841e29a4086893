"""Tangential laws: stiffness from material data, the trial force and LAMMPS' rescaling."""

import math

import pytest

from contactlab import analytic
from contactlab.analytic import Material
from contactlab.errors import ParameterError
from contactlab.laws import Mindlin, TangentialSpring


def test_mindlin_from_material_rigid_flat():
    """kt = 8 G* a with G* = G / (2 - nu) on a rigid flat (Mindlin 1949)."""
    e, nu, r = 7.0e10, 0.33, 0.1
    law = Mindlin.from_material(Material(e, nu, r), 0.4)
    shear = e / (2 * (1 + nu))
    assert law.k_mindlin == pytest.approx(8 * shear / (2 - nu) * math.sqrt(r), rel=1e-14)
    d = 1e-6
    assert law.stiffness(d) == pytest.approx(8 * shear / (2 - nu) * math.sqrt(r * d), rel=1e-14)


def test_effective_shear_modulus_two_bodies():
    """Two identical bodies give half the one-body value (LAMMPS' mix_stiffnessG)."""
    e, nu = 4.8e10, 0.2
    one = analytic.effective_shear_modulus(e, nu)
    two = analytic.effective_shear_modulus(e, nu, e, nu)
    assert two == pytest.approx(one / 2, rel=1e-14)
    assert two == pytest.approx(e / (4 * (2 - nu) * (1 + nu)), rel=1e-14)


@pytest.mark.parametrize("history", ["total", "incremental"])
def test_history_on_cap_reproduces_the_cap(history):
    """After LAMMPS' rescaling, the trial force equals the capped force."""
    law = Mindlin(1e10, 0.3, history=history)
    d, slip, cap = 2e-7, 0.4, -1.7
    h = law.history_on_cap(cap, d, slip)
    assert law.trial_force(h, d, slip) == pytest.approx(cap, rel=1e-14)


def test_spring_with_damping():
    law = TangentialSpring(stiffness=1e6, friction=0.5, damping=2.0)
    assert law.trial_force(1e-6, 1e-5, 0.1) == pytest.approx(-1.0 - 0.2)
    assert law.history_on_cap(-1.2, 1e-5, 0.1) == pytest.approx(1e-6)
    with pytest.raises(ParameterError, match="damping"):
        TangentialSpring(stiffness=1e6, friction=0.5, damping=-1.0)
    with pytest.raises(TypeError):
        TangentialSpring(stiffness=1e6, friction=0.5, dampng=1.0)
