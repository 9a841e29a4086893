"""The pair reduction against a direct two-body integration, and the impulse bookkeeping."""

import math

import pytest

from contactlab import analytic
from contactlab.benchmarks.chung_ooi.cases import AL_ALLOY, COPPER, NYLON
from contactlab.benchmarks.chung_ooi.grading import grain
from contactlab.benchmarks.chung_ooi.pairs import pair_impact
from contactlab.errors import ParameterError


def _two_bodies(spheres, before, friction, steps):
    """Both spheres after the impact, by velocity Verlet on the two bodies themselves.

    Fixed normal along x (sphere 1 to 2), tangential y, spins about z; Hertz normal force
    with the pair's E* and R*, Mindlin total form with LAMMPS' rules (history += slip dt,
    trial -kt h, Coulomb rescaling). Shares no code with the reduction.
    """
    (mat1, r1), (mat2, r2) = spheres
    m1, m2 = grain(mat1, r1).mass, grain(mat2, r2).mass
    i1, i2 = 0.4 * m1 * r1**2, 0.4 * m2 * r2**2
    r_eff = r1 * r2 / (r1 + r2)
    e_eff = 1 / (
        (1 - mat1.poisson_ratio**2) / mat1.youngs_modulus
        + (1 - mat2.poisson_ratio**2) / mat2.youngs_modulus
    )
    g1 = mat1.youngs_modulus / (2 * (1 + mat1.poisson_ratio))
    g2 = mat2.youngs_modulus / (2 * (1 + mat2.poisson_ratio))
    g_eff = 1 / ((2 - mat1.poisson_ratio) / g1 + (2 - mat2.poisson_ratio) / g2)
    k_hertz = 4 / 3 * e_eff * math.sqrt(r_eff)
    m_eff = m1 * m2 / (m1 + m2)
    vn = before.normal1 - before.normal2
    t_c = analytic.hertz_contact_time(k_hertz, m_eff, vn)
    dt = t_c / steps
    u1, u2 = before.normal1, before.normal2
    t1, t2, w1, w2 = before.tangential1, before.tangential2, before.spin1, before.spin2
    d, h, fn, ft, touched = 0.0, 0.0, 0.0, 0.0, False

    def kick(fn, ft):
        nonlocal u1, u2, t1, t2, w1, w2
        u1 -= 0.5 * dt * fn / m1
        u2 += 0.5 * dt * fn / m2
        t1 += 0.5 * dt * ft / m1
        t2 -= 0.5 * dt * ft / m2
        w1 += 0.5 * dt * r1 * ft / i1
        w2 += 0.5 * dt * r2 * ft / i2

    while True:
        kick(fn, ft)
        d += dt * (u1 - u2)
        if d <= 0.0:
            if touched:
                return analytic.PairRebound(u1, u2, t1, t2, w1, w2)
            fn = ft = 0.0
            continue
        touched = True
        fn = k_hertz * d**1.5
        slip = t1 - t2 + r1 * w1 + r2 * w2
        kt = 8 * g_eff * math.sqrt(r_eff * d)
        h += slip * dt
        ft = -kt * h
        if abs(ft) > friction * fn:
            ft = math.copysign(friction * fn, ft)
            h = -ft / kt
        kick(fn, ft)


SPHERES = ((AL_ALLOY, 0.1), (COPPER, 0.25))


@pytest.mark.parametrize("spin1", [0.0, 3.0, -8.0])
def test_reduction_matches_two_body_integration(spin1):
    before = analytic.PairRebound(0.3, -0.1, 0.05, -0.02, spin1, 1.5)
    after, _ = pair_impact(SPHERES, before, 1.0, 0.3)
    direct = _two_bodies(SPHERES, before, 0.3, 4000)
    for field in ("normal1", "normal2", "tangential1", "tangential2"):
        # velocity Verlet at t_c/4000: second order, ~1e-6 of the speeds
        assert getattr(after, field) == pytest.approx(getattr(direct, field), abs=2e-6)
    for field, radius in (("spin1", 0.1), ("spin2", 0.25)):
        # spins compared as R w, on the same velocity scale
        got, want = getattr(after, field) * radius, getattr(direct, field) * radius
        assert got == pytest.approx(want, abs=2e-6)


def test_momenta_are_conserved():
    before = analytic.PairRebound(0.3, -0.1, 0.05, -0.02, 3.0, 1.5)
    after, _ = pair_impact(SPHERES, before, 0.6, 0.3, "incremental")
    (mat1, r1), (mat2, r2) = SPHERES
    m1, m2 = grain(mat1, r1).mass, grain(mat2, r2).mass

    def momenta(s):
        # linear momenta, and angular momentum of each sphere about the contact point
        # (the contact force has no moment there): I w - R m vt for sphere 1 ...
        return (
            m1 * s.normal1 + m2 * s.normal2,
            m1 * s.tangential1 + m2 * s.tangential2,
            0.4 * m1 * r1**2 * s.spin1 - r1 * m1 * s.tangential1,
            0.4 * m2 * r2**2 * s.spin2 + r2 * m2 * s.tangential2,
        )

    for a, b in zip(momenta(before), momenta(after), strict=True):
        assert a == pytest.approx(b, rel=1e-12, abs=1e-12)  # exact bookkeeping, rounding


def test_identical_spheres_are_one_sphere_on_a_plane():
    """A sphere against its mirror image: mass m on a rigid plane of twice the pair's E*.

    Mirror symmetry (equal tangential velocities, spins +w and -w) leaves no slip, so no
    tangential force: the spins and tangential velocities come out unchanged.
    """
    import contactlab as cl

    radius, spin = 0.1, 6.0
    before = analytic.PairRebound(0.2, -0.2, 0.1, 0.1, spin, -spin)
    after, pair = pair_impact(((NYLON, radius), (NYLON, radius)), before, 0.5, 0.4)
    body = grain(NYLON, radius)
    k_hertz = cl.laws.Hertz.from_material(body.material()).k_hertz  # rigid flat: E/(1-nu^2)
    normal = cl.laws.HertzDamped(
        k_hertz, analytic.tsuji_damping_coefficient(k_hertz, body.mass, 0.5, "force")
    )
    plane = cl.simulate_impact(body, cl.Sensor.rigid(), normal, 0.2)
    assert pair.contact_time == pytest.approx(plane.contact_time, rel=1e-7)  # rtol 1e-9 runs
    assert -after.normal1 == pytest.approx(plane.rebound_velocity, rel=1e-7)
    assert (after.tangential1, after.tangential2) == (0.1, 0.1)  # no force: exactly unchanged
    assert (after.spin1, after.spin2) == (spin, -spin)


def test_bad_input_names_the_parameter():
    before = analytic.PairRebound(0.3, -0.1, 0.0, 0.0, 0.0, 0.0)
    with pytest.raises(ParameterError, match="masses"):
        analytic.pair_rebound((-1.0, 1.0), (0.1, 0.1), before, 0.1, 0.0)
    with pytest.raises(ParameterError, match="tangential_impulse"):
        analytic.pair_rebound((1.0, 1.0), (0.1, 0.1), before, 0.1, math.nan)


def test_a_wall_partner_changes_nothing_on_its_side():
    before = analytic.PairRebound(0.3, 0.0, 0.0, 0.0, 2.0, 0.0)
    after = analytic.pair_rebound((1.0, math.inf), (0.1, math.inf), before, 0.4, -0.05)
    assert (after.normal2, after.tangential2, after.spin2) == (0.0, 0.0, 0.0)
    assert after.normal1 == pytest.approx(0.3 - 0.4)
