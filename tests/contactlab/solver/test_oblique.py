"""Oblique impacts: closed forms, invariants, the normal impact alone, LAMMPS' rules."""

import math

import numpy as np
import pytest

import contactlab as cl
from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.laws import Hertz, HertzDamped, Mindlin, TangentialSpring

SPEED = 3.9
"""Impact speed of Chung & Ooi's test 4 [m/s]."""

GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
"""Chung & Ooi's aluminium oxide sphere (test 4)."""

HERTZ = Hertz.from_material(GRAIN.material())
DAMPED = HertzDamped.from_material(GRAIN.material(), restitution=0.8, mass=GRAIN.mass)
SENSOR = cl.Sensor.from_resonance(200e3, mass=20e-3, damping_ratio=0.02)


def mindlin(history, friction=0.092):
    return Mindlin.from_material(
        cl.analytic.Material(3.8e11, 0.23, GRAIN.radius), friction, history=history
    )


TANGENTIAL = {
    "total": mindlin("total"),
    "incremental": mindlin("incremental"),
    "spring": TangentialSpring(stiffness=2e7, friction=0.092, damping=0.05),
}


SLIDING = {
    "hertz-total": (HERTZ, "total"),
    "hertz-incremental": (HERTZ, "incremental"),
    "hertz-spring": (HERTZ, "spring"),
}


@pytest.mark.parametrize(("normal", "tangential"), SLIDING.values(), ids=SLIDING.keys())
@pytest.mark.parametrize("sensor", [cl.Sensor.rigid(), SENSOR], ids=["rigid", "sensor"])
def test_gross_sliding_impulse(normal, tangential, sensor):
    """In gross sliding the tangential impulse is mu times the normal impulse."""
    angle = math.radians(60.0)
    res = cl.simulate_oblique(GRAIN, sensor, normal, TANGENTIAL[tangential], SPEED, angle)
    assert [p[2] for p in res.phases] == ["slide-"]
    # elastic Hertz realises e = 1 to ~4e-9 (rtol 1e-9); the closed form takes e <= 1
    e = min(res.restitution, 1.0)
    vt, spin = analytic.gross_sliding_rebound(
        analytic.ObliqueImpact(
            res.normal_velocity, res.incident_tangential_velocity, 0.0, GRAIN.radius, e, 0.092
        )
    )
    # issue's bar 1e-3; the impulse closed form is exact, the solver runs at rtol 1e-9
    assert res.tangential_velocity == pytest.approx(vt, rel=1e-6)
    assert res.angular_velocity == pytest.approx(spin, rel=1e-6)
    assert res.tangential_impulse == pytest.approx(-0.092 * res.normal_impulse, rel=1e-6)


STICKING_FIRST = {
    "total": TANGENTIAL["total"],
    "incremental": TANGENTIAL["incremental"],
    "spring": TangentialSpring(stiffness=2e7, friction=0.092),
}


@pytest.mark.parametrize("tangential", STICKING_FIRST.values(), ids=STICKING_FIRST.keys())
def test_damped_normal_force_sticks_first(tangential):
    """A damped normal force jumps at the touch (~t**0.25) while the elastic tangential
    force grows from zero, so every form sticks briefly first (LAMMPS' rule: the history
    starts at zero): the impulse ratio falls short of mu by the stick's share."""
    res = cl.simulate_oblique(
        GRAIN, cl.Sensor.rigid(), DAMPED, tangential, SPEED, math.radians(60.0)
    )
    (_start, end, first), *rest = res.phases
    assert first == "stick" and [p[2] for p in rest] == ["slide-"]
    assert end < 0.01 * res.contact_time  # measured 0.22 %, 0.60 %, 0.84 % of the contact
    ratio = -res.tangential_impulse / res.normal_impulse
    assert 0.092 * (1 - 1e-3) < ratio < 0.092  # issue's 1e-3 bar; measured 5e-5 to 3.6e-4


def _discrete_stick_end(normal, spring, angle, dt, horizon=2e-8):
    """End [s] of the first stick of LAMMPS' rules at step ``dt`` (velocity Verlet, history
    increment, then Coulomb rescaling), written out here, sharing no code with the solver."""
    m, radius = GRAIN.mass, GRAIN.radius
    inertia = 0.4 * m * radius**2
    d, v, u, w, h, t = 0.0, SPEED * math.cos(angle), SPEED * math.sin(angle), 0.0, 0.0, 0.0
    n_force = t_force = 0.0
    stuck = False
    while t < horizon:
        v -= 0.5 * dt * n_force / m
        u += 0.5 * dt * t_force / m
        w -= 0.5 * dt * radius * t_force / inertia
        d, t = d + dt * v, t + dt
        n_force = float(normal.force(d, v))
        slip = u - radius * w
        h += slip * dt
        t_force = -spring.k * h - spring.damping * slip
        cap = spring.friction * n_force
        if abs(t_force) > cap:
            if stuck:
                return t
            t_force = math.copysign(cap, t_force)
            h = -(t_force + spring.damping * slip) / spring.k
        else:
            stuck = True
        v -= 0.5 * dt * n_force / m
        u += 0.5 * dt * t_force / m
        w -= 0.5 * dt * radius * t_force / inertia
    raise AssertionError("no stick ended within the horizon")


def test_a_damped_spring_slides_an_instant_then_sticks():
    """With a constant tangential damping the trial force ``-eta s`` is finite at the touch
    while the cap ``mu N`` starts at zero: the contact slides, but only for an instant.
    The damped Hertz cap grows like ``t**0.25``, faster than any trial force, so sliding
    ends at once with ``eta s`` absorbed into the rescaled history, and the contact sticks
    until the spring's force ``k s t`` catches up with the cap (14.6 ns here, 0.22 % of
    the contact), then slides. LAMMPS' rules at a fixed step reach this limit only like
    ``dt**0.25`` (the cap at the first step is ``~ dt**0.25``); their stick end converges
    to the solver's (an earlier version of this test claimed sliding throughout)."""
    spring = TangentialSpring(stiffness=2e7, friction=0.092, damping=0.05)
    angle = math.radians(60.0)
    res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), DAMPED, spring, SPEED, angle)
    (_, slide_end, first), (_, stick_end, second), (_, _, third) = res.phases
    assert (first, second, third) == ("slide-", "stick", "slide-")
    assert slide_end < 1e-30  # the instant where the cap outgrows -eta s
    contact = res.contact_time
    steps = [contact / n for n in (1_024_000, 8_192_000)]  # dt and dt / 8
    ends = [_discrete_stick_end(DAMPED, spring, angle, dt) for dt in steps]
    gaps = [stick_end - e for e in ends]
    assert 0 < gaps[1] < gaps[0]  # from below, closing in
    # dt**0.25 convergence: the gap shrinks by 8**-0.25 = 0.595 per refinement (measured
    # 0.587); 5 % for the next order's share at these steps
    assert gaps[1] / gaps[0] == pytest.approx(8**-0.25, rel=0.05)
    ratio = -res.tangential_impulse / res.normal_impulse
    assert 0.092 * (1 - 1e-4) < ratio < 0.092  # the stick's share: measured 5.0e-5


@pytest.mark.parametrize("sensor", [cl.Sensor.rigid(), SENSOR], ids=["rigid", "sensor"])
@pytest.mark.parametrize("degrees", [0.0, 10.0, 45.0])
def test_normal_side_is_the_normal_impact(sensor, degrees):
    """The tangential force does not act on the normal motion."""
    angle = math.radians(degrees)
    res = cl.simulate_oblique(GRAIN, sensor, DAMPED, TANGENTIAL["total"], SPEED, angle, spin=50.0)
    alone = cl.simulate_impact(GRAIN, sensor, DAMPED, SPEED * math.cos(angle))
    # both integrate the same normal equations at rtol 1e-9 and 1e-10
    assert res.restitution == pytest.approx(alone.restitution, rel=1e-8)
    assert res.contact_time == pytest.approx(alone.contact_time, rel=1e-8)
    assert res.peak_normal_force == pytest.approx(alone.peak_contact_force, rel=1e-6)


@pytest.mark.parametrize("tangential", TANGENTIAL.keys())
@pytest.mark.parametrize("spin", [-400.0, 0.0, 400.0])
def test_energy_never_grows_and_contact_momentum(tangential, spin):
    """Kinetic energy never grows; angular momentum about the contact point is kept."""
    inertia = 0.4 * GRAIN.mass * GRAIN.radius**2
    for degrees in (5, 15, 25, 35, 50, 70, 85):
        res = cl.simulate_oblique(
            GRAIN,
            cl.Sensor.rigid(),
            HERTZ,
            TANGENTIAL[tangential],
            SPEED,
            math.radians(degrees),
            spin=spin,
        )
        balance = res.energy_balance
        if (tangential, spin, degrees) == ("total", 400.0, 15):
            continue  # the total form creates energy here: test_total_form_energy_gain
        # round-off of the kinetic energies at rtol 1e-9 (measured <= 4e-9)
        assert balance["dissipated"] >= -1e-8 * balance["kinetic_in"]
        before = inertia * spin + GRAIN.mass * GRAIN.radius * res.incident_tangential_velocity
        after = inertia * res.angular_velocity + GRAIN.mass * GRAIN.radius * res.tangential_velocity
        # I w + m R vt is an exact invariant: only integration error remains
        assert after == pytest.approx(before, rel=1e-9, abs=1e-12 * abs(GRAIN.mass * SPEED))


def _lammps_rebound(lammps_rules, law, angle, spin, steps):
    """Rebound ``(vn', vt', spin')`` by LAMMPS' update rules (conftest.py) of this file's
    grain at SPEED and ``angle`` [rad] from the normal, spinning at ``spin`` [rad/s],
    on a rigid flat through HERTZ and ``law`` (friction 0.092)."""
    vn, vt = SPEED * math.cos(angle), SPEED * math.sin(angle)
    tangential = (law.history_kind, law.stiffness, 0.092)
    return lammps_rules(GRAIN.mass, GRAIN.radius, HERTZ.k_hertz, tangential, vn, vt, spin, steps)


def test_total_form_energy_gain(lammps_rules):
    """LAMMPS' ``mindlin`` (total displacement) is not conservative: while sticking its
    force ``-kt(d) h`` does work ``integral kt' h**2 / 2``, which can come out positive.
    Nearly rolling at 15 deg it gains 4.4e-8 of the impact energy; LAMMPS' own update
    rules (independent integrator) give the same gain, so it is the model, not the solver.
    """
    inertia = 0.4 * GRAIN.mass * GRAIN.radius**2
    angle, spin = math.radians(15.0), 400.0
    law = TANGENTIAL["total"]
    res = cl.simulate_oblique(
        GRAIN, cl.Sensor.rigid(), HERTZ, law, SPEED, angle, spin=spin, rtol=1e-11
    )
    gain = -res.energy_balance["dissipated"] / res.energy_balance["kinetic_in"]
    out = _lammps_rebound(lammps_rules, law, angle, spin, steps=8000)
    e_in = 0.5 * GRAIN.mass * SPEED**2 + 0.5 * inertia * spin**2
    e_out = 0.5 * GRAIN.mass * (out[0] ** 2 + out[1] ** 2) + 0.5 * inertia * out[2] ** 2
    assert gain > 3e-8  # a real gain, ten times the solver's error at this tolerance
    # 8000 steps: the rules' own step error is ~1e-10 of the energy (converged to 1 %)
    assert gain == pytest.approx((e_out - e_in) / e_in, rel=0.02)


@pytest.mark.parametrize("spin", [-3000.0, -20.0, 20.0, 3000.0])
def test_spin_at_normal_incidence(spin):
    """A spinning sphere dropped straight down: friction drives it along the flat (a
    slow spin sticks and the tangential spring's recoil may reverse it)."""
    res = cl.simulate_oblique(
        GRAIN, cl.Sensor.rigid(), HERTZ, TANGENTIAL["total"], SPEED, 0.0, spin=spin
    )
    assert res.slip_before == pytest.approx(-GRAIN.radius * spin)
    impact = analytic.ObliqueImpact(SPEED, 0.0, spin, GRAIN.radius, 1.0, 0.092)
    if analytic.slides_throughout(impact):
        assert np.sign(res.tangential_velocity) == np.sign(spin)  # it rolls the way it spins
        vt, w = analytic.gross_sliding_rebound(impact)
        # elastic Hertz: e = 1 to solver precision, closed form exact in sliding
        assert res.tangential_velocity == pytest.approx(vt, rel=1e-6)
        assert res.angular_velocity == pytest.approx(w, rel=1e-6)


@pytest.mark.parametrize("history", ["total", "incremental"])
@pytest.mark.parametrize("degrees", [5.0, 10.0, 20.0])
def test_lammps_update_rules_converge_to_the_solver(history, degrees, lammps_rules):
    """LAMMPS' discrete rules at a small step give this solver's rebound (stick/slip)."""
    law = TANGENTIAL[history]
    angle = math.radians(degrees)
    res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), HERTZ, law, SPEED, angle)
    ref = _lammps_rebound(lammps_rules, law, angle, 0.0, steps=2000)
    vn = SPEED * math.cos(angle)
    # the rules are first order in the step (incremental); 2000 steps: < 1e-4 of the speed
    assert abs(res.tangential_velocity - ref[1]) < 1e-4 * SPEED
    assert abs(GRAIN.radius * (res.angular_velocity - ref[2])) < 1e-4 * SPEED
    assert res.restitution == pytest.approx(ref[0] / vn, abs=1e-6)  # Verlet, second order


def test_stick_slip_phases_at_small_angle():
    """Near normal incidence the contact sticks and reverses (Maw et al. 1976)."""
    res = cl.simulate_oblique(
        GRAIN, cl.Sensor.rigid(), HERTZ, TANGENTIAL["total"], SPEED, math.radians(5.0)
    )
    kinds = [p[2] for p in res.phases]
    assert "stick" in kinds and "slide+" in kinds  # the tangential spring recoils
    cap = 0.092 * res.normal_force + 1e-9 * res.peak_normal_force
    assert np.all(np.abs(res.tangential_force) <= cap)  # Coulomb never exceeded


def test_signals_and_table():
    res = cl.simulate_oblique(
        GRAIN, SENSOR, DAMPED, TANGENTIAL["incremental"], SPEED, 0.5, sample_rate=5e7
    )
    frame = res.to_pandas()
    assert list(frame.columns)[:3] == ["t [s]", "normal_force [N]", "tangential_force [N]"]
    assert frame["t [s]"].diff().iloc[1] == pytest.approx(2e-8)
    assert np.all(res.normal_force >= 0.0)
    assert res.peak_tangential_force <= 0.092 * res.peak_normal_force * (1 + 1e-9)
    _fig, ax = res.plot()
    assert len(ax.lines) >= 3
    summary = res.summary()
    assert summary["restitution [-]"] == res.restitution


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"angle": math.pi / 2}, "angle"),
        ({"angle": -0.1}, "angle"),
        ({"angle": math.nan}, "angle"),
        ({"velocity": math.nan}, "velocity"),
        ({"spin": math.inf}, "spin"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, name):
    args = {"velocity": SPEED, "angle": 0.3} | kwargs
    with pytest.raises(ParameterError, match=name):
        cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), HERTZ, TANGENTIAL["total"], **args)


def test_bad_laws_and_keywords():
    with pytest.raises(ParameterError, match="friction"):
        Mindlin(1e9, -0.1)
    with pytest.raises(ParameterError, match="history"):
        Mindlin(1e9, 0.1, history="totl")
    with pytest.raises(ParameterError, match="normal_law"):
        cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), TANGENTIAL["total"], HERTZ, SPEED, 0.3)
    with pytest.raises(TypeError):
        cl.simulate_oblique(
            GRAIN, cl.Sensor.rigid(), HERTZ, TANGENTIAL["total"], SPEED, 0.3, spinn=1.0
        )
