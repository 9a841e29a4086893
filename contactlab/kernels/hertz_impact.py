"""The power-law contact piece of the compiled impact loop: DOP853 and readings on it.

A Hertz-family contact (``a d**p + b |d|**q d'``, :mod:`contactlab.kernels.power`) is
integrated by the compiled DOP853 piece (:func:`contactlab.kernels.power_piece.integrate`:
warped start at the touch, the contact's end located on the step's interpolant), the
same piece :func:`contactlab.simulate_impact` runs for every Hertz-family law.

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

from contactlab.compiled import njit
from contactlab.kernels.brent import brent_next, brent_start
from contactlab.kernels.dop853 import interpolate
from contactlab.kernels.modal import (
    CONTACT_PEAK,
    LOBE_END,
    SENSOR_PEAK,
    falls,
    may_exceed,
    raise_peak,
)
from contactlab.kernels.power import (
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
from contactlab.kernels.power_piece import STATUS_OK as PIECE_OK
from contactlab.kernels.power_piece import contact_tolerances, integrate

__all__ = ["INTERVAL_PER_PERIOD", "power_contact", "power_setup"]

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


@njit(cache=True, error_model="numpy", borrowed=True)
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

    ``track`` and ``best`` as in :func:`contactlab.kernels.modal.scan`, with one
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
                raise_peak(best, CONTACT_PEAK, cur[_S2], t_now)
                turns = falls(prev[_S2_SLOPE], cur[_S2_SLOPE])
                if turns and may_exceed(prev[_S2], prev[_S2_SLOPE], best[CONTACT_PEAK], dt):
                    top = _root(
                        _S2_SLOPE, u_prev, prev[_S2_SLOPE], u, cur[_S2_SLOPE], a, hj, Fj, yj,
                        par, z, values, work,
                    )  # fmt: skip
                    _at(top, a, hj, Fj, yj, par, z, values)
                    peak = max(force(z[2] - z[0], z[3] - z[1], par), 0.0)
                    raise_peak(best, CONTACT_PEAK, peak, _to_time(top, t0, warped))
            if track[2] and cur[_S1] > floor:
                track[2], track[0] = False, True  # the lobe, started at the touch, is open
            elif track[0]:
                interval = (u_prev, prev, u, cur, dt)
                clock = (t0, warped)
                _read_lobe(interval, clock, a, hj, Fj, yj, par, z, values, track, best, work)
            prev, cur = cur, prev
            u_prev, t_prev = u, t_now
            if u >= u_end:
                return


@njit(cache=True, error_model="numpy", inline="always")
def _read_lobe(interval, clock, a, hj, Fj, yj, par, z, values, track, best, work):
    """The sensor lobe on one sample interval ``(u_prev, prev, u, cur, dt)`` (``dt`` its
    length [s]): its peaks and its end, in time through ``clock = (t0, warped)`` (the step
    variable's origin [s] and whether it is ``s = tau**(1/4)``); ``values`` is scratch."""
    u_prev, prev, u, cur, dt = interval
    t0, warped = clock
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
    if falls(prev[_S1_SLOPE], cur[_S1_SLOPE]) and reach >= best[SENSOR_PEAK]:
        top = _root(
            _S1_SLOPE, u_prev, prev[_S1_SLOPE], u, cur[_S1_SLOPE], a, hj, Fj, yj, par, z,
            values, work,
        )  # fmt: skip
        if top <= end:
            _at(top, a, hj, Fj, yj, par, z, values)
            raise_peak(best, SENSOR_PEAK, values[_S1], _to_time(top, t0, warped))
    if end < u or cur[_S1] <= 0.0:
        best[LOBE_END] = _to_time(end, t0, warped)
        track[0] = False
    else:
        raise_peak(best, SENSOR_PEAK, cur[_S1], _to_time(u, t0, warped))


@njit(cache=True, error_model="numpy")
def _state_at(steps, u, y):
    """State at step variable ``u`` on a run of steps (the step holding ``u``)."""
    count, t_old, h, y_old, F = steps
    j = min(max(np.searchsorted(t_old[:count], u, side="right") - 1, 0), count - 1)
    z = np.empty(y_old.shape[1])
    interpolate(F[j], y_old[j], (u - t_old[j]) / h[j], z)
    y[:] = z[:4]


@njit(cache=True, error_model="numpy")
def power_setup(par, v0, rtol):
    """What every power-law contact piece of an impact at ``v0`` [m/s] shares:
    ``(rtol, atol, limits)``, the integrator's tolerances
    (:func:`contactlab.kernels.power_piece.contact_tolerances`) and the reading's noise
    floor [N] and longest sample interval [s] (see :func:`_read_steps`)."""
    atol = contact_tolerances(rtol, v0)
    rigid = par[RIGID] > 0.0
    floor = 0.0 if rigid else _NOISE * (par[K1] * atol[0] + par[C1] * atol[1])
    return rtol, atol, (floor, INTERVAL_PER_PERIOD * _shortest_period(par, v0))


@njit(cache=True, error_model="numpy")
def power_contact(setup, par, t, y, horizon, track, best, work):
    """One power-law contact piece from ``(t, y)`` [s, state]; returns its end time [s]
    (nan: none within ``horizon`` [s]) or -1 on a step-size underflow. ``y`` becomes the
    state at the end; ``setup`` is :func:`power_setup`'s; ``track`` and ``best`` as in
    :func:`_read_steps`."""
    rtol, atol, limits = setup
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
