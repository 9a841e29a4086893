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

M = 5.0e-5  # grain mass [kg], close to the paper's 5.007e-5
V = 2.0  # impact speed [m/s]
E_GRAIN = 21.6e6  # the paper's grain: E = 2 G (1 + nu) [Pa]
NU = 0.2
R = 2.5e-3  # [m]

EXACT = 1e-6
"""Closed forms that are exact for the law: the solver's events are roots of exact
expressions (exact method) or DOP853 at rtol 1e-10 (adaptive), far inside 1e-6."""


def wall(law, velocity=V, mass=M):
    return law.impact(mass, velocity)


@pytest.mark.parametrize("damping", [0.0, 0.3, 1.0, 3.0])
def test_linear_matches_force_zero_closed_form(damping):
    res = wall(LinearViscoelastic(1e5, damping))
    assert res.contact_time == pytest.approx(
        analytic.linear_contact_time(1e5, damping, M, convention="force"), rel=EXACT
    )
    assert res.restitution == pytest.approx(
        analytic.linear_restitution(1e5, damping, M, convention="force"), rel=EXACT
    )


@pytest.mark.parametrize("restitution", [0.3, 0.6, 0.9])
def test_linear_from_restitution_force_convention_is_realised(restitution):
    law = LinearViscoelastic.from_restitution(1e5, restitution, M, convention="force")
    assert wall(law).restitution == pytest.approx(restitution, rel=EXACT)


def test_linear_from_restitution_overlap_convention_realises_more():
    law = LinearViscoelastic.from_restitution(1e5, 0.5, M)
    # the DEM-code formula assumes the overlap-zero end; one-sided contact ends earlier
    e = wall(law).restitution
    assert e > 0.5
    assert e == pytest.approx(
        analytic.linear_restitution(1e5, law.damping, M, convention="force"), rel=EXACT
    )


@pytest.mark.parametrize("velocity", [0.5, 2.0, 8.0])
def test_hertz_matches_closed_form(velocity):
    law = Hertz.from_material(E_GRAIN, NU, R)
    res = wall(law, velocity)
    assert res.contact_time == pytest.approx(
        analytic.hertz_contact_time(law.k_hertz, M, velocity), rel=EXACT
    )
    assert res.peak_contact_force == pytest.approx(
        analytic.hertz_max_force(law.k_hertz, M, velocity), rel=EXACT
    )
    assert res.restitution == pytest.approx(1.0, rel=EXACT)


def test_hertz_paper_contact_times(paper_grain):
    # the notes' numbers (rounded to 0.1 us): 180.6 us for 5.0 mm and 90.3 us for 2.5 mm
    law = Hertz.from_material(*paper_grain.material())
    res = cl.simulate_impact(paper_grain, cl.Sensor.rigid(), law, velocity=2.0)
    assert res.contact_time == pytest.approx(180.6e-6, abs=0.05e-6)
    small = cl.Grain(diameter=2.5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
    law = Hertz.from_material(*small.material())
    res = cl.simulate_impact(small, cl.Sensor.rigid(), law, velocity=2.0)
    assert res.contact_time == pytest.approx(90.3e-6, abs=0.05e-6)


def test_hertz_second_body_softens_contact():
    rigid = Hertz.from_material(E_GRAIN, NU, R)
    grain_on_grain = Hertz.from_material(E_GRAIN, NU, R, E_GRAIN, NU, R)
    # two equal grains: E* halves, R* halves -> kH drops by 2 * sqrt(2)
    assert grain_on_grain.k_hertz == pytest.approx(rigid.k_hertz / 2 / math.sqrt(2), rel=1e-12)


@pytest.mark.parametrize("velocity", [0.5, 2.0, 6.0])
def test_hertz_damped_restitution_is_velocity_independent(velocity):
    law = HertzDamped.from_material(E_GRAIN, NU, R, 0.5, M)
    e_ref = wall(law, 1.0).restitution
    # Tsuji scaling: e depends only on alpha; both solves are accurate to ~1e-9
    assert wall(law, velocity).restitution == pytest.approx(e_ref, rel=EXACT)


def test_hertz_damped_matches_tsuji_restitution():
    law = HertzDamped.from_material(E_GRAIN, NU, R, 0.5, M)
    alpha = analytic.tsuji_damping_factor(0.5)
    assert wall(law).restitution == pytest.approx(
        analytic.tsuji_restitution(alpha, convention="force"), rel=EXACT
    )


@pytest.mark.parametrize("dissipation", [1e-7, 5e-7])
def test_kuwabara_kono_series(dissipation):
    law = KuwabaraKono(Hertz.from_material(E_GRAIN, NU, R).k_hertz, dissipation)
    x = analytic.kuwabara_kono_parameter(law.k_hertz, dissipation, M, V)
    e_series = analytic.kuwabara_kono_restitution(law.k_hertz, dissipation, M, V)
    # the two-term series leaves an O(x**2.5) remainder (Schwager & Poeschel 2008 expand in
    # half-integer powers); measured 0.24 x**2.5 here, so 0.5 x**2.5 must hold
    assert abs(wall(law).restitution - e_series) < 0.5 * x**2.5


@pytest.mark.parametrize("damping", [0.01, 0.1, 0.3])
def test_hunt_crossley_exact_restitution(damping):
    law = HuntCrossley(1e7, 1.5, damping)
    assert wall(law).restitution == pytest.approx(
        analytic.hunt_crossley_restitution(damping, V), rel=EXACT
    )


@pytest.mark.parametrize("k_unload", [1e5, 2e5, 1e6])
def test_walton_braun_closed_form(k_unload):
    law = WaltonBraun(1e5, k_unload)
    res = wall(law)
    assert res.restitution == pytest.approx(
        analytic.walton_braun_restitution(1e5, k_unload), rel=EXACT
    )
    assert res.contact_time == pytest.approx(
        analytic.walton_braun_contact_time(1e5, k_unload, M), rel=EXACT
    )


@pytest.mark.parametrize("yield_force", [1.0, 3.0, 10.0])
def test_linear_plastic_closed_form(yield_force):
    law = LinearPlastic(1e5, yield_force)
    res = wall(law)
    assert res.restitution == pytest.approx(
        analytic.linear_plastic_restitution(1e5, yield_force, M, V), rel=EXACT
    )
    assert res.contact_time == pytest.approx(
        analytic.linear_plastic_contact_time(1e5, yield_force, M, V), rel=EXACT
    )
    assert res.peak_contact_force == pytest.approx(
        min(yield_force, V * math.sqrt(1e5 * M)), rel=EXACT
    )


@pytest.mark.parametrize("yield_pressure", [2e5, 1e6, 3e6])
def test_thornton_restitution(yield_pressure):
    e_star = analytic.effective_modulus(E_GRAIN, NU)
    law = Thornton(e_star, R, yield_pressure)
    expected = analytic.thornton_restitution(e_star, R, yield_pressure, M, V)
    assert wall(law).restitution == pytest.approx(expected, rel=EXACT)


def test_plastic_trapezoid_stops_the_grain():
    law = PlasticTrapezoid(100e-6, 10e-6)
    res = wall(law)
    # impulse m v0 exactly; the rest is Gauss-Legendre on straight pieces (exact)
    assert res.impulse == pytest.approx(M * V, rel=1e-12)
    assert abs(res.restitution) < 1e-12
    assert res.contact_time == 100e-6


# --- properties for every law -------------------------------------------------------
def _law_strategy():
    k = st.floats(1e3, 1e7)
    kh = st.floats(1e6, 1e9)
    frac = st.floats(0.05, 1.0)
    return st.one_of(
        st.builds(LinearViscoelastic, k, st.floats(0.0, 5.0)),
        st.builds(Hertz, kh),
        st.builds(HertzDamped, kh, st.floats(0.0, 2.0)),
        st.builds(KuwabaraKono, kh, st.floats(0.0, 1e-5)),
        st.builds(HuntCrossley, kh, st.just(1.5), st.floats(0.0, 0.5)),
        st.builds(lambda k1, f: WaltonBraun(k1, k1 / f), k, frac),
        st.builds(LinearPlastic, k, st.floats(0.05, 20.0)),
        st.builds(Thornton, st.floats(1e6, 1e8), st.floats(5e-4, 5e-3), st.floats(1e5, 1e7)),
    )


@settings(max_examples=60, deadline=None)
@given(law=_law_strategy(), velocity=st.floats(0.1, 10.0))
def test_impact_invariants(law, velocity):
    res = wall(law, velocity)
    assert np.all(res.contact_force >= 0.0)
    assert 0.0 <= res.restitution <= 1.0 + 1e-9  # 1e-9: solver accuracy on an elastic law
    momentum = M * velocity * (1.0 + res.restitution)
    # impulse by Gauss-Legendre on the dense solution vs momentum change; 1e-6 covers the
    # d**0.25 start of damped Hertz, where the quadrature converges slowest
    assert res.impulse == pytest.approx(momentum, rel=1e-6)
    kinetic_in = 0.5 * M * velocity**2
    kinetic_change = 0.5 * M * res.v2[-1] ** 2 - kinetic_in
    # same quadrature bound; abs 1e-8 of the energy in: the solver's local rtol 1e-10
    # accumulated over ~100 steps, which an elastic impact's near-zero change cannot beat
    assert res.grain_work == pytest.approx(kinetic_change, rel=1e-6, abs=1e-8 * kinetic_in)


@settings(max_examples=60, deadline=None)
@given(law=_law_strategy(), d_max=st.floats(1e-7, 1e-4))
def test_force_never_tensile_and_cycle_passive(law, d_max):
    d = np.concatenate([np.linspace(0.0, d_max, 200), np.linspace(d_max, 0.0, 200)])
    rate = np.concatenate([np.full(200, 0.5), np.full(200, -0.5)])
    history = np.maximum.accumulate(d)
    force = law.force(d, rate, history)
    assert np.all(force >= 0.0)
    assert np.all(law.force(-d - 1e-9, rate) == 0.0)
    # quasi-static loading-unloading cycle: the law may store but not create energy
    assert law.work(d) >= -1e-12 * law.force(d_max) * d_max


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
