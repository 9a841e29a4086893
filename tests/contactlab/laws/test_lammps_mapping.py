"""contactlab laws as LAMMPS granular models: exact coefficients, or a refusal saying why.

The coefficients are checked against LAMMPS' own force formulas (granular_model.cpp,
gran_sub_mod_normal.cpp, gran_sub_mod_damping.cpp) written out here; that LAMMPS then
computes exactly the law's force, step by step, is checked in
tests/dem_check/engines/lammps/test_drop.py; the exporter writes the same words
(tests/contactlab/inverse/test_export_dem.py).
"""

import math

import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.laws.lammps import ENGINE_LAWS, REFUSED, granular_model

MASS, RADIUS = 5.0e-5, 2.5e-3  # effective mass [kg] and radius [m] of the contact
K_HERTZ = 4.0 / 3.0 * 21.6e6 * math.sqrt(RADIUS)  # the paper's grain on a rigid flat


def lammps_hertz_force(model, overlap):
    """LAMMPS ``hertz k``: ``k a d`` with ``a = sqrt(R* d)``."""
    return model.stiffness * math.sqrt(model.effective_radius * overlap) * overlap


def test_linear_law_is_hooke_with_velocity_damping():
    model = granular_model(cl.laws.LinearViscoelastic(1e5, 0.7), MASS, RADIUS)
    assert (model.normal, model.damping) == ("hooke", "velocity")
    assert (model.stiffness, model.damping_coefficient) == (1e5, 0.7)  # taken as they are


@pytest.mark.parametrize("law", [cl.laws.Hertz(K_HERTZ), cl.laws.KuwabaraKono(K_HERTZ, 2e-6)])
def test_hertz_stiffness_absorbs_the_effective_radius(law):
    model = granular_model(law, MASS, RADIUS)
    overlap = 1.3e-5  # [m]
    # k sqrt(R* d) d = kH d**1.5: one sqrt and a division apart, a few ulps
    assert lammps_hertz_force(model, overlap) == pytest.approx(K_HERTZ * overlap**1.5, rel=1e-14)


def test_kuwabara_kono_is_viscoelastic_damping():
    law = cl.laws.KuwabaraKono(K_HERTZ, 2e-6)
    model = granular_model(law, MASS, RADIUS)
    assert model.damping == "viscoelastic"
    overlap = 1.3e-5  # [m]
    contact_radius = math.sqrt(RADIUS * overlap)
    # LAMMPS' viscoelastic damping prefactor eta m* a against 1.5 A kH d**0.5: a few ulps
    assert model.damping_coefficient * MASS * contact_radius == pytest.approx(
        1.5 * law.dissipation * K_HERTZ * overlap**0.5, rel=1e-14
    )


@pytest.mark.parametrize("restitution", [0.05, 0.3, 0.5, 0.9, 0.999])
def test_hertz_damped_restitution_input_gives_the_laws_damping(restitution):
    law = cl.laws.HertzDamped.from_material(
        cl.analytic.Material(21.6e6, 0.2, RADIUS), restitution, MASS
    )
    model = granular_model(law, MASS, RADIUS)
    assert model.damping == "coeff_restitution"
    log_e = math.log(model.damping_coefficient)
    # LAMMPS' coeff_restitution on hertz: damp = sqrt(3/2) 2 sqrt(5/6) (-ln e)/sqrt(pi^2+ln^2 e)
    damp = -math.sqrt(1.5) * 2.0 * math.sqrt(5.0 / 6.0) * log_e / math.hypot(math.pi, log_e)
    overlap = 1.3e-5  # [m]
    elastic = lammps_hertz_force(model, overlap)
    # prefactor damp sqrt(m* Fe/d) against eta d**0.25: exp/log round trip, ~1e-15
    assert damp * math.sqrt(MASS * elastic / overlap) == pytest.approx(
        law.damping * overlap**0.25, rel=1e-13
    )
    # the fit's restitution is the overlap-convention one, which is LAMMPS' input: the
    # mapping recovers it (same m*), to the exp/log round trip
    assert model.damping_coefficient == pytest.approx(restitution, rel=1e-13)


def test_undamped_hertz_damped_maps_to_restitution_one():
    model = granular_model(cl.laws.HertzDamped(K_HERTZ, 0.0), MASS, RADIUS)
    assert model.damping_coefficient == 1.0  # ln 1 = 0: no damping


def test_hertz_damped_beyond_lammps_reach_names_the_damping():
    too_damped = math.sqrt(5.0) * math.sqrt(MASS * K_HERTZ)  # alpha = sqrt(5)
    with pytest.raises(ParameterError, match=r"HertzDamped: damping = .*alpha.*sqrt\(5\)"):
        granular_model(cl.laws.HertzDamped(K_HERTZ, too_damped), MASS, RADIUS)


@pytest.mark.parametrize(
    "law",
    [
        cl.laws.HuntCrossley(1e6, 1.5, 0.1),
        cl.laws.WaltonBraun(1e5, 2e5),
        cl.laws.LinearPlastic(1e5, 1.0),
        cl.laws.Thornton(21.6e6, RADIUS, 1e6),
        cl.laws.PlasticTrapezoid(1e-4, 1e-5),
    ],
    ids=lambda law: type(law).__name__,
)
def test_laws_lammps_cannot_hold_are_refused_with_the_reason(law):
    name = type(law).__name__
    with pytest.raises(ParameterError, match=rf"law {name} cannot be represented in LAMMPS") as e:
        granular_model(law, MASS, RADIUS)
    assert REFUSED[type(law)] in str(e.value)
    assert "LinearViscoelastic, Hertz, HertzDamped, HertzViscous, KuwabaraKono" in str(e.value)


def test_a_subclass_is_refused_as_its_force_may_differ():
    class Stiffer(cl.laws.Hertz):
        pass

    with pytest.raises(ParameterError, match="law Stiffer cannot be represented"):
        granular_model(Stiffer(K_HERTZ), MASS, RADIUS)


def test_words_are_one_sided_and_write_floats_exactly():
    model = granular_model(cl.laws.Hertz(K_HERTZ), MASS, RADIUS)
    words = model.words().split()
    assert words[-1] == "limit_damping"  # one-sided: never tensile
    assert float(words[1]) == model.stiffness  # 17 digits: LAMMPS reads the same double
    assert set(ENGINE_LAWS) == {
        cl.laws.LinearViscoelastic,
        cl.laws.Hertz,
        cl.laws.HertzDamped,
        cl.laws.HertzViscous,
        cl.laws.KuwabaraKono,
    }
