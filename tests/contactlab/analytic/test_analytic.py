"""Closed forms of contactlab.analytic against independent methods, known numbers and limits.

The independent method is direct integration of m x'' = -F(x, x') from first touch with
scipy's DOP853 at rtol 1e-11, ending at an exact event (zero overlap or zero force).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from contactlab import analytic as an
from contactlab.errors import ParameterError

RTOL = 1e-11  # integration tolerance; events are located to machine precision on top

# The paper's grain (keska2021, NOTES.md): 5 mm, 765 kg/m^3, G = 9 MPa, nu = 0.2, 2 m/s.
MASS = 765.0 * math.pi / 6.0 * 5e-3**3
STIFFNESS = 1e5
VELOCITY = 2.0


def _paper_k_hertz(diameter):
    e_star = an.effective_modulus(an.youngs_from_shear(9e6, 0.2), 0.2)
    return an.hertz_stiffness(e_star, an.effective_radius(diameter / 2))


def _integrate(accel, state, end, length, t_max, extra_events=()):
    """Integrate x'' = accel(x, x') from ``state`` until the terminal event ``end``.

    ``length`` is the overlap scale [m]; the absolute tolerance is 1e-6 of the relative
    one on that scale so that small late overlaps stay resolved. Returns the solve_ivp
    result; ``status == 1`` when ``end`` was reached.
    """

    def rhs(t, y):
        return [y[1], accel(y[0], y[1])]

    def end_event(t, y):
        return end(y[0], y[1])

    end_event.terminal = True
    end_event.direction = -1
    speed = abs(state[1]) or length / t_max
    return solve_ivp(
        rhs,
        (0.0, t_max),
        state,
        method="DOP853",
        rtol=RTOL,
        atol=[1e-6 * RTOL * length, 1e-6 * RTOL * speed],
        events=[end_event, *extra_events],
    )


def _impact(force, mass, velocity, convention, length, t_max):
    """One impact of m x'' = -force(x, x') with x(0) = 0, x'(0) = v.

    Returns (contact time [s], restitution [-], largest overlap [m]); (inf, 0, .) if the
    contact has not ended by ``t_max``. Under "force" the end event is the force while
    x > 0 and x itself after, so it changes sign even where the force only reaches zero
    together with the overlap.
    """

    def loaded(x, v):
        return force(max(x, 0.0), v)

    def force_end(x, v):
        return force(x, v) if x > 0.0 else x

    def at_rest(t, y):
        return y[1]

    at_rest.direction = -1
    end = (lambda x, v: x) if convention == "overlap" else force_end
    sol = _integrate(
        lambda x, v: -loaded(x, v) / mass, [0.0, velocity], end, length, t_max, [at_rest]
    )
    d_max = sol.y_events[1][0][0]
    if sol.status != 1:
        return math.inf, 0.0, d_max
    return sol.t_events[0][0], -sol.y_events[0][0][1] / velocity, d_max


# --- material helpers -----------------------------------------------------------------------


def test_effective_values_of_two_equal_bodies_halve():
    # three reciprocals, each rounded once
    assert an.effective_mass(2e-3, 2e-3) == pytest.approx(1e-3, rel=1e-15)
    assert an.effective_radius(4e-3, 4e-3) == pytest.approx(2e-3, rel=1e-15)
    assert an.effective_modulus(2e9, 0.0, 2e9, 0.0) == pytest.approx(1e9, rel=1e-15)


def test_effective_values_against_a_wall_are_the_body_values():
    # 1/(1/m + 0) reproduces m to rounding
    assert an.effective_mass(MASS) == pytest.approx(MASS, rel=1e-15)
    assert an.effective_radius(2.5e-3) == pytest.approx(2.5e-3, rel=1e-15)
    assert an.effective_modulus(21.6e6, 0.2) == pytest.approx(21.6e6 / 0.96, rel=1e-15)


def test_youngs_from_shear_gives_the_paper_value():
    # NOTES.md: G = 9 MPa, nu = 0.2 -> E = 21.6 MPa; rounding only
    assert an.youngs_from_shear(9e6, 0.2) == pytest.approx(21.6e6, rel=1e-15)


# --- Hertz ----------------------------------------------------------------------------------


def test_hertz_time_factor_is_the_integral():
    value, _ = quad(lambda u: 2.0 / math.sqrt(1.0 - u**2.5), 0.0, 1.0)
    # quad's estimate on an integrable endpoint singularity is good to ~1e-10
    assert an.HERTZ_TIME_FACTOR == pytest.approx(value, rel=1e-9)


@pytest.mark.parametrize(("diameter", "expected_us"), [(5e-3, 180.6), (2.5e-3, 90.3)])
def test_hertz_contact_time_reproduces_the_paper_notes(diameter, expected_us):
    mass = 765.0 * math.pi / 6.0 * diameter**3
    t_c = an.hertz_contact_time(_paper_k_hertz(diameter), mass, VELOCITY)
    # the notes round to 0.1 us
    assert abs(t_c * 1e6 - expected_us) <= 0.05


@pytest.mark.parametrize("diameter", [2.5e-3, 5e-3, 12e-3])
def test_hertz_contact_time_matches_the_textbook_constant(diameter):
    mass = 765.0 * math.pi / 6.0 * diameter**3
    e_star = an.effective_modulus(21.6e6, 0.2)
    textbook = 2.868266 * (mass**2 / (diameter / 2 * e_star**2 * VELOCITY)) ** 0.2
    t_c = an.hertz_contact_time(_paper_k_hertz(diameter), mass, VELOCITY)
    # the textbook constant is printed with 7 significant digits
    assert t_c == pytest.approx(textbook, rel=2e-7)


@pytest.mark.parametrize(("k_hertz", "mass", "velocity"), [(1.5e6, MASS, 2.0), (3e9, 1e-2, 0.3)])
def test_hertz_against_integration(k_hertz, mass, velocity):
    d_max = an.hertz_max_overlap(k_hertz, mass, velocity)
    t_c = an.hertz_contact_time(k_hertz, mass, velocity)
    t_num, e_num, d_num = _impact(
        lambda x, v: k_hertz * x**1.5, mass, velocity, "overlap", d_max, 3 * t_c
    )
    # rtol 1e-11 integration; 1e-9 leaves room for the x^1.5 kink at first touch
    assert t_c == pytest.approx(t_num, rel=1e-9)
    assert d_max == pytest.approx(d_num, rel=1e-9)
    assert e_num == pytest.approx(1.0, rel=1e-9)
    # F_max = kH d_max^1.5 at the numerically found largest overlap
    assert an.hertz_max_force(k_hertz, mass, velocity) == pytest.approx(
        k_hertz * d_num**1.5, rel=1e-9
    )


# --- linear spring-dashpot ------------------------------------------------------------------

ZETAS = [0.0, 0.05, 0.3, 0.6, 1 / math.sqrt(2), 0.8, 0.95, 1.0, 1.3, 4.0]


def _damping(zeta, stiffness=STIFFNESS, mass=MASS):
    return 2.0 * zeta * math.sqrt(stiffness * mass)


@pytest.mark.parametrize("convention", an.CONVENTIONS)
@pytest.mark.parametrize("zeta", ZETAS)
def test_linear_against_integration(zeta, convention):
    c = _damping(zeta)
    w0 = math.sqrt(STIFFNESS / MASS)
    t_num, e_num, _ = _impact(
        lambda x, v: STIFFNESS * x + c * v,
        MASS,
        VELOCITY,
        convention,
        VELOCITY / w0,
        30.0 / w0,  # past every finite contact here; x(30/w0) > 0 stays resolved for zeta >= 1
    )
    t_c = an.linear_contact_time(STIFFNESS, c, MASS, convention)
    e = an.linear_restitution(STIFFNESS, c, MASS, convention)
    # rtol 1e-11 integration over a few periods
    assert t_c == pytest.approx(t_num, rel=1e-9)
    assert e == pytest.approx(e_num, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("zeta", [0.1, 0.5, 1 / math.sqrt(2), 0.75, 0.9, 0.999])
def test_linear_force_convention_is_schwager_poeschel_for_every_underdamped_zeta(zeta):
    root = math.sqrt(1.0 - zeta**2)
    phi = math.atan2(2.0 * zeta * root, 1.0 - 2.0 * zeta**2)
    w0 = math.sqrt(STIFFNESS / MASS)
    c = _damping(zeta)
    # two closed forms of the same quantity: rounding only
    assert an.linear_contact_time(STIFFNESS, c, MASS, "force") == pytest.approx(
        (math.pi - phi) / (w0 * root), rel=1e-12
    )
    assert an.linear_restitution(STIFFNESS, c, MASS, "force") == pytest.approx(
        math.exp(-zeta * (math.pi - phi) / root), rel=1e-12
    )


@pytest.mark.parametrize("zeta", [1.001, 1.5, 10.0, 1e4])
def test_linear_force_convention_overdamped_from_the_roots(zeta):
    w0 = math.sqrt(STIFFNESS / MASS)
    l1, l2 = np.roots([1.0, 2.0 * zeta * w0, w0**2])[::-1]  # l1 > l2, both negative
    t_roots = math.log(l2**2 / l1**2) / (l1 - l2)
    e_roots = (l1 / l2) * math.exp(l1 * t_roots)
    c = _damping(zeta)
    # np.roots loses digits in the small root for large zeta (cancellation)
    assert an.linear_contact_time(STIFFNESS, c, MASS, "force") == pytest.approx(t_roots, rel=1e-7)
    assert an.linear_restitution(STIFFNESS, c, MASS, "force") == pytest.approx(e_roots, rel=1e-7)


@pytest.mark.parametrize("convention", an.CONVENTIONS)
def test_linear_undamped_limit(convention):
    w0 = math.sqrt(STIFFNESS / MASS)
    # zero damping: exact pi / w0 and e = 1 up to rounding
    assert an.linear_contact_time(STIFFNESS, 0.0, MASS, convention) == pytest.approx(
        math.pi / w0, rel=1e-15
    )
    assert an.linear_restitution(STIFFNESS, 0.0, MASS, convention) == 1.0
    # zeta = 1e-8: first-order corrections are ~1e-8
    c = _damping(1e-8)
    assert an.linear_contact_time(STIFFNESS, c, MASS, convention) == pytest.approx(
        math.pi / w0, rel=3e-8
    )
    assert an.linear_restitution(STIFFNESS, c, MASS, convention) == pytest.approx(1.0, abs=4e-8)


def test_linear_critical_damping():
    c = _damping(1.0)
    w0 = math.sqrt(STIFFNESS / MASS)
    # exact special values, rounding only
    assert an.linear_contact_time(STIFFNESS, c, MASS, "force") == pytest.approx(2.0 / w0, 1e-15)
    assert an.linear_restitution(STIFFNESS, c, MASS, "force") == pytest.approx(math.exp(-2), 1e-15)
    assert an.linear_contact_time(STIFFNESS, c, MASS, "overlap") == math.inf
    assert an.linear_restitution(STIFFNESS, c, MASS, "overlap") == 0.0


@pytest.mark.parametrize("zeta", [1 - 1e-9, 1 + 1e-9])
def test_linear_force_convention_is_continuous_at_critical_damping(zeta):
    c = _damping(zeta)
    w0 = math.sqrt(STIFFNESS / MASS)
    # both are smooth in zeta: a 1e-9 step moves them by ~1e-9
    assert an.linear_contact_time(STIFFNESS, c, MASS, "force") * w0 == pytest.approx(2.0, rel=1e-8)
    assert an.linear_restitution(STIFFNESS, c, MASS, "force") == pytest.approx(
        math.exp(-2.0), rel=1e-8
    )


def test_linear_force_restitution_tends_to_zero_like_inverse_four_zeta_squared():
    # the overdamped limit is e -> 0, not a positive floor; 1/(4 zeta^2) within 1e-3 at 1e4
    zeta = 1e4
    e = an.linear_restitution(STIFFNESS, _damping(zeta), MASS, "force")
    assert e * 4.0 * zeta**2 == pytest.approx(1.0, rel=1e-3)


zeta_values = st.floats(min_value=0.0, max_value=50.0)


@settings(max_examples=200, deadline=None)
@given(zeta=zeta_values)
def test_linear_restitution_bounds_and_convention_order(zeta):
    c = _damping(zeta)
    e_overlap = an.linear_restitution(STIFFNESS, c, MASS, "overlap")
    e_force = an.linear_restitution(STIFFNESS, c, MASS, "force")
    assert 0.0 <= e_overlap <= e_force <= 1.0
    t_overlap = an.linear_contact_time(STIFFNESS, c, MASS, "overlap")
    assert an.linear_contact_time(STIFFNESS, c, MASS, "force") <= t_overlap


@settings(max_examples=200, deadline=None)
@given(zeta=zeta_values, step=st.floats(min_value=1e-3, max_value=10.0))
def test_linear_restitution_falls_with_damping(zeta, step):
    for convention in an.CONVENTIONS:
        lower = an.linear_restitution(STIFFNESS, _damping(zeta), MASS, convention)
        higher = an.linear_restitution(STIFFNESS, _damping(zeta + step), MASS, convention)
        assert higher <= lower
        if lower > 0.0 and convention == "force":
            assert higher < lower


@settings(max_examples=200, deadline=None)
@given(e=st.floats(min_value=1e-12, max_value=1.0))
def test_linear_damping_from_restitution_round_trip(e):
    for convention in an.CONVENTIONS:
        c = an.linear_damping_from_restitution(STIFFNESS, e, MASS, convention)
        # required accuracy of the inversion
        assert an.linear_restitution(STIFFNESS, c, MASS, convention) == pytest.approx(e, abs=1e-10)


@pytest.mark.parametrize("e", [1e-300, 1e-30, 1e-3, 0.5, 1 - 1e-12])
def test_linear_damping_from_restitution_force_round_trip_relative(e):
    c = an.linear_damping_from_restitution(STIFFNESS, e, MASS, "force")
    # brentq stops at 4 eps relative in zeta; ln e carries it with a factor ~2
    assert an.linear_restitution(STIFFNESS, c, MASS, "force") == pytest.approx(e, rel=1e-12)


def test_linear_damping_from_restitution_force_needs_more_damping():
    c_overlap = an.linear_damping_from_restitution(STIFFNESS, 0.5, MASS, "overlap")
    c_force = an.linear_damping_from_restitution(STIFFNESS, 0.5, MASS, "force")
    assert c_force > c_overlap
    assert an.linear_damping_from_restitution(STIFFNESS, 1.0, MASS, "force") == 0.0


# --- Tsuji / EDEM damped Hertz --------------------------------------------------------------

# Realised restitution under the "force" convention (table in tsuji_restitution's Notes).
TSUJI_FORCE_TABLE = {0.3: 0.397140, 0.5: 0.550283, 0.7: 0.718201, 0.9: 0.902026}


def _tsuji_impact(k_hertz, eta, mass, velocity, convention):
    d_max = an.hertz_max_overlap(k_hertz, mass, velocity)
    t_c = an.hertz_contact_time(k_hertz, mass, velocity)
    _, e, _ = _impact(
        lambda x, v: k_hertz * x**1.5 + eta * x**0.25 * v,
        mass,
        velocity,
        convention,
        d_max,
        20 * t_c,
    )
    return e


@pytest.mark.parametrize("target", sorted(TSUJI_FORCE_TABLE))
def test_tsuji_realised_restitution(target):
    k_hertz = _paper_k_hertz(5e-3)
    eta = an.tsuji_damping_coefficient(k_hertz, MASS, target)
    alpha = an.tsuji_damping_factor(target)
    e_overlap = _tsuji_impact(k_hertz, eta, MASS, VELOCITY, "overlap")
    e_force = _tsuji_impact(k_hertz, eta, MASS, VELOCITY, "force")
    # rtol 1e-11 integration; the d^(1/4) kink at first touch costs a little more
    assert e_overlap == pytest.approx(target, rel=1e-8)
    assert e_force == pytest.approx(an.tsuji_restitution(alpha, "force"), rel=1e-8)
    # the docstring table is rounded to 6 digits
    assert e_force == pytest.approx(TSUJI_FORCE_TABLE[target], abs=5e-7)
    assert an.tsuji_restitution(alpha, "overlap") == pytest.approx(target, rel=1e-13)


@pytest.mark.parametrize("target", [0.2, 0.6, 0.95])
def test_tsuji_force_mapping_realises_its_target(target):
    k_hertz = _paper_k_hertz(5e-3)
    eta = an.tsuji_damping_coefficient(k_hertz, MASS, target, convention="force")
    # integration tolerance as above
    assert _tsuji_impact(k_hertz, eta, MASS, VELOCITY, "force") == pytest.approx(target, rel=1e-8)


@pytest.mark.parametrize(
    ("alpha", "convention"), [(0.6, "overlap"), (0.6, "force"), (3.0, "force"), (12.0, "force")]
)
@pytest.mark.parametrize(
    ("k_hertz", "mass", "velocity"),
    [(1.5e6, MASS, 2.0), (1.5e6, MASS, 0.05), (1.5e6, 1e-3, 2.0), (4e10, 0.2, 7.0)],
)
def test_tsuji_restitution_depends_on_alpha_only(alpha, convention, k_hertz, mass, velocity):
    eta = alpha * math.sqrt(mass * k_hertz)
    e = _tsuji_impact(k_hertz, eta, mass, velocity, convention)
    # integration tolerance as above
    assert e == pytest.approx(an.tsuji_restitution(alpha, convention), rel=1e-8)


def test_tsuji_overdamped_overlap_never_separates():
    assert an.tsuji_restitution(math.sqrt(5.0), "overlap") == 0.0
    assert an.tsuji_restitution(0.0, "force") == 1.0


# --- Kuwabara-Kono --------------------------------------------------------------------------


def _kuwabara_kono_impact(x, convention):
    k_hertz, mass, velocity = 1.5e6, MASS, 2.0
    dissipation = x / (1.5 * (k_hertz / mass) ** 0.4 * velocity**0.2)
    assert an.kuwabara_kono_parameter(k_hertz, dissipation, mass, velocity) == pytest.approx(x)
    d_max = an.hertz_max_overlap(k_hertz, mass, velocity)
    t_c = an.hertz_contact_time(k_hertz, mass, velocity)
    _, e, _ = _impact(
        lambda d, v: k_hertz * (d**1.5 + 1.5 * dissipation * d**0.5 * v),
        mass,
        velocity,
        convention,
        d_max,
        20 * t_c,
    )
    series = an.kuwabara_kono_restitution(k_hertz, dissipation, mass, velocity)
    return series, e


def test_kuwabara_kono_constants():
    value, _ = quad(lambda u: 2.0 * math.sqrt(u) * math.sqrt(1.0 - 0.8 * u**2.5), 0.0, 1.25**0.4)
    # C1 is the first-order dissipation integral; quad is good to ~1e-12 here
    assert an.KUWABARA_KONO_C1 == pytest.approx(value, rel=1e-10)
    # the published values (Ramirez et al. 1999) carry 5 decimals
    assert an.KUWABARA_KONO_C1 == pytest.approx(1.15344, abs=1e-5)
    assert an.KUWABARA_KONO_C2 == pytest.approx(0.79826, abs=1e-5)


@pytest.mark.parametrize("x", [0.01, 0.05, 0.1])
def test_kuwabara_kono_series_error_is_third_order_in_overlap_convention(x):
    series, e_overlap = _kuwabara_kono_impact(x, "overlap")
    # measured: error = C3 x^3 with C3 = 0.49-0.52 for x <= 0.1 (integration error ~1e-10)
    assert 0.45 * x**3 < series - e_overlap < 0.55 * x**3


@pytest.mark.parametrize("x", [0.002, 0.005, 0.01])
def test_kuwabara_kono_series_is_the_overlap_convention_expansion(x):
    series, e_overlap = _kuwabara_kono_impact(x, "overlap")
    _, e_force = _kuwabara_kono_impact(x, "force")
    assert abs(series - e_force) > 3.0 * abs(series - e_overlap)
    # measured gap 0.26 x^2.5 at small x; 10 % covers its slow drift with x
    assert e_force - e_overlap == pytest.approx(0.26 * x**2.5, rel=0.1)


def test_kuwabara_kono_rejects_the_series_beyond_its_turning_point():
    k_hertz, mass, velocity = 1.5e6, MASS, 2.0
    dissipation = 0.8 / (1.5 * (k_hertz / mass) ** 0.4 * velocity**0.2)
    with pytest.raises(ParameterError, match="dissipation"):
        an.kuwabara_kono_restitution(k_hertz, dissipation, mass, velocity)


# --- Hunt-Crossley --------------------------------------------------------------------------


@pytest.mark.parametrize("convention", an.CONVENTIONS)
@pytest.mark.parametrize("exponent", [1.0, 1.5])
@pytest.mark.parametrize("chi_v", [0.01, 0.3, 1.0, 5.0])
def test_hunt_crossley_against_integration(chi_v, exponent, convention):
    k, mass, velocity = 1e6, MASS, 2.0
    chi = chi_v / velocity
    length = (mass * velocity**2 / k) ** (1.0 / (exponent + 1.0))
    _, e_num, _ = _impact(
        lambda x, v: k * x**exponent * (1.0 + 1.5 * chi * v),
        mass,
        velocity,
        convention,
        length,
        200 * length / velocity,
    )
    # rtol 1e-11 integration
    assert an.hunt_crossley_restitution(chi, velocity) == pytest.approx(e_num, rel=1e-8)


@pytest.mark.parametrize("chi_v", [1e-2, 1e-3, 1e-4, 1e-6])
def test_hunt_crossley_linearised_is_the_first_order_term(chi_v):
    e = an.hunt_crossley_restitution(chi_v, 1.0)
    linear = an.hunt_crossley_restitution_linearised(chi_v, 1.0)
    assert linear == 1.0 - chi_v
    # next term is +(chi v)^2 (measured); at 1e-6 e itself is known to ~1e-16 = 1e-4 (chi v)^2
    assert (e - linear) / chi_v**2 == pytest.approx(1.0, abs=max(1.1 * chi_v, 1e-3))


def test_hunt_crossley_series_meets_brent_at_its_threshold():
    from contactlab.analytic.hertz import HUNT_CROSSLEY_SERIES

    above = an.hunt_crossley_restitution(HUNT_CROSSLEY_SERIES / 1.5, 1.0)  # Brent
    below = an.hunt_crossley_restitution(
        math.nextafter(HUNT_CROSSLEY_SERIES, 0.0) / 1.5, 1.0
    )  # the series, one float of y lower (moves e by 1e-22)
    # both to rounding: a few eps of e = 1
    assert below == pytest.approx(above, abs=4 * np.finfo(float).eps)


@pytest.mark.parametrize("chi_v", [3.384e-152, 1e-75, 1e-300])
def test_hunt_crossley_vanishing_damping(chi_v):
    """Regression: chi v = 3.4e-152, drawn by the audit sweep, did not converge in Brent's
    100 iterations on [0, 1] (the root s ~ chi v); it is e = 1 - chi v to rounding."""
    assert an.hunt_crossley_restitution(chi_v, 1.0) == 1.0 - chi_v


@pytest.mark.parametrize("y", [20.0, 40.0, 1e6])
def test_hunt_crossley_high_damping_limit(y):
    # rebound speed -> 1/lam with 1 - z = exp(-(y - ln(1 + y) + 1)) (to first order)
    expected = 1.0 - math.exp(-(y - math.log1p(y) + 1.0))
    # relative rounding of z near 1
    assert an.hunt_crossley_restitution(y / 1.5, 1.0) * y == pytest.approx(expected, rel=1e-14)


def test_hunt_crossley_linearised_rejects_large_damping():
    with pytest.raises(ParameterError, match="damping"):
        an.hunt_crossley_restitution_linearised(2.0, 1.0)


# --- Walton-Braun and linear with a force cap -----------------------------------------------


@pytest.mark.parametrize("ratio", [1.0, 1.5, 10.0])
def test_walton_braun_against_integration(ratio):
    k1, k2 = STIFFNESS, STIFFNESS * ratio
    w1 = math.sqrt(k1 / MASS)
    loading = _integrate(
        lambda x, v: -k1 * x / MASS, [0.0, VELOCITY], lambda x, v: v, 1e-4, 10 / w1
    )
    d_max = loading.y_events[0][0][0]
    d0 = d_max * (1.0 - k1 / k2)
    unloading = _integrate(
        lambda x, v: -k2 * (x - d0) / MASS, [d_max, 0.0], lambda x, v: x - d0, d_max, 10 / w1
    )
    t_num = loading.t_events[0][0] + unloading.t_events[0][0]
    e_num = -unloading.y_events[0][0][1] / VELOCITY
    # rtol 1e-11 integration
    assert an.walton_braun_contact_time(k1, k2, MASS) == pytest.approx(t_num, rel=1e-9)
    assert an.walton_braun_restitution(k1, k2) == pytest.approx(e_num, rel=1e-9)


@pytest.mark.parametrize("speed_ratio", [1.001, 2.0, 10.0])
def test_linear_plastic_against_integration(speed_ratio):
    k, yield_force = STIFFNESS, 0.5
    v_y = an.linear_plastic_yield_velocity(k, yield_force, MASS)
    v = speed_ratio * v_y
    w0 = math.sqrt(k / MASS)
    length = v / w0
    elastic = _integrate(
        lambda x, u: -k * x / MASS, [0.0, v], lambda x, u: yield_force - k * x, length, 10 / w0
    )
    plastic = _integrate(
        lambda x, u: -yield_force / MASS, elastic.y_events[0][0], lambda x, u: u, length, 1e3 / w0
    )
    d_max = plastic.y_events[0][0][0]
    unloading = _integrate(
        lambda x, u: -(yield_force - k * (d_max - x)) / MASS,
        plastic.y_events[0][0],
        lambda x, u: yield_force - k * (d_max - x),
        length,
        10 / w0,
    )
    t_num = sum(phase.t_events[0][0] for phase in (elastic, plastic, unloading))
    e_num = -unloading.y_events[0][0][1] / v
    # rtol 1e-11 integration in three phases
    assert an.linear_plastic_contact_time(k, yield_force, MASS, v) == pytest.approx(t_num, rel=1e-9)
    assert an.linear_plastic_restitution(k, yield_force, MASS, v) == pytest.approx(e_num, rel=1e-9)


def test_linear_plastic_below_yield_is_elastic():
    v_y = an.linear_plastic_yield_velocity(STIFFNESS, 0.5, MASS)
    w0 = math.sqrt(STIFFNESS / MASS)
    assert an.linear_plastic_restitution(STIFFNESS, 0.5, MASS, 0.5 * v_y) == 1.0
    # closed form reduces to pi / w0: rounding only
    t_c = an.linear_plastic_contact_time(STIFFNESS, 0.5, MASS, v_y)
    assert t_c == pytest.approx(math.pi / w0, rel=1e-15)


# --- Thornton -------------------------------------------------------------------------------

E_STAR, RADIUS, YIELD_PRESSURE = 70e9, 2.5e-3, 1e9


def test_thornton_yield_force_is_hertz_at_yield_overlap():
    d_y = an.thornton_yield_overlap(E_STAR, RADIUS, YIELD_PRESSURE)
    k_hertz = an.hertz_stiffness(E_STAR, RADIUS)
    # two routes to the same number: rounding only
    f_y = an.thornton_yield_force(E_STAR, RADIUS, YIELD_PRESSURE)
    assert f_y == pytest.approx(k_hertz * d_y**1.5, rel=1e-13)
    # v_y is the speed whose elastic Hertz impact just reaches d_y
    v_y = an.thornton_yield_velocity(E_STAR, RADIUS, YIELD_PRESSURE, MASS)
    assert an.hertz_max_overlap(k_hertz, MASS, v_y) == pytest.approx(d_y, rel=1e-13)


def _thornton_energy_restitution(velocity):
    """e from the model's definition: Hertz to d_y, linear plastic, Hertz unloading."""
    d_y = an.thornton_yield_overlap(E_STAR, RADIUS, YIELD_PRESSURE)
    f_y = an.hertz_stiffness(E_STAR, RADIUS) * d_y**1.5
    slope = math.pi * YIELD_PRESSURE * RADIUS
    kinetic = 0.5 * MASS * velocity**2
    plastic_work = kinetic - 0.4 * f_y * d_y
    excess = (-f_y + math.sqrt(f_y**2 + 2.0 * slope * plastic_work)) / slope
    f_max = f_y + slope * excess
    contact_radius = math.sqrt(RADIUS * (d_y + excess))
    released = 0.3 * f_max**2 / (E_STAR * contact_radius)
    return math.sqrt(released / kinetic)


@pytest.mark.parametrize("speed_ratio", [1.0, 1.01, 2.0, 5.0, 20.0, 100.0])
def test_thornton_restitution_against_energy_balance(speed_ratio):
    v = speed_ratio * an.thornton_yield_velocity(E_STAR, RADIUS, YIELD_PRESSURE, MASS)
    e = an.thornton_restitution(E_STAR, RADIUS, YIELD_PRESSURE, MASS, v)
    # closed algebra on both sides; the quadratic root loses a few digits near yield
    assert e == pytest.approx(_thornton_energy_restitution(v), rel=1e-10)


def test_thornton_restitution_below_yield_is_one():
    v_y = an.thornton_yield_velocity(E_STAR, RADIUS, YIELD_PRESSURE, MASS)
    assert an.thornton_restitution(E_STAR, RADIUS, YIELD_PRESSURE, MASS, 0.5 * v_y) == 1.0


# --- Rayleigh time, trapezoid pulse, half-sine residual -------------------------------------


def _rayleigh_speed_ratio(nu):
    """Rayleigh-wave / shear-wave speed from the exact Rayleigh equation."""
    k2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
    return brentq(lambda s: s**6 - 8 * s**4 + (24 - 16 * k2) * s**2 + 16 * (k2 - 1), 0.5, 0.9999)


@pytest.mark.parametrize("nu", np.linspace(0.0, 0.5, 11).tolist())
def test_rayleigh_time_against_the_rayleigh_wave_speed(nu):
    radius, density, shear = 2.5e-3, 765.0, 9e6
    exact = math.pi * radius * math.sqrt(density / shear) / _rayleigh_speed_ratio(nu)
    # the linear fit 0.1631 nu + 0.8766 is off by at most 0.30 % (at nu = 0 and 0.5)
    assert an.rayleigh_time(radius, density, shear, nu) == pytest.approx(exact, rel=3.1e-3)


@pytest.mark.parametrize("ramp_fraction", [0.0, 0.1, 0.5])
def test_plastic_trapezoid_impulse_is_the_momentum(ramp_fraction):
    t_k = 30e-6
    t_r = ramp_fraction * t_k
    amplitude = an.plastic_trapezoid_amplitude(MASS, VELOCITY, t_k, t_r)
    impulse = np.trapezoid([0.0, amplitude, amplitude, 0.0], [0.0, t_r, t_k - t_r, t_k])
    # the trapezoid rule is exact for the piecewise-linear pulse
    assert impulse == pytest.approx(MASS * VELOCITY, rel=1e-14)


def _half_sine_residual(ratio):
    period = 1.0
    omega = 2.0 * math.pi / period
    tau = ratio * period
    sol = solve_ivp(
        lambda t, y: [y[1], omega**2 * (math.sin(math.pi * t / tau) - y[0])],
        (0.0, tau),
        [0.0, 0.0],
        method="DOP853",
        rtol=RTOL,
        atol=1e-14,
    )
    x, v = sol.y[:, -1]
    return math.hypot(x, v / omega)


@pytest.mark.parametrize("ratio", [0.01, 0.2, 0.5, 0.8, 1.0, 1.5, 2.2, 2.5, 3.7])
def test_half_sine_residual_against_integration(ratio):
    closed = an.half_sine_residual_amplitude(ratio, 1.0)
    # rtol 1e-11 integration; abs 1e-9 for the zeros at ratio 1.5, 2.5
    assert closed == pytest.approx(_half_sine_residual(ratio), rel=1e-8, abs=1e-9)


def test_half_sine_residual_limits():
    # value pi/2 at tau = T/2 (removable 0/0), impulsive limit 4 tau/T: rounding only
    assert an.half_sine_residual_amplitude(0.5, 1.0) == pytest.approx(math.pi / 2, rel=1e-15)
    assert an.half_sine_residual_amplitude(1e-9, 1.0) == pytest.approx(4e-9, rel=1e-8)
    assert an.half_sine_residual_amplitude(1.5, 1.0) < 1e-15


# --- bad input ------------------------------------------------------------------------------

VALID = {
    an.effective_mass: {"mass": 1e-3, "other_mass": 2e-3},
    an.effective_radius: {"radius": 1e-3, "other_radius": 2e-3},
    an.effective_modulus: {
        "youngs_modulus": 1e9,
        "poisson_ratio": 0.3,
        "other_youngs_modulus": 2e11,
        "other_poisson_ratio": 0.3,
    },
    an.hertz_stiffness: {"effective_modulus": 1e9, "effective_radius": 1e-3},
    an.youngs_from_shear: {"shear_modulus": 9e6, "poisson_ratio": 0.2},
    an.hertz_max_overlap: {"k_hertz": 1e6, "mass": 1e-4, "velocity": 2.0},
    an.hertz_max_force: {"k_hertz": 1e6, "mass": 1e-4, "velocity": 2.0},
    an.hertz_contact_time: {"k_hertz": 1e6, "mass": 1e-4, "velocity": 2.0},
    an.damping_ratio: {"stiffness": 1e5, "damping": 0.1, "mass": 1e-4},
    an.linear_contact_time: {"stiffness": 1e5, "damping": 0.1, "mass": 1e-4},
    an.linear_restitution: {"stiffness": 1e5, "damping": 0.1, "mass": 1e-4},
    an.linear_damping_from_restitution: {"stiffness": 1e5, "restitution": 0.5, "mass": 1e-4},
    an.tsuji_damping_factor: {"restitution": 0.5},
    an.tsuji_damping_coefficient: {"k_hertz": 1e6, "mass": 1e-4, "restitution": 0.5},
    an.tsuji_restitution: {"alpha": 0.5},
    an.kuwabara_kono_parameter: {"k_hertz": 1e6, "dissipation": 1e-6, "mass": 1e-4, "velocity": 2},
    an.kuwabara_kono_restitution: {
        "k_hertz": 1e6,
        "dissipation": 1e-6,
        "mass": 1e-4,
        "velocity": 2.0,
    },
    an.hunt_crossley_restitution: {"damping": 0.1, "velocity": 2.0},
    an.hunt_crossley_restitution_linearised: {"damping": 0.1, "velocity": 2.0},
    an.walton_braun_restitution: {"loading_stiffness": 1e5, "unloading_stiffness": 2e5},
    an.walton_braun_contact_time: {
        "loading_stiffness": 1e5,
        "unloading_stiffness": 2e5,
        "mass": 1e-4,
    },
    an.linear_plastic_yield_velocity: {"stiffness": 1e5, "yield_force": 1.0, "mass": 1e-4},
    an.linear_plastic_restitution: {
        "stiffness": 1e5,
        "yield_force": 1.0,
        "mass": 1e-4,
        "velocity": 2.0,
    },
    an.linear_plastic_contact_time: {
        "stiffness": 1e5,
        "yield_force": 1.0,
        "mass": 1e-4,
        "velocity": 2.0,
    },
    an.thornton_yield_overlap: {
        "effective_modulus": 1e9,
        "effective_radius": 1e-3,
        "yield_pressure": 1e8,
    },
    an.thornton_yield_force: {
        "effective_modulus": 1e9,
        "effective_radius": 1e-3,
        "yield_pressure": 1e8,
    },
    an.thornton_yield_velocity: {
        "effective_modulus": 1e9,
        "effective_radius": 1e-3,
        "yield_pressure": 1e8,
        "mass": 1e-4,
    },
    an.thornton_restitution: {
        "effective_modulus": 1e9,
        "effective_radius": 1e-3,
        "yield_pressure": 1e8,
        "mass": 1e-4,
        "velocity": 2.0,
    },
    an.rayleigh_time: {
        "radius": 1e-3,
        "density": 765.0,
        "shear_modulus": 9e6,
        "poisson_ratio": 0.2,
    },
    an.plastic_trapezoid_amplitude: {
        "mass": 1e-4,
        "velocity": 2.0,
        "contact_time": 3e-5,
        "ramp_time": 1e-6,
    },
    an.half_sine_residual_amplitude: {"pulse_duration": 3e-5, "period": 2.5e-5},
}
ZERO_ALLOWED = {"damping", "alpha", "dissipation", "ramp_time", "poisson_ratio"}
ZERO_ALLOWED |= {"other_poisson_ratio"}
INF_ALLOWED = {"other_mass", "other_radius", "other_youngs_modulus"}
WRONG = [-1.0, math.nan, "1.0", None, True, [1.0]]


def _bad_cases():
    for func, kwargs in VALID.items():
        for name in kwargs:
            bad = list(WRONG)
            if name not in ZERO_ALLOWED:
                bad.append(0.0)
            if name not in INF_ALLOWED:
                bad.append(math.inf)
            for value in bad:
                yield pytest.param(func, name, value, id=f"{func.__name__}-{name}-{value!r}")


@pytest.mark.parametrize(("func", "name", "value"), list(_bad_cases()))
def test_bad_input_names_the_parameter(func, name, value):
    kwargs = dict(VALID[func], **{name: value})
    with pytest.raises(ParameterError, match=name):
        func(**kwargs)


@pytest.mark.parametrize("func", list(VALID))
def test_valid_input_gives_a_finite_value(func):
    # guards the table above: each bad case differs from a working call in one argument
    assert math.isfinite(func(**VALID[func]))


@pytest.mark.parametrize(
    ("func", "name", "value"),
    [
        (an.linear_damping_from_restitution, "restitution", 1.5),
        (an.tsuji_damping_factor, "restitution", 0.0),
        (an.effective_modulus, "poisson_ratio", 0.6),
        (an.effective_modulus, "poisson_ratio", -1.0),
        (an.rayleigh_time, "poisson_ratio", 0.51),
        (an.walton_braun_restitution, "unloading_stiffness", 0.5e5),
        (an.walton_braun_contact_time, "unloading_stiffness", 0.5e5),
        (an.plastic_trapezoid_amplitude, "ramp_time", 1.6e-5),
    ],
)
def test_out_of_range_input_names_the_parameter(func, name, value):
    kwargs = dict(VALID[func], **{name: value})
    with pytest.raises(ParameterError, match=name):
        func(**kwargs)


CONVENTION_FUNCTIONS = [
    (an.linear_contact_time, VALID[an.linear_contact_time]),
    (an.linear_restitution, VALID[an.linear_restitution]),
    (an.linear_damping_from_restitution, VALID[an.linear_damping_from_restitution]),
    (an.tsuji_damping_factor, VALID[an.tsuji_damping_factor]),
    (an.tsuji_damping_coefficient, VALID[an.tsuji_damping_coefficient]),
    (an.tsuji_restitution, VALID[an.tsuji_restitution]),
]


@pytest.mark.parametrize(("func", "kwargs"), CONVENTION_FUNCTIONS)
@pytest.mark.parametrize("convention", ["Overlap", "forces", "", None, 1])
def test_unknown_convention_is_rejected(func, kwargs, convention):
    with pytest.raises(ParameterError, match="convention"):
        func(**kwargs, convention=convention)


@pytest.mark.parametrize(("func", "kwargs"), CONVENTION_FUNCTIONS)
def test_unknown_keyword_is_a_type_error(func, kwargs):
    with pytest.raises(TypeError):
        func(**kwargs, conventions="force")
