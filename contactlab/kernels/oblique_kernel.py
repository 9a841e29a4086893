"""The oblique impact's contact, compiled: stick and slide phases with their events.

:func:`solve_contact` is the phase loop of :mod:`contactlab.solver.oblique` in numba: each
phase a smooth piece integrated by the compiled DOP853 stepper
(:mod:`contactlab.kernels.dop853`, the normal solver's), started in
``s = tau**(1/4)`` at the touch and handed over to time as
:func:`contactlab.solver.adaptive.integrate_piece` does, its events located after every
step by :func:`contactlab.kernels.oblique_events.first_crossing`. The phase at the touch
is LAMMPS' rule in the limit ``t -> 0+`` (:func:`_touch_phase`). The single solver keeps
every step's interpolant (``keep``) for its output grid; the batch
(:mod:`contactlab.batch.oblique`) runs the same loop without them.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.brent import WORK_SIZE
from contactlab.kernels.dop853 import WORK_ROWS, initial_step, interpolant, interpolate, step
from contactlab.kernels.elastic_cap_rhs import EVENTS, events
from contactlab.kernels.model_rhs import ANY_MODEL, rhs
from contactlab.kernels.oblique_events import SUBSTEPS, first_crossing, sample, waits
from contactlab.kernels.oblique_rhs import (
    FRICTION,
    PHASE,
    STICK,
    direction,
    history_on_cap,
    slip,
    trial_force,
)
from contactlab.kernels.power import force
from contactlab.kernels.power_piece import retake_bound

__all__ = [
    "MAX_PHASES",
    "STATUS_CHATTER",
    "STATUS_OK",
    "STATUS_OPEN",
    "STATUS_UNDERFLOW",
    "solve_contact",
    "tolerances",
]

STATUS_OK, STATUS_UNDERFLOW, STATUS_OPEN, STATUS_CHATTER = 0, 1, 2, 3
"""Outcome of :func:`solve_contact`: done; the step size underflowed; the contact had not
ended after a second; more than :data:`MAX_PHASES` stick/slide switches."""

MAX_PHASES = 1000
"""Stick/slide switches after which the solver gives up (a chattering contact)."""

PIECE_LENGTH = 1.0
"""Longest phase [s]: a contact still open after it is not an impact."""

PROBE = 1e-6
"""Fraction of the first step at which the phase at a touch is read."""

STATES = 7
"""``[x1, v1, x2, v2, vt, w, h]``."""

_DENSE = 7  # interpolant coefficient rows
_FIRST_CAPACITY = 64


@njit(cache=True, error_model="numpy")
def tolerances(rtol, velocity, normal_velocity, force_scale, force_history, radius):
    """Absolute tolerances of the seven states.

    ``1e-3 rtol`` of what one microsecond of motion changes: the normal states at the
    normal speed ``normal_velocity`` [m/s] (near grazing incidence many decades below the
    impact speed ``velocity`` [m/s]), the tangential ones at the impact speed, a force
    history at ``force_scale`` [N] times the normal speed's fraction, the spin at
    ``velocity / radius``.
    """
    normal = normal_velocity / velocity
    length = velocity * 1e-6  # displacement scale [m]: 1 us of travel at impact speed
    history = normal * force_scale if force_history else length
    scales = np.array(
        [
            normal * length,
            normal * velocity,
            normal * length,
            normal * velocity,
            velocity,
            velocity / radius,
            history,
        ]
    )
    return 1e-3 * rtol * scales


@njit(cache=True, error_model="numpy")
def _grow(store):
    count, t_old, h, y_old, F = store
    size = 2 * t_old.size
    t2, h2 = np.empty(size), np.empty(size)
    y2, F2 = np.empty((size, y_old.shape[1])), np.empty((size, _DENSE, y_old.shape[1]))
    t2[:count], h2[:count], y2[:count], F2[:count] = t_old, h, y_old, F
    return count, t2, h2, y2, F2


@njit(cache=True, error_model="numpy")
def _empty_store(n, capacity):
    return (
        0,
        np.empty(capacity),
        np.empty(capacity),
        np.empty((capacity, n)),
        np.empty((capacity, _DENSE, n)),
    )


@njit(cache=True, error_model="numpy")
def _run(t, y0, h_try, end, rtol, atol, par, warped, store, keep):
    """Steps from ``(t, y0)`` until ``end``, an event, or (warped) the hand-over to time.

    Returns (status, t, y, last step (t_old, h, y_old, F), hit time, hit index, store):
    ``t, y`` the last step's end; the hit index -1 if no event.
    """
    n = y0.size
    phase = par[PHASE]
    K, f, y_new, f_new = np.empty((WORK_ROWS, n)), np.empty(n), np.empty(n), np.empty(n)
    F, y, y_old, tmp = np.empty((_DENSE, n)), y0.copy(), y0.copy(), np.empty(n)
    row, work, rising = np.empty(EVENTS), np.empty(WORK_SIZE), np.empty(SUBSTEPS + 1)
    times, rows = np.empty(SUBSTEPS + 1), np.zeros((SUBSTEPS + 1, EVENTS))
    armed = np.zeros(EVENTS, dtype=np.bool_)
    rhs(y, par, warped, f)
    count = events(y, par, phase, rows[SUBSTEPS])
    for j in range(count):
        armed[j] = waits(rows[SUBSTEPS, j], direction(j, int(phase)))
    hit, hit_j, t_old, h = math.nan, -1, t, 0.0
    bound, retakes = end, 0
    while t < end:
        ok, t_new, h_next, h = step(
            t, y, f, h_try, bound, rtol, atol, par, warped, K, y_new, f_new, ANY_MODEL
        )
        if not ok:
            return STATUS_UNDERFLOW, t, y, (t_old, h, y_old, F), hit, hit_j, store
        t_old = t
        y_old[:] = y
        interpolant(K, h, y_old, y_new, f_new, par, warped, F, ANY_MODEL)
        sample(t_old, h, y_old, F, y_new, par, phase, times, rows, tmp)
        hit, hit_j = first_crossing(
            (t_old, h, y_old, F), count, armed, times, rows, par, phase, tmp, row, work, rising
        )
        if hit_j == 0:  # the contact's end: the step again, to just past it (power_piece)
            again = retake_bound(t_old, hit, t_new, retakes)
            if not math.isnan(again):
                rows[SUBSTEPS] = rows[0]
                h_try, bound, retakes = h_next, again, retakes + 1
                continue
        if keep:
            if store[0] == store[1].size:
                store = _grow(store)
            c = store[0]
            store[1][c], store[2][c], store[3][c], store[4][c] = t_old, h, y_old, F
            store = (c + 1, store[1], store[2], store[3], store[4])
        y[:] = y_new
        f[:] = f_new
        t, h_try, bound = t_new, h_next, end
        if hit_j >= 0:
            break
        if warped and t_old > 0.0 and t**4 - t_old**4 < t_old**4:
            break  # adaptive._warp_stops_paying: steps in time do as well from here
        for j in range(count):
            armed[j] = armed[j] or waits(rows[SUBSTEPS, j], direction(j, int(phase)))
    return STATUS_OK, t, y, (t_old, h, y_old, F), hit, hit_j, store


@njit(cache=True, error_model="numpy")
def _piece(t0, y0, touch, rtol, atol, par, warp, steps, keep):
    """One phase from ``(t0, y0)``: :func:`contactlab.solver.adaptive.integrate_piece`.

    Returns (status, switch, hit time, hit index, state at the hit, warp, steps, failure
    time): ``switch`` the local time [s] where the warped steps hand over to time.
    """
    n = y0.size
    switch, y, hit, hit_j, first = 0.0, y0.copy(), math.nan, -1, -1.0
    y_hit = y0.copy()
    if touch:
        f0 = np.empty(n)
        rhs(y, par, False, f0)
        first_in_s = initial_step(y, f0, rtol, atol, par, False) ** 0.25
        z0, z_tol = np.append(y, 0.0), np.append(atol, 1.0)
        status, s, z, last, hit_s, hit_j, warp = _run(
            0.0, z0, first_in_s, PIECE_LENGTH**0.25, rtol, z_tol, par, True, warp, keep
        )
        if status != STATUS_OK:
            return status, switch, hit, hit_j, y_hit, warp, steps, t0 + s**4
        switch, y, first = s**4, z[:n].copy(), s**4 - last[0] ** 4
        if hit_j >= 0:
            hit = t0 + hit_s**4
            z_hit = np.empty(n + 1)
            interpolate(last[3], last[2], (hit_s - last[0]) / last[1], z_hit)
            y_hit[:] = z_hit[:n]
    if hit_j < 0 and switch < PIECE_LENGTH:
        if first < 0.0:
            f0 = np.empty(n)
            rhs(y, par, False, f0)
            first = initial_step(y, f0, rtol, atol, par, False)
        status, t, _, last, hit, hit_j, steps = _run(
            t0 + switch, y, first, t0 + PIECE_LENGTH, rtol, atol, par, False, steps, keep
        )
        if status != STATUS_OK:
            return status, switch, hit, hit_j, y_hit, warp, steps, t
        if hit_j >= 0:
            interpolate(last[3], last[2], (hit - last[0]) / last[1], y_hit)
    return STATUS_OK, switch, hit, hit_j, y_hit, warp, steps, math.nan


@njit(cache=True, error_model="numpy")
def _cap(z, par, phase):
    """``phase mu max(N, 0)`` [N]: the sliding force at state ``z``."""
    return phase * par[FRICTION] * max(force(z[2] - z[0], z[3] - z[1], par), 0.0)


@njit(cache=True, error_model="numpy")
def _touch_phase(y0, rtol, atol, par):
    """Phase at a touch: the limit ``t -> 0+`` of LAMMPS' rule.

    The history starts at the touch and the force is capped only once the trial force
    exceeds ``mu N``. A trial force already above the cap at the touch itself (a damped
    spring's ``-eta s`` against a cap that starts at zero) slides. Otherwise the contact
    sticks unless the trial force along a sticking path from the touch's state exceeds the
    cap just after it: that path is followed for one short DOP853 step (:data:`PROBE` of
    the first step); the ratio of an elastic trial force to the cap is a power of time
    near the touch, so the probe's length does not matter. (Reading a damped spring at the
    probe instead chose sticking wherever the cap had outgrown ``eta s`` by then, and broke
    Coulomb before it: issue 21's matrix.) Returns the phase (0, +1 or -1) and the state
    it was read at (``y0`` or the probe's; Kratos' cap reads its kind of slide there,
    :mod:`contactlab.kernels.elastic_cap`).
    """
    s0 = slip(y0, par)
    if s0 == 0.0:
        return STICK, y0
    d0 = y0[2] - y0[0]
    tangential = trial_force(y0[6], d0, s0, par)
    if abs(tangential) > _cap(y0, par, 1.0):
        return (1 if tangential > 0.0 else -1), y0
    n = y0.size
    f0, y_new, f_new = np.empty(n), np.empty(n), np.empty(n)
    rhs(y0, par, False, f0)
    probe = PROBE * initial_step(y0, f0, rtol, atol, par, False)
    K = np.empty((WORK_ROWS, n))
    ok, _, _, _ = step(
        0.0, y0, f0, probe, probe, rtol, atol, par, False, K, y_new, f_new, ANY_MODEL
    )
    z = y_new if ok else y0
    tangential = trial_force(z[6], z[2] - z[0], slip(z, par), par)
    if abs(tangential) <= _cap(z, par, 1.0):
        return STICK, z
    return (1 if tangential > 0.0 else -1), z


@njit(cache=True, error_model="numpy")
def solve_contact(par, y0, rtol, atol, keep):
    """The contact from the touch (``y0``, zero overlap) to the separation.

    Parameters
    ----------
    par : numpy.ndarray
        Packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`); not modified.
    y0 : numpy.ndarray
        ``[x1, v1, x2, v2, vt, w, h]`` at the touch.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the seven states (:func:`tolerances`).
    keep : bool
        Whether to keep every step's interpolant (the single solver's output grid).

    Returns
    -------
    tuple
        ``(status, failure time [s], y_end, pieces, count, warp, steps)``: ``pieces``
        (MAX_PHASES, 8) rows ``(t0, t1, phase, switch, first warped step, end, first step
        in time, end)`` of which ``count`` are used; ``warp`` and ``steps`` the kept steps
        ``(count, t_old, h, y_old, F)`` in ``s`` (eight components) and in time.
    """
    par = par.copy()
    par[PHASE] = STICK
    n = y0.size
    capacity = _FIRST_CAPACITY if keep else 1
    warp, steps = _empty_store(n + 1, capacity), _empty_store(n, capacity)
    pieces = np.zeros((MAX_PHASES, 8))
    phase = _touch_phase(y0, rtol, atol, par)[0]
    t, y, touch = 0.0, y0.copy(), True
    for k in range(MAX_PHASES):
        par[PHASE] = phase
        w0, s0 = warp[0], steps[0]
        status, switch, hit, hit_j, y_hit, warp, steps, failed = _piece(
            t, y, touch, rtol, atol, par, warp, steps, keep
        )
        if status != STATUS_OK:
            return status, failed, y, pieces, k, warp, steps
        if hit_j < 0:
            return STATUS_OPEN, t + PIECE_LENGTH, y, pieces, k, warp, steps
        pieces[k, 0], pieces[k, 1], pieces[k, 2], pieces[k, 3] = t, hit, phase, switch
        pieces[k, 4], pieces[k, 5], pieces[k, 6], pieces[k, 7] = w0, warp[0], s0, steps[0]
        y, t, touch = y_hit, hit, False
        if hit_j == 0:
            return STATUS_OK, math.nan, y, pieces, k + 1, warp, steps
        if phase == STICK:
            phase = 1 if hit_j == 1 else -1
        else:
            y[6] = history_on_cap(_cap(y, par, phase), y[2] - y[0], slip(y, par), par)
            phase = STICK
    return STATUS_CHATTER, t, y, pieces, MAX_PHASES, warp, steps
