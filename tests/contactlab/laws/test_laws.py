"""Contact laws: impacts on an immovable wall against closed forms, properties, bad input."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab import analytic
from contactlab.laws import (
    LAWS,
    Hertz,
    HertzDamped,
    HuntCrossley,
    KuwabaraKono,
    LinearPlastic,
    LinearViscoelastic,
    PlasticTrapezoid,
    Thornton,
    WaltonBraun,
    get_law,
)
from contactlab.solver.wall import wall_impact
from contactlab.testing import (
    assert_contact_time,
    assert_matches_closed_form,
    assert_passive,
    assert_restitution,
)
from contactlab.testing.strategies import impact_velocities, laws

M = 5.0e-5  # grain mass [kg], close to the paper's 5.007e-5
GRAIN = cl.Grain.from_mass(M)
V = 2.0  # impact speed [m/s]
E_GRAIN = 21.6e6  # the paper's grain: E = 2 G (1 + nu) [Pa]
NU = 0.2
R = 2.5e-3  # [m]

EXACT = 1e-6
"""Closed forms that are exact for the law: the solver's events are roots of exact
expressions (exact method) or DOP853 at rtol 1e-10 (adaptive), far inside 1e-6."""


def wall(law, velocity=V, mass=M):
    return wall_impact(law, mass, velocity)


@pytest.mark.parametrize("damping", [0.0, 0.3, 1.0, 3.0])
def test_linear_matches_force_zero_closed_form(damping):
    assert_matches_closed_form(LinearViscoelastic(1e5, damping), GRAIN, V, rtol=EXACT)


@pytest.mark.parametrize("restitution", [0.3, 0.6, 0.9])
def test_linear_from_restitution_force_convention_is_realised(restitution):
    law = LinearViscoelastic.from_restitution(1e5, restitution, M, convention="force")
    assert_restitution(law, GRAIN, V, restitution, rtol=EXACT, source="the target of the mapping")


def test_linear_from_restitution_overlap_convention_realises_more():
    law = LinearViscoelastic.from_restitution(1e5, 0.5, M)
    # the DEM-code formula assumes the overlap-zero end; one-sided contact ends earlier
    res = assert_matches_closed_form(law, GRAIN, V, rtol=EXACT)
    assert res.restitution > 0.5


@pytest.mark.parametrize("velocity", [0.5, 2.0, 8.0])
def test_hertz_matches_closed_form(velocity):
    assert_matches_closed_form(
        Hertz.from_material(cl.analytic.Material(E_GRAIN, NU, R)), GRAIN, velocity, rtol=EXACT
    )


def test_hertz_paper_contact_times(paper_grain, paper_grain_small):
    # the notes' numbers are rounded to 0.1 us, hence the absolute 0.05 us
    for grain, expected in ((paper_grain, 180.6e-6), (paper_grain_small, 90.3e-6)):
        law = Hertz.from_material(grain.material())
        assert_contact_time(
            law, grain, 2.0, expected, rtol=0.0, atol=0.05e-6, source="paper/NOTES.md"
        )


def test_hertz_second_body_softens_contact():
    rigid = Hertz.from_material(cl.analytic.Material(E_GRAIN, NU, R))
    grain_on_grain = Hertz.from_material(
        cl.analytic.Material(E_GRAIN, NU, R), cl.analytic.Material(E_GRAIN, NU, R)
    )
    # two equal grains: E* halves, R* halves -> kH drops by 2 * sqrt(2)
    assert grain_on_grain.k_hertz == pytest.approx(rigid.k_hertz / 2 / math.sqrt(2), rel=1e-12)


@pytest.mark.parametrize("velocity", [0.5, 2.0, 6.0])
def test_hertz_damped_restitution_is_velocity_independent(velocity):
    law = HertzDamped.from_material(cl.analytic.Material(E_GRAIN, NU, R), 0.5, M)
    e_ref = wall(law, 1.0).restitution
    # Tsuji scaling: e depends only on alpha; both solves are accurate to ~1e-9
    assert_restitution(law, GRAIN, velocity, e_ref, rtol=EXACT, source="the impact at 1 m/s")


def test_hertz_damped_matches_tsuji_restitution():
    law = HertzDamped.from_material(cl.analytic.Material(E_GRAIN, NU, R), 0.5, M)
    assert_matches_closed_form(law, GRAIN, V, rtol=EXACT)


@pytest.mark.parametrize("dissipation", [1e-7, 5e-7])
def test_kuwabara_kono_series(dissipation):
    law = KuwabaraKono(
        Hertz.from_material(cl.analytic.Material(E_GRAIN, NU, R)).k_hertz, dissipation
    )
    # rtol 0: the tolerance is the closed form's own allowance 0.5 x**2.5 (the two-term
    # series leaves an O(x**2.5) remainder, Schwager & Poeschel 2008 expand in
    # half-integer powers; measured 0.24 x**2.5 here)
    assert_matches_closed_form(law, GRAIN, V, rtol=0.0)


@pytest.mark.parametrize("damping", [0.01, 0.1, 0.3])
def test_hunt_crossley_exact_restitution(damping):
    assert_matches_closed_form(HuntCrossley(1e7, 1.5, damping), GRAIN, V, rtol=EXACT)


@pytest.mark.parametrize("k_unload", [1e5, 2e5, 1e6])
def test_walton_braun_closed_form(k_unload):
    assert_matches_closed_form(WaltonBraun(1e5, k_unload), GRAIN, V, rtol=EXACT)


@pytest.mark.parametrize("yield_force", [1.0, 3.0, 10.0])
def test_linear_plastic_closed_form(yield_force):
    assert_matches_closed_form(LinearPlastic(1e5, yield_force), GRAIN, V, rtol=EXACT)


@pytest.mark.parametrize("yield_pressure", [2e5, 1e6, 3e6])
def test_thornton_restitution(yield_pressure):
    law = Thornton(analytic.effective_modulus(E_GRAIN, NU), R, yield_pressure)
    assert_matches_closed_form(law, GRAIN, V, rtol=EXACT)


def test_plastic_trapezoid_stops_the_grain():
    law = PlasticTrapezoid(100e-6, 10e-6)
    # rtol 0: duration and plateau are prescribed, so they come out exactly; the
    # restitution 0 has its registered allowance of 1e-12 (roundoff)
    res = assert_matches_closed_form(law, GRAIN, V, rtol=0.0)
    # impulse m v0 exactly; the rest is Gauss-Legendre on straight pieces (exact)
    assert res.impulse == pytest.approx(M * V, rel=1e-12)


# --- properties for every law -------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(law=laws(), velocity=impact_velocities())
def test_impact_invariants(law, velocity):
    res = wall(law, velocity)
    assert np.all(res.contact_force >= 0.0)
    # 2e-8: DOP853's local rtol 1e-10 accumulated over the ~100-200 steps of an elastic
    # contact (measured up to 8.6e-9 over Hertz stiffness 1e6-1e9 and 0.1-10 m/s)
    assert 0.0 <= res.restitution <= 1.0 + 2e-8
    momentum = M * velocity * (1.0 + res.restitution)
    # impulse by Gauss-Legendre on the dense solution vs momentum change; 1e-6 covers the
    # d**0.25 start of damped Hertz, where the quadrature converges slowest
    assert res.impulse == pytest.approx(momentum, rel=1e-6)
    kinetic_in = 0.5 * M * velocity**2
    kinetic_change = 0.5 * M * res.v2[-1] ** 2 - kinetic_in
    # same quadrature bound; abs 4e-8 of the energy in: twice the restitution bound above
    # (energy goes with v**2), which an elastic impact's near-zero change cannot beat
    assert res.grain_work == pytest.approx(kinetic_change, rel=1e-6, abs=4e-8 * kinetic_in)


@settings(max_examples=60, deadline=None)
@given(law=laws(), d_max=st.floats(1e-7, 1e-4))
def test_force_never_tensile_and_cycle_passive(law, d_max):
    d = np.concatenate([np.linspace(0.0, d_max, 200), np.linspace(d_max, 0.0, 200)])
    rate = np.concatenate([np.full(200, 0.5), np.full(200, -0.5)])
    history = np.maximum.accumulate(d)
    force = law.force(d, rate, history)
    assert np.all(force >= 0.0)
    assert np.all(law.force(-d - 1e-9, rate) == 0.0)
    # the law may store and dissipate energy but not create it, quasi-statically and at speed
    assert_passive(law, d_max)
    assert_passive(law, d_max, rate=0.5)


# --- bad input --------------------------------------------------------------------
@pytest.mark.parametrize("bad", [-1.0, 0.0, math.nan, math.inf, "1e5", None, True])
def test_bad_stiffness_named(bad):
    with pytest.raises(cl.ParameterError, match="stiffness"):
        LinearViscoelastic(stiffness=bad, damping=0.1)


@pytest.mark.parametrize(
    ("cls", "kwargs", "name"),
    [
        (Hertz, {"k_hertz": -1.0}, "k_hertz"),
        (HertzDamped, {"k_hertz": 1e8, "damping": math.nan}, "damping"),
        (KuwabaraKono, {"k_hertz": 1e8, "dissipation": -1e-6}, "dissipation"),
        (HuntCrossley, {"stiffness": 1e8, "exponent": 0.5, "damping": 0.1}, "exponent"),
        (WaltonBraun, {"loading_stiffness": 2e5, "unloading_stiffness": 1e5}, "unloading"),
        (LinearPlastic, {"stiffness": 1e5, "yield_force": 0.0}, "yield_force"),
        (
            Thornton,
            {"effective_modulus": 1e7, "effective_radius": 1e-3, "yield_pressure": math.inf},
            "yield_pressure",
        ),
        (PlasticTrapezoid, {"contact_time": 1e-4, "ramp_time": 6e-5}, "ramp_time"),
    ],
)
def test_bad_parameters_named(cls, kwargs, name):
    with pytest.raises(cl.ParameterError, match=name):
        cls(**kwargs)


def test_unknown_keyword_lists_valid_names():
    with pytest.raises(cl.ParameterError, match="valid parameters are stiffness, damping") as info:
        LinearViscoelastic(stiffness=1e5, dampin=0.1)
    assert isinstance(info.value, TypeError)


def test_registry():
    assert set(LAWS) >= {"linear", "hertz", "hertz_damped", "walton_braun", "plastic_trapezoid"}
    assert get_law("linear", stiffness=1e5) == LinearViscoelastic(1e5)
    with pytest.raises(cl.ParameterError, match="Did you mean 'hertz'"):
        get_law("herz", k_hertz=1e8)
