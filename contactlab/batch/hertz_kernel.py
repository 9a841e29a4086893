"""Compiled kernel of :func:`contactlab.batch.hertz_impacts`: one damped-Hertz impact per row.

Each row is solved as :func:`contactlab.simulate_impact` solves a grain on a sensor (or a
wall) through :class:`~contactlab.laws.HertzDamped` (Tsuji's ``kH d**1.5 + eta d**0.25
d'``) with ``method="adaptive"``: every contact piece by the compiled DOP853 piece of the
single solver (:func:`contactlab.solver.power_piece.integrate`: warped start at the
touch, the contact's end located on the step's interpolant), every free flight exactly
in modal form (:func:`contactlab.batch.modal_kernel.free_flight`), the same window and
contact cap.

The headline numbers are read on the dense solution as
:class:`contactlab.ImpactResult` defines them: each contact step is sampled at points
no further apart than :data:`INTERVAL_PER_PERIOD` of a bound on the system's fastest
period (so a sample interval holds at most one turn of either signal); a fall of a
signal's slope through zero between two of them is a local maximum, located by Brent's
method on the slope and read there, and a fall of the sensor signal through zero ends
its first lobe.
"""

import math

import numpy as np

from contactlab.batch.modal_kernel import (
    COND_LIMIT,
    IN_CONTACT,
    SENSOR,
    STATUS_FALLBACK,
    STATUS_OK,
    conjugates_once,
    falls,
    fastest,
    free_flight,
    may_exceed,
    quadratic_modes,
    row_parameters,
    signal,
)
from contactlab.compiled import njit
from contactlab.solver.brent import WORK_SIZE, brent_next, brent_start
from contactlab.solver.dop853_kernel import interpolate
from contactlab.solver.impact import (
    FIRST_CONTACT_HORIZON,
    MAX_CONTACTS,
    RINGING_PERIODS,
    WINDOW_PER_CONTACT,
)
from contactlab.solver.power_piece import STATUS_OK as PIECE_OK
from contactlab.solver.power_piece import contact_tolerances, integrate
from contactlab.solver.power_rhs import (
    C1,
    DAMPING,
    DAMPING_EXPONENT,
    EXPONENT,
    K1,
    M1,
    M2,
    RIGID,
    STIFFNESS,
    force,
    power,
)

__all__ = ["INTERVAL_PER_PERIOD", "solve_rows"]

INTERVAL_PER_PERIOD = 0.18
"""Longest sample interval in which the signals' turns are looked for, as a fraction of
the shortest period the contact can have (:func:`_shortest_period`).

A signal's turns are half a period apart, so an interval well under half a period holds
at most one. Measured on 400 random rows (the tests' domain), an integrator step spans
up to 1.44 periods of the fastest mode of the linearised two-mass system (where that
mode is barely excited): a fixed two samples per step (0.72 period) missed turns and
moved sensor peaks by up to 3e-4; eight (0.18) did not. Sampling at 0.18 of the bound
(:func:`_shortest_period`) instead of a count gives the same numbers as at 0.03 of it on
3 000 random rows at rtol 1e-9 to 1.4e-7, and at rtol 1e-6 to 3e-4: the finer sampling
then finds wiggles of the interpolant on overdamped plates, peaks 3e-4 above the
converged one where the coarser reading is within 3e-5 (the single solver's zoom finds
them too). On the benchmark's rows (sensor 10-300 kHz) the steps are mostly shorter
than the interval, and one thread solves 8 300 rows/s against 3 500 with eight samples
a step."""

_S2, _S2_SLOPE, _S1, _S1_SLOPE = range(4)

_NOISE = 100.0
"""Sensor signal below this many times the integrator's absolute tolerance (in the
signal's units) is not yet read as the lobe (see :func:`_read_steps`)."""

_STEEP = np.finfo(np.float64).max
"""The contact force's slope at the touch, where it is infinite for a damped Hertz law
(``d**0.25``): the largest float keeps Brent's interpolation finite."""


@njit(cache=True, error_model="numpy", inline="always")
def _signals(z, par, out):
    """Contact force S2 (clipped), its slope, sensor signal S1 and its slope, in time."""
    d, r = z[2] - z[0], z[3] - z[1]
    raw = force(d, r, par)
    s1 = 0.0 if par[RIGID] > 0.0 else par[K1] * z[0] + par[C1] * z[1]
    a1 = 0.0 if par[RIGID] > 0.0 else (raw - s1) / par[M1]
    rate_of_rate = -raw / par[M2] - a1
    out[_S2] = 0.0 if d < 0.0 else max(raw, 0.0)
    if d > 0.0:
        d_p = power(d, d, par[EXPONENT], False)
        slope = par[STIFFNESS] * par[EXPONENT] * d_p / d * r
        if par[DAMPING] != 0.0:
            d_q = power(d, d, par[DAMPING_EXPONENT], False)
            slope += par[DAMPING] * d_q * (par[DAMPING_EXPONENT] * r * r / d + rate_of_rate)
        out[_S2_SLOPE] = slope
    else:
        out[_S2_SLOPE] = _STEEP if r > 0.0 else 0.0
    out[_S1] = s1
    out[_S1_SLOPE] = 0.0 if par[RIGID] > 0.0 else par[K1] * z[1] + par[C1] * a1


@njit(cache=True, error_model="numpy", inline="always")
def _at(u, a, h, F, y_old, par, z, values):
    """Signals at step variable ``u`` of the step starting at ``a`` of length ``h``."""
    interpolate(F, y_old, (u - a) / h, z)
    _signals(z, par, values)


@njit(cache=True, error_model="numpy")
def _root(kind, lo, f_lo, hi, f_hi, a, h, F, y_old, par, z, values, work):
    """Where signal ``kind`` crosses zero on [lo, hi] inside one step (Brent)."""
    x, done = brent_start(work, lo, f_lo, hi, f_hi)
    while not done:
        _at(x, a, h, F, y_old, par, z, values)
        x, done = brent_next(work, values[kind])
    return x


@njit(cache=True, error_model="numpy")
def _shortest_period(par, v0):
    """A lower bound on the periods of the contact's oscillations [s].

    The overlap never exceeds the elastic one on a rigid wall, ``d_max = (5 m2 v0**2 /
    (4 kH))**(2/5)`` (the plate and the damper only take energy), so the contact
    stiffness ``1.5 kH d**0.5`` stays below ``kc``; the eigenvalues of ``M**-1 K`` of the
    linearised two-mass system are below their Gershgorin bound
    ``max((k1 + 2 kc) / m1, 2 kc / m2)`` (on a wall ``kc / m2``).
    """
    d_max = (5.0 * par[M2] * v0 * v0 / (4.0 * par[STIFFNESS])) ** 0.4
    kc = 1.5 * par[STIFFNESS] * math.sqrt(d_max)
    if par[RIGID] > 0.0:
        omega2 = kc / par[M2]
    else:
        omega2 = max((par[K1] + 2.0 * kc) / par[M1], 2.0 * kc / par[M2])
    return 2.0 * math.pi / math.sqrt(omega2)


@njit(cache=True, error_model="numpy", inline="always")
def _to_time(u, t0, warped):
    return t0 + u**4 if warped else u


@njit(cache=True, error_model="numpy")
def _read_steps(steps, warped, t0, u_end, par, limits, track, best, z, work):
    """Read the signals' turns on a run of steps up to step variable ``u_end``.

    ``track`` and ``best`` as in :func:`contactlab.batch.modal_kernel.scan`, with one
    more: track [0] the sensor lobe is open, [1] the contact force's peak is wanted,
    [2] the signal has not yet risen above ``floor`` [N]; best [0] sensor peak [N], [1]
    contact-force peak [N], [2] lobe end (absolute time [s]). ``limits`` is
    ``(floor, spacing)``: the noise floor [N] and the longest sample interval [s].

    The signal starts at zero at the touch (the plate at rest) and rises: its lobe
    starts there, as :func:`contactlab.metrics.first_lobe` reads it. Until it rises
    above ``floor``, the size of the integrator's absolute tolerance in the signal's
    units, its sign is the interpolant's error (an elastic Hertz force grows like
    ``t**1.5``, the plate's signal like ``t**2.5``), so crossings there are not read.
    """
    count, t_old, h, y_old, F = steps
    floor, spacing = limits
    prev, cur, values = np.empty(4), np.empty(4), np.empty(4)
    for j in range(count):
        a, hj = t_old[j], h[j]
        if a >= u_end:
            return
        Fj, yj = F[j], y_old[j]
        u_prev, t_prev = a, _to_time(a, t0, warped)
        if j == 0:  # later steps start where the last one's final sample ended
            _at(a, a, hj, Fj, yj, par, z, prev)
        span = 4.0 * (a + hj) ** 3 * hj if warped else hj  # longest time the step covers
        samples = max(1, math.ceil(span / spacing))
        for i in range(1, samples + 1):
            u = min(a + hj * i / samples, u_end)
            _at(u, a, hj, Fj, yj, par, z, cur)
            t_now = _to_time(u, t0, warped)
            dt = t_now - t_prev
            if track[1]:
                best[1] = max(best[1], cur[_S2])
                turns = falls(prev[_S2_SLOPE], cur[_S2_SLOPE])
                if turns and may_exceed(prev[_S2], prev[_S2_SLOPE], best[1], dt):
                    top = _root(
                        _S2_SLOPE, u_prev, prev[_S2_SLOPE], u, cur[_S2_SLOPE], a, hj, Fj, yj,
                        par, z, values, work,
                    )  # fmt: skip
                    _at(top, a, hj, Fj, yj, par, z, values)
                    best[1] = max(best[1], max(force(z[2] - z[0], z[3] - z[1], par), 0.0))
            if track[2] and cur[_S1] > floor:
                track[2], track[0] = False, True  # the lobe, started at the touch, is open
            elif track[0]:
                interval = (u_prev, prev, u, cur, dt)
                _read_lobe(interval, a, hj, Fj, yj, par, z, values, track, best, work)
                if not track[0]:
                    best[2] = _to_time(best[2], t0, warped)
            prev, cur = cur, prev
            u_prev, t_prev = u, t_now
            if u >= u_end:
                return


@njit(cache=True, error_model="numpy", inline="always")
def _read_lobe(interval, a, hj, Fj, yj, par, z, values, track, best, work):
    """The sensor lobe on one sample interval ``(u_prev, prev, u, cur, dt)`` (``dt`` its
    length [s]): its peaks, its end (in the step variable); ``values`` is scratch."""
    u_prev, prev, u, cur, dt = interval
    end = u
    reach = prev[_S1] + 2.0 * prev[_S1_SLOPE] * dt  # the bound of may_exceed, both ways
    if falls(prev[_S1], cur[_S1]):
        end = _root(_S1, u_prev, prev[_S1], u, cur[_S1], a, hj, Fj, yj, par, z, values, work)
    elif prev[_S1_SLOPE] < 0.0 and cur[_S1_SLOPE] >= 0.0 and reach <= 0.0:
        # a dip inside the interval: its bottom decides whether the lobe ends there
        low = _root(
            _S1_SLOPE, u_prev, prev[_S1_SLOPE], u, cur[_S1_SLOPE], a, hj, Fj, yj, par, z,
            values, work,
        )  # fmt: skip
        _at(low, a, hj, Fj, yj, par, z, values)
        if values[_S1] <= 0.0:
            bottom = values[_S1]
            end = _root(_S1, u_prev, prev[_S1], low, bottom, a, hj, Fj, yj, par, z, values, work)
    if falls(prev[_S1_SLOPE], cur[_S1_SLOPE]) and reach >= best[0]:
        top = _root(
            _S1_SLOPE, u_prev, prev[_S1_SLOPE], u, cur[_S1_SLOPE], a, hj, Fj, yj, par, z,
            values, work,
        )  # fmt: skip
        if top <= end:
            _at(top, a, hj, Fj, yj, par, z, values)
            best[0] = max(best[0], values[_S1])
    if end < u or cur[_S1] <= 0.0:
        best[2] = end
        track[0] = False
    else:
        best[0] = max(best[0], cur[_S1])


@njit(cache=True, error_model="numpy")
def _state_at(steps, u, y):
    """State at step variable ``u`` on a run of steps (the step holding ``u``)."""
    count, t_old, h, y_old, F = steps
    j = min(max(np.searchsorted(t_old[:count], u, side="right") - 1, 0), count - 1)
    z = np.empty(y_old.shape[1])
    interpolate(F[j], y_old[j], (u - t_old[j]) / h[j], z)
    y[:] = z[:4]


@njit(cache=True, error_model="numpy")
def _contact(par, t, y, horizon, rtol, atol, limits, track, best, work):
    """One contact piece from ``(t, y)``; returns its end time [s] (nan: none within
    ``horizon``) or -1 on a step-size underflow. ``y`` becomes the state at the end."""
    touch = y[2] - y[0] == 0.0 and y[3] - y[1] > 0.0
    status, warp, steps, switch, hit = integrate(par, t, y, horizon, rtol, atol, touch)
    if status != PIECE_OK:
        return -1.0
    end = t + horizon if math.isnan(hit) else hit
    z = np.empty(5)
    reading = track[0] or track[1] or track[2]
    if reading and warp[0] > 0:
        u_end = (end - t) ** 0.25 if end - t < switch or steps[0] == 0 else math.inf
        _read_steps(warp, True, t, u_end, par, limits, track, best, z, work)
    if reading and steps[0] > 0:
        _read_steps(steps, False, t, end, par, limits, track, best, z, work)
    if steps[0] > 0 and end - t >= switch:
        _state_at(steps, end, y)
    else:
        _state_at(warp, (end - t) ** 0.25, y)
    return hit


@njit(cache=True, error_model="numpy")
def solve_row(m1, k1, c1, m2, k_hertz, damping, v0, rtol, out):
    """Solve one impact; write the six outputs into ``out``; return the row status."""
    rigid = math.isinf(k1)
    par = row_parameters(k_hertz, 1.5, damping, 0.25, m1, k1, c1, m2, rigid)
    lam_f, vec_f = np.zeros(2, np.complex128), np.zeros((4, 2), np.complex128)
    inv_f = np.zeros((2, 4), np.complex128)
    nm_f = 0
    if not rigid:
        nm_f = 2
        if not quadratic_modes(m1, c1, k1, 0, lam_f, vec_f, inv_f) < COND_LIMIT:
            return STATUS_FALLBACK
    rate_f = fastest(lam_f, nm_f)
    nm_f = conjugates_once(lam_f, vec_f, inv_f, nm_f)
    free_modes = (lam_f, vec_f, inv_f, nm_f, rate_f)
    ringing = 0.0 if rigid else RINGING_PERIODS * 2.0 * math.pi / math.sqrt(k1 / m1)
    atol = contact_tolerances(rtol, v0)
    y, work = np.array([0.0, 0.0, 0.0, v0]), np.zeros(WORK_SIZE)
    track = np.array([False, True, not rigid])
    best = np.array([0.0, 0.0, math.nan])
    floor = 0.0 if rigid else _NOISE * (k1 * atol[0] + c1 * atol[1])
    limits = (floor, INTERVAL_PER_PERIOD * _shortest_period(par, v0))
    t, limit, contacts, contact_time, rebound = 0.0, math.inf, 0, math.nan, math.nan
    while True:
        par[IN_CONTACT] = 1.0
        if track[0]:  # a piece's start is a candidate for the sensor's peak
            best[0] = max(best[0], signal(SENSOR, y, par))
        horizon = (FIRST_CONTACT_HORIZON if contacts == 0 else limit) - t
        end = _contact(par, t, y, horizon, rtol, atol, limits, track, best, work)
        if end < 0.0 or (math.isnan(end) and contacts == 0):
            return STATUS_FALLBACK
        if math.isnan(end):  # the window ends in this contact
            break
        t = end
        if contacts == 0:
            contact_time = t
            track[1] = False
            if track[2]:  # no rise of the signal in the whole first contact
                return STATUS_FALLBACK
        limit = max(WINDOW_PER_CONTACT * t, t + ringing)  # auto_window, after every contact
        contacts += 1
        rebound = -y[3]
        if contacts >= MAX_CONTACTS:
            return STATUS_FALLBACK
        if limit - t <= 0.0:
            break
        lobe_open = track[0]
        tau = free_flight(y, limit - t, free_modes, par, track, best, work)
        if lobe_open and not track[0]:
            best[2] += t
        if tau < 0.0:  # free until the window ends
            break
        t += tau
    if track[0]:  # the lobe is still open at the window's end
        best[0] = max(best[0], signal(SENSOR, y, par))
    out[0] = contact_time
    out[2] = best[1]
    if rigid:
        out[1], out[3] = contact_time, best[1]
    else:
        out[1], out[3] = best[2], best[0]
    out[4] = rebound / v0
    out[5] = contacts
    return STATUS_OK


@njit(cache=True, error_model="numpy", nogil=True)
def solve_rows(m1, k1, c1, m2, k_hertz, damping, v0, rtol, out, status):
    """Solve every row: ``out`` (rows, 6), ``status`` (rows,); GIL released."""
    for i in range(m1.size):
        row = (m1[i], k1[i], c1[i], m2[i], k_hertz[i], damping[i], v0[i])
        status[i] = solve_row(*row, rtol, out[i])
