"""contactlab laws as Kratos DEM contact laws, as each law states it: exact coefficients,
or a refusal saying why.

The coefficients are checked against Kratos' own force formulas
(``DEM_D_Hertz_viscous_Coulomb_CL.cpp``, ``DEM_D_Linear_viscous_Coulomb_CL.cpp``) written
out here with the bodies' ``E1 = E2 = young``, ``nu = 0`` (so ``E* = young / 2``); that
Kratos then computes the law's impact is checked in tests/dem_check/engines/kratos/.
"""

import math

import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.laws import LAWS, kratos, lammps
from contactlab.laws.kratos import ENGINE_LAWS, REFUSED, kratos_contact

MASS, RADIUS = 5.0e-5, 2.5e-3  # effective mass [kg] and radius [m] of the contact
K_HERTZ = 4.0 / 3.0 * 21.6e6 * math.sqrt(RADIUS)  # the paper's grain on a rigid flat
OVERLAP, RATE = 1.3e-5, 0.7  # [m], [m/s]


def e_star(contact):
    """Kratos' ``E1 E2 / (E2 (1 - nu1**2) + E1 (1 - nu2**2))`` with equal E, nu = 0."""
    young = contact.young
    return young * young / (young + young)


def kratos_hertz_force(contact, overlap, rate):
    """``Kn = 2 E* sqrt(R* d)``, ``F = 2/3 Kn d + 2 gamma sqrt(m* Kn) d'``."""
    kn = 2.0 * e_star(contact) * math.sqrt(contact.effective_radius * overlap)
    damping = 2.0 * contact.gamma * math.sqrt(contact.effective_mass * kn) * rate
    return 2.0 / 3.0 * kn * overlap + damping


def kratos_linear_force(contact, overlap, rate, wall):
    """``Kn = pi 0.31225 E* R`` (wall) or 1.432 times that (spheres), ``F = Kn d + 2 gamma
    sqrt(m* Kn) d'``."""
    kn = math.pi * 0.31225 * e_star(contact) * contact.effective_radius
    kn *= 1.0 if wall else 1.432
    return kn * overlap + 2.0 * contact.gamma * math.sqrt(contact.effective_mass * kn) * rate


@pytest.mark.parametrize("wall", [True, False])
@pytest.mark.parametrize(
    "law",
    [cl.laws.Hertz(K_HERTZ), cl.laws.HertzDamped(K_HERTZ, 0.05)],
    ids=lambda law: type(law).__name__,
)
def test_hertz_family_is_kratos_hertz_law_with_the_same_force(law, wall):
    contact = kratos_contact(law, MASS, RADIUS, wall)
    assert contact.name == kratos.HERTZ_LAW
    # a square root, a product and a sum apart: a few ulps
    expected = float(law.force(OVERLAP, RATE))
    assert kratos_hertz_force(contact, OVERLAP, RATE) == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("wall", [True, False])
def test_linear_law_is_kratos_linear_law_with_the_same_force(wall):
    law = cl.laws.LinearViscoelastic(1e5, 0.7)
    contact = kratos_contact(law, MASS, RADIUS, wall)
    assert contact.name == kratos.LINEAR_LAW
    expected = float(law.force(OVERLAP, RATE))
    # a division and a multiplication by the same factor apart: a few ulps
    assert kratos_linear_force(contact, OVERLAP, RATE, wall) == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("mapping", [kratos, lammps], ids=["Kratos", "LAMMPS"])
def test_every_registered_law_maps_or_states_why_not(mapping):
    assert set(mapping.ENGINE_LAWS).isdisjoint(mapping.REFUSED)
    assert set(mapping.ENGINE_LAWS) | set(mapping.REFUSED) == set(LAWS.values())


def upper_typical(cls):
    """A law of class ``cls`` at the top of its typical ranges (damped, if it damps)."""
    return cls._from_typical(**{name: high for name, (_, high, _) in cls.typical.items()})


@pytest.mark.parametrize(
    "law", [upper_typical(cls) for cls in REFUSED], ids=lambda law: type(law).__name__
)
def test_laws_kratos_cannot_hold_are_refused_with_the_reason(law):
    name = type(law).__name__
    with pytest.raises(ParameterError, match=rf"law {name} cannot be represented in Kratos") as e:
        kratos_contact(law, MASS, RADIUS, True)
    assert REFUSED[type(law)] in str(e.value)
    assert "Supported exactly: LinearViscoelastic, Hertz, HertzDamped" in str(e.value)


def test_a_subclass_is_refused_as_its_force_may_differ():
    class Stiffer(cl.laws.Hertz):
        pass

    assert Stiffer not in ENGINE_LAWS
    with pytest.raises(ParameterError, match="law Stiffer cannot be represented in Kratos"):
        kratos_contact(Stiffer(K_HERTZ), MASS, RADIUS, True)
