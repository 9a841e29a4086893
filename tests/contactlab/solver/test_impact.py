"""The two-mass solver against an independent integration, limits and invariants."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import contactlab as cl
from contactlab import analytic
from contactlab.laws import Hertz, HertzDamped, LinearViscoelastic, PlasticTrapezoid, WaltonBraun
from contactlab.solver.wall import wall_impact


def reference(grain, sensor, force, velocity, t_max):
    """Tight DOP853 of the same equations, written out independently of the package."""
    m1, k1, c1, m2 = sensor.mass, sensor.stiffness, sensor.damping, grain.mass

    def rhs(t, y):
        x1, v1, x2, v2 = y
        s2 = force(x2 - x1, v2 - v1)
        return [v1, (s2 - k1 * x1 - c1 * v1) / m1, v2, -s2 / m2]

    def end(t, y):
        return force(y[2] - y[0], y[3] - y[1])

    end.terminal, end.direction = True, -1
    sol = solve_ivp(
        rhs,
        (0, t_max),
        [0, 0, 0, velocity],
        "DOP853",
        rtol=1e-13,
        atol=1e-20,
        events=end,
        dense_output=True,
    )
    t_c = sol.t_events[0][0]
    tt = np.linspace(0, t_c, 200001)
    y = sol.sol(tt)
    f = force(y[2] - y[0], y[3] - y[1])
    return {
        "contact_time": t_c,
        "peak_contact_force": f.max(),
        "rebound": -sol.y_events[0][0][3],
        "impulse": np.trapezoid(f, tt),
    }


@pytest.mark.parametrize(
    ("law", "rel"),
    [
        # linear law: exact solver, root-located events -> 1e-8 (the target)
        (LinearViscoelastic(1e5, 1.0), 1e-8),
        (LinearViscoelastic(1e4, 0.0), 1e-8),
        # Hertz family: adaptive DOP853 at rtol 1e-10 -> 1e-6 (the target)
        (Hertz(1.5e6), 1e-6),
        (HertzDamped(1.5e6, 0.2), 1e-6),
    ],
)
def test_independent_integration(paper_grain, paper_sensor, law, rel):
    res = cl.simulate_impact(paper_grain, paper_sensor, law, velocity=2.0, duration=500e-6)
    ref = reference(paper_grain, paper_sensor, lambda d, r: law._force(d, r, None), 2.0, 1e-3)
    assert res.contact_time == pytest.approx(ref["contact_time"], rel=rel)
    # the reference peak is read on a 200 001-point grid: relative error ~ (pi/2e5)**2 / 2
    assert res.peak_contact_force == pytest.approx(ref["peak_contact_force"], rel=max(rel, 1e-9))
    rebound = -res._evaluate([res.separation_time])[0][0, 3]
    assert rebound == pytest.approx(ref["rebound"], rel=rel)
    # trapezoidal reference impulse on 200 001 points: error ~1e-10 relative
    assert res.contact_intervals[0][1] - res.contact_intervals[0][0] > 0
    first = res._integrate(lambda st, f: f, *res.contact_intervals[0])
    assert first == pytest.approx(ref["impulse"], rel=max(rel, 1e-9))


def test_heavy_stiff_sensor_is_a_wall(paper_grain):
    law = LinearViscoelastic(1e5, 1.0)
    wall = cl.simulate_impact(paper_grain, cl.Sensor.rigid(), law, velocity=2.0)
    # 10 MHz is beyond any real sensor, on purpose: the warning says so
    with pytest.warns(cl.PlausibilityWarning, match="resonance = 1e\\+07 Hz"):
        heavy = cl.Sensor.from_resonance(10e6, mass=10.0, damping_ratio=0.02)
    res = cl.simulate_impact(paper_grain, heavy, law, velocity=2.0, duration=wall.duration)
    # m2/m1 = 5e-6 and (f_contact/f1)**2 ~ 1e-8: the wall limit holds to ~1e-5
    assert res.contact_time == pytest.approx(wall.contact_time, rel=1e-5)
    assert res.restitution == pytest.approx(wall.restitution, rel=1e-5)


def test_slow_pulse_is_followed(paper_grain):
    # contact 222 us vs sensor period 5 us: quasi-static error ~ (T/tau)**2 ~ 1e-3
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 200e3, damping_ratio=0.02)
    res = cl.simulate_impact(
        paper_grain, sensor, LinearViscoelastic(1e4, 0.0), velocity=2.0, duration=300e-6
    )
    assert res.peak_sensor_force == pytest.approx(res.peak_contact_force, rel=0.01)
    assert res.sensor_response_time == pytest.approx(res.contact_time, rel=0.02)


@pytest.mark.parametrize("ratio", [1.5, 2.5])
def test_half_sine_shock_spectrum_zeros(ratio):
    # prescribed half-sine as a fine trapezoid is not a half-sine; use a linear law on a
    # wall-like heavy grain instead: contact force of an elastic linear contact is a half
    # sine of length pi/w whose residual ringing on an undamped sensor vanishes at tau/T
    sensor = cl.Sensor.from_resonance(40e3, mass=1.0, damping_ratio=0.0)
    tau = ratio * sensor.period
    m2 = 1e-6
    k2 = m2 * (math.pi / tau) ** 2
    grain = cl.Grain.from_mass(m2)
    res = cl.simulate_impact(
        grain, sensor, LinearViscoelastic(k2), velocity=1.0, duration=tau + 4 * sensor.period
    )
    after = res.t > tau * 1.01
    peak_force = res.peak_contact_force
    residual = np.abs(res.sensor_force[after]).max() / peak_force
    # m2/m1 = 1e-6 perturbs the pulse by ~1e-6; a non-zero of the spectrum is O(0.1-1)
    assert residual < 1e-4
    assert analytic.half_sine_residual_amplitude(tau, sensor.period) < 1e-12


def test_short_pulse_peak_measures_impulse(paper_grain):
    # tau << T: the sensor sees an impulse J, and its peak is about w1 * J
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 1e3, damping_ratio=0.0)
    law = PlasticTrapezoid(5e-6, 1e-6)
    res = cl.simulate_impact(paper_grain, sensor, law, velocity=2.0, duration=1.2e-3)
    impulse = paper_grain.mass * 2.0
    # tau/T = 0.005: the impulse approximation errs by ~(pi tau/T)**2/6 ~ 4e-5
    assert res.peak_sensor_force == pytest.approx(2 * math.pi * 1e3 * impulse, rel=1e-3)


@pytest.mark.parametrize(
    "law",
    [
        LinearViscoelastic(1e5, 1.0),
        WaltonBraun(1e5, 3e5),
        HertzDamped(1.5e6, 0.3),
        PlasticTrapezoid(60e-6, 6e-6),
    ],
)
def test_invariants(paper_grain, paper_sensor, law):
    res = cl.simulate_impact(paper_grain, paper_sensor, law, velocity=2.0, duration=500e-6)
    v1_end = res._evaluate([res.duration])[0][0, 1]
    # integral S1 + m1 v1(end) = integral S2 (momentum of the sensor mass); quadrature 1e-9
    lhs = res.sensor_impulse + paper_sensor.mass * v1_end
    assert lhs == pytest.approx(res.impulse, rel=1e-8)
    balance = res.energy_balance
    # energy closes to the solver's accuracy (rtol 1e-10) and the quadrature's (~1e-9)
    assert abs(balance["residual"]) < 1e-7 * balance["kinetic_in"]


def test_paper_conclusions_2_and_3(paper_grain):
    # an undamped contact: with c2 = 1 N*s/m the force steps to c2 v0 = 2 N at touch and
    # the step rings the sensor whatever the pulse length (the paper's Figure 5 case)
    law = LinearViscoelastic(1e4, 0.0)
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    long = cl.simulate_impact(paper_grain, sensor, law, velocity=2.0, duration=500e-6)
    assert long.contact_time > sensor.period / 2  # 222 us vs 12.5 us
    # conclusion 2: long pulse -> the signal follows the force; quasi-static error
    # ~ (T / tau)**2 ~ 1 %, plus ringing from the pulse's kink at touch: allow 5 %
    assert long.peak_sensor_force == pytest.approx(long.peak_contact_force, rel=0.05)
    assert long.sensor_response_time == pytest.approx(long.contact_time, rel=0.05)
    # conclusion 3: a short pulse on a slow sensor -> first lobe outlasts the contact and
    # lasts about half a sensor period
    slow = cl.Sensor.from_disc(10e-3, 2e-3, 2e3, damping_ratio=0.02)
    short = cl.simulate_impact(
        paper_grain, slow, LinearViscoelastic(1e5, 1.0), velocity=2.0, duration=1.5e-3
    )
    assert short.sensor_response_time > 3 * short.contact_time
    assert short.sensor_response_time == pytest.approx(slow.period / 2, rel=0.1)


def test_euler_agrees_within_its_truncation_error(paper_grain, paper_sensor):
    law = LinearViscoelastic(1e5, 1.0)
    exact = cl.simulate_impact(paper_grain, paper_sensor, law, velocity=2.0, duration=80e-6)
    # dt = 1e-9 (not the paper's 1e-10) keeps the pure-Python loop near 0.2 s; first-order
    # error ~ dt * w ~ 1e-9 * 2e5 ~ 1e-4 relative, events step-limited (+- dt)
    euler = cl.simulate_impact(
        paper_grain, paper_sensor, law, velocity=2.0, duration=80e-6, method="euler", time_step=1e-9
    )
    assert euler.contact_time == pytest.approx(exact.contact_time, abs=5e-9)
    assert euler.restitution == pytest.approx(exact.restitution, rel=2e-3)


def test_verify_reports_small_differences(paper_grain, paper_sensor):
    res = cl.simulate_impact(
        paper_grain,
        paper_sensor,
        LinearViscoelastic(1e5, 1.0),
        velocity=2.0,
        duration=200e-6,
        verify=True,
    )
    # exact vs adaptive at rtol 1e-12: agreement to ~1e-9
    assert res.verification["contact_time"] < 1e-8
    assert res.verification["reference_method"] == "adaptive"


def test_a_rate_at_the_resolution_minimum_up_to_round_off_does_not_warn(paper_grain):
    # a rigid wall: the minimum is ten samples per contact time, 10 / (t_end - t_touch)
    law = LinearViscoelastic(1e5, 1.0)
    (start, end), *_ = cl.simulate_impact(
        paper_grain, cl.Sensor.rigid(), law, 2.0
    ).contact_intervals
    minimum = 10.0 / (end - start)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        # one ulp below the minimum: round-off of the rate, not too few samples
        cl.simulate_impact(
            paper_grain, cl.Sensor.rigid(), law, 2.0, sample_rate=np.nextafter(minimum, 0.0)
        )
    with pytest.warns(cl.ResolutionWarning, match="at least"):
        # 1 % below is a real shortfall
        cl.simulate_impact(paper_grain, cl.Sensor.rigid(), law, 2.0, sample_rate=0.99 * minimum)


def test_bad_input_and_warnings(paper_grain, paper_sensor):
    law = LinearViscoelastic(1e5, 1.0)
    with pytest.raises(cl.ParameterError, match="velocity"):
        cl.simulate_impact(paper_grain, paper_sensor, law, velocity=-1.0)
    with pytest.raises(cl.ParameterError, match="method"):
        cl.simulate_impact(paper_grain, paper_sensor, law, velocity=1.0, method="rk4")
    with pytest.raises(cl.ParameterError, match="nonlinear"):
        cl.simulate_impact(paper_grain, paper_sensor, Hertz(1e6), velocity=1.0, method="exact")
    with pytest.raises(cl.ParameterError, match="resonance"):
        cl.Sensor.from_resonance(-40e3, mass=1e-3)
    with pytest.warns(cl.WindowWarning, match="at least"):
        cl.simulate_impact(paper_grain, paper_sensor, law, velocity=2.0, duration=10e-6)
    with pytest.warns(cl.ResolutionWarning, match="at least"):
        cl.simulate_impact(
            paper_grain, paper_sensor, law, velocity=2.0, duration=500e-6, sample_rate=100e3
        )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cl.simulate_impact(paper_grain, paper_sensor, law, velocity=2.0, duration=500e-6)


def test_result_outputs(paper_grain, paper_sensor):
    res = cl.simulate_impact(
        paper_grain, paper_sensor, LinearViscoelastic(1e5, 1.0), velocity=2.0, duration=500e-6
    )
    frame = res.to_frame()
    assert list(frame.columns[:3]) == ["t [s]", "contact_force [N]", "sensor_force [N]"]
    assert len(frame) == 20001
    _, ax = res.plot()
    assert ax.get_xlabel() == "time [µs]"
    assert "contact_time" in repr(res)


@pytest.mark.parametrize(
    "law",
    [LinearViscoelastic(1e5, 1.0), HertzDamped(1.5e6, 0.2), PlasticTrapezoid(70e-6, 7e-6)],
)
@pytest.mark.parametrize("sensor_hz", [None, 40e3])
def test_grid_matches_dense_evaluation(paper_grain, law, sensor_hz):
    """The fast uniform-grid paths equal pointwise evaluation of the same solution."""
    sensor = cl.Sensor.rigid() if sensor_hz is None else cl.Sensor.from_disc(10e-3, 2e-3, sensor_hz)
    res = cl.simulate_impact(paper_grain, sensor, law, 2.0, 300e-6)
    states, force = res._evaluate(res.t)
    grid = np.column_stack([res.x1, res.v1, res.x2, res.v2])
    scale = np.max(np.abs(states), axis=0) + 1e-300
    # the grid multiplies two tables of exponentials where pointwise evaluation takes one
    # exponential: a few roundings apart, so 1e-12 of each signal's range
    assert np.max(np.abs(grid - states) / scale) < 1e-12
    assert np.max(np.abs(res.contact_force - force)) <= 1e-12 * np.max(force)


def test_receding_grain_touching_at_zero_overlap_is_not_a_contact():
    """Regression: a grain leaving a damped linear contact reaches zero overlap exactly on
    an event-scan point; touching is not contact (found by the invariant property test)."""
    res = wall_impact(LinearViscoelastic(1000.0, 0.125), 5.0e-5, 1.0)
    assert len(res.contact_intervals) == 1
    # grain work equals the kinetic energy change (Gauss-Legendre on straight pieces)
    kinetic_change = 0.5 * 5.0e-5 * (res.v2[-1] ** 2 - 1.0)
    assert res.grain_work == pytest.approx(kinetic_change, rel=1e-9)


def test_event_root_on_a_force_vanishing_like_a_power_1_5():
    """Regression: Thornton's unloading force ``kp (d - dp)**1.5`` vanishes with zero slope,
    where Brent's method needs more than scipy's default 100 iterations (found by the
    invariant property test)."""
    law = cl.laws.Thornton(20587035.16746306, 0.0005, 330998.08004019235)
    res = wall_impact(law, 5.0e-5, 7.0)
    assert 0.0 < res.restitution < 1.0
    # momentum balance on the dense solution, as in the law invariants (quadrature 1e-6)
    assert res.impulse == pytest.approx(5.0e-5 * 7.0 * (1.0 + res.restitution), rel=1e-6)


@pytest.mark.parametrize(
    "law",
    [
        HertzDamped(1.5e6, 0.2),
        # yields almost at the touch: the branch change falls inside the start in s
        cl.laws.Thornton(20e6, 2.5e-3, 1e5),
    ],
)
def test_loose_tolerance_keeps_event_times_tight(paper_grain, paper_sensor, law):
    """Starting a contact in s = t**(1/4) removes the touch's singularity, so even a loose
    tolerance places the contact end far better than the tolerance itself."""
    loose = cl.simulate_impact(paper_grain, paper_sensor, law, 2.0, 500e-6, rtol=1e-6)
    tight = cl.simulate_impact(paper_grain, paper_sensor, law, 2.0, 500e-6, rtol=1e-13)
    # measured 5e-10 (damped Hertz) at rtol 1e-6; 1e-8 leaves a factor 20
    assert loose.contact_time == pytest.approx(tight.contact_time, rel=1e-8)
    assert [e[1] for e in loose.events] == [e[1] for e in tight.events]
    assert loose.impulse == pytest.approx(tight.impulse, rel=1e-7)


def test_damper_jump_at_the_touch_is_the_attained_peak(paper_grain):
    """A damped linear contact on a stiff sensor jumps to c v0 at the touch and falls from
    there: the peak is that value, exactly, at t = 0, on any output grid."""
    sensor = cl.Sensor.from_resonance(200e3, mass=1.233e-3, damping_ratio=0.02)
    law = LinearViscoelastic(1e4, 1.0)  # c**2 / m = 2e4 N/m > k: the force falls from t = 0
    for rate in (2e7, 1e9):
        res = cl.simulate_impact(paper_grain, sensor, law, 2.0, sample_rate=rate)
        assert res.peak_contact_force == 2.0  # c v0, exact: the state at t = 0 is exact
        assert res.peak_contact_time == 0.0
        assert res.contact_force[0] == 2.0
