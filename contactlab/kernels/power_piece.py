"""A compiled contact piece under a power-law contact: DOP853 with event location.

:func:`integrate` is :func:`contactlab.solver.adaptive.integrate_piece` compiled for the
laws of :class:`contactlab.laws.base.PowerForm` (every Hertz-family law): the same
stepper (:mod:`contactlab.kernels.dop853`), the same start in
``s = tau**(1/4)`` at a touch and hand-over to time, the same event (the contact force
falling through zero, sought at nine points of each step and between them, located by
Brent's method on the step's interpolant to the solver's tolerance and taken on its
crossed side, :func:`contactlab.roots.crossed_side`: the oblique solver's rule,
:mod:`contactlab.kernels.oblique_events`).
It serves :func:`~contactlab.solver.adaptive.adaptive_contact` (one impact) and the
batch kernel (:mod:`contactlab.kernels.hertz_impact`, thousands of impacts).
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.brent import WORK_SIZE
from contactlab.kernels.dop853 import WORK_ROWS, initial_step, interpolant, step
from contactlab.kernels.model_rhs import NORMAL, events
from contactlab.kernels.oblique_events import SUBSTEPS, first_crossing, sample, waits
from contactlab.kernels.power import force_floor, rhs

__all__ = [
    "MAX_RETAKES",
    "RETAKE_FLOATS",
    "RETAKE_SHARE",
    "STATUS_OK",
    "STATUS_UNDERFLOW",
    "contact_tolerances",
    "integrate",
    "retake_bound",
]

STATUS_OK, STATUS_UNDERFLOW = 0, 1
"""Outcome of :func:`integrate`: done, or the step size underflowed."""

_DENSE = 7  # interpolant coefficient rows
_FIRST_CAPACITY = 256
"""Steps a contact piece's arrays hold before they grow (doubling, with a copy of every
step so far): a damped-Hertz contact of the batch benchmark takes 127-133 steps, so 64
grew, and copied, on nearly every row."""


@njit(cache=True, error_model="numpy")
def contact_tolerances(rtol, velocity):
    """Absolute tolerances of a contact piece's ``[x1, v1, x2, v2]``.

    ``1e-3 rtol`` of one microsecond of travel at the impact speed [m] for the
    displacements, of the impact speed [m/s] for the velocities: the adaptive solver's
    and the batch kernel's choice alike.
    """
    scale = velocity * 1e-6
    return 1e-3 * rtol * np.array([scale, velocity, scale, velocity])


MAX_RETAKES = 8
"""Most retakes of the step that ends one contact piece (:func:`retake_bound`); one or
two are usual."""

RETAKE_FLOATS = 128
"""A contact's end closer than this many floats to its step's start is read on that step
(:func:`retake_bound`): the interpolant is exact to first order at the step's start, so
its error there is below ``(128 ulp / h)**2`` of the step's; and a shorter step would not
give its 9 event samples (:data:`contactlab.solver.adaptive.SUBSTEPS`) distinct times."""

RETAKE_SHARE = 2.0**-20
"""Share of a step past the contact's end [-] up to which the step stands
(:func:`retake_bound`). A retaken step is bounded half of it past the end located, so
that it crosses the end by a margin no rounding removes and locates the end itself (a
bound at the end would leave the event a rounding short of zero about half the time, and
one more step); what the non-smooth force does in a millionth of a step past the end is
below rounding (the error of a step across it falls like a power above 3 of that part)."""


@njit(cache=True)
def retake_bound(t_old, end, t_new, count):
    """Where a step from ``t_old`` to ``t_new`` [s] across the contact's end, located at
    ``end`` [s] on it, is taken again to from ``t_old`` [s], or nan where it stands
    (``count`` retakes so far).

    The root cause of Thornton's wrong rebounds (issue 21; 1e-5 off the closed form): the
    force of a Hertz-family branch, ``k (d - d_p)**1.5``, is continued past the contact's
    end as ``k x |x|**0.5`` (``x = d - d_p``; its sign change marks the end), which is
    not smooth at ``x = 0`` (the overlap's fourth derivative grows like ``|x|**-0.5``).
    DOP853's error estimate assumes a smooth solution over the step: on a step across
    that point its 5th-order estimate, damped by a far larger 3rd-order one (``err5**2 /
    sqrt(err5**2 + 0.01 err3**2)``), accepted steps whose end state, and the interpolant
    the end was located on, were off by 1e5 times the tolerance. Such a step is taken
    again, bounded just past the end located on it, until no more than
    :data:`RETAKE_SHARE` of the step lies past the end, the end lies within
    :data:`RETAKE_FLOATS` of the step's start, or :data:`MAX_RETAKES` is reached: the state
    at the contact's end then comes from a step that does not cross the non-smooth point
    (to a millionth of the step). A branch exit needs no retake for the step to hold (the
    formula is smooth across it); the normal solver retakes those steps too, so that the
    next branch starts from a step's end (:func:`contactlab.solver.adaptive.integrate_piece`).
    """
    ulp = np.nextafter(t_old, math.inf) - t_old
    if (
        count >= MAX_RETAKES
        or end <= t_old + RETAKE_FLOATS * ulp
        or t_new - end <= RETAKE_SHARE * (t_new - t_old)
    ):
        return math.nan
    return end + 0.5 * RETAKE_SHARE * (end - t_old)


@njit(cache=True, error_model="numpy")
def _grow(t_old, h, y_old, F):
    size = 2 * t_old.size
    t2, h2 = np.empty(size), np.empty(size)
    y2, F2 = np.empty((size, y_old.shape[1])), np.empty((size, _DENSE, y_old.shape[1]))
    t2[: t_old.size], h2[: h.size] = t_old, h
    y2[: y_old.shape[0]], F2[: F.shape[0]] = y_old, F
    return t2, h2, y2, F2


@njit(cache=True, error_model="numpy", inline="always")
def _span(F, y_old, i, j):
    """Bounds ``(lo, hi)`` of ``z[j] - z[i]`` on a step's interpolant (``y_old``, ``F``).

    The interpolant is ``y_old + x F0 + x (1 - x) P(x)``, ``P = F1 + x (F2 + (1 - x) (F3
    + ...))`` (Horner in ``x`` and ``1 - x``, :func:`contactlab.kernels.dop853.interpolate`):
    interval arithmetic from the innermost coefficient, each factor ``x`` or ``1 - x`` in
    ``[0, 1]``, bounds ``P``, and ``x (1 - x)`` lies in ``[0, 1/4]``; the chord ``y_old +
    x F0`` lies between the step's ends.
    """
    last = F.shape[0] - 1
    lo = hi = F[last, j] - F[last, i]
    for k in range(last - 1, 0, -1):
        c = F[k, j] - F[k, i]
        lo, hi = c + min(lo, 0.0), c + max(hi, 0.0)
    start = y_old[j] - y_old[i]
    end = start + (F[0, j] - F[0, i])
    return min(start, end) + 0.25 * min(lo, 0.0), max(start, end) + 0.25 * max(hi, 0.0)


@njit(cache=True, error_model="numpy", inline="always")
def _pressed(F, y_old, par):
    """Whether the contact force is bounded above zero on the whole step's interpolant
    (overlap and rate from :func:`_span`, the force from
    :func:`contactlab.kernels.power.force_floor`), by more than ``1e-9`` of its size (the
    interpolant's rounding is ~1e-16 of it): no sample of the step could then find the
    contact's end, and :func:`_run` skips them."""
    d_lo, d_hi = _span(F, y_old, 0, 2)
    r_lo, r_hi = _span(F, y_old, 1, 3)
    floor, size = force_floor(d_lo, d_hi, r_lo, r_hi, par)
    return floor > 1e-9 * size


@njit(cache=True, error_model="numpy")
def _run(t, y, h_try, end, rtol, atol, par, warped):
    """Steps from ``(t, y)`` until ``end``, the event, or (warped) the hand-over.

    The contact's end is looked for at :data:`~contactlab.kernels.oblique_events.SUBSTEPS`
    + 1 points of every step and between them
    (:func:`contactlab.kernels.oblique_events.first_crossing`), not at the step's ends
    only: a sensor plate's ringing can bring the force to zero and back inside one step
    (docs/verification.md, finding 12). A step whose interpolant keeps the force bounded
    above zero (:func:`_pressed`) is not sampled: the search would find nothing there.

    Returns (status, n_steps, t_old, h, y_old, F, hit, t, y, t_old_last): ``hit`` is the
    event time (nan if none); ``t, y`` the last step's end; ``t_old_last`` its start.
    """
    n = y.size
    t_old, hs = np.empty(_FIRST_CAPACITY), np.empty(_FIRST_CAPACITY)
    y_old, F = np.empty((_FIRST_CAPACITY, n)), np.empty((_FIRST_CAPACITY, _DENSE, n))
    K, f, y_new, f_new = np.empty((WORK_ROWS, n)), np.empty(n), np.empty(n), np.empty(n)
    tmp, row, work, rising = np.empty(n), np.empty(1), np.empty(WORK_SIZE), np.empty(SUBSTEPS + 1)
    times, rows = np.empty(SUBSTEPS + 1), np.empty((SUBSTEPS + 1, 1))
    rhs(y, par, warped, f)
    y = y.copy()
    events(y, par, 0.0, rows[SUBSTEPS])
    armed = np.array([waits(rows[SUBSTEPS, 0], -1)])
    hit, count, last_start = math.nan, 0, t
    bound, retaken = end, 0
    while t < end:
        ok, t_new, h_next, h = step(
            t, y, f, h_try, bound, rtol, atol, par, warped, K, y_new, f_new, NORMAL
        )
        if not ok:
            return STATUS_UNDERFLOW, count, t_old, hs, y_old, F, hit, t, y, last_start
        if count == t_old.size:
            t_old, hs, y_old, F = _grow(t_old, hs, y_old, F)
        dense = F[count]
        interpolant(K, h, y, y_new, f_new, par, warped, dense, NORMAL)
        if _pressed(dense, y, par):
            rows[0, 0] = rows[SUBSTEPS, 0]
            events(y_new, par, 0.0, rows[SUBSTEPS])
            hit = math.nan
        else:
            sample(t, h, y, dense, y_new, par, 0.0, times, rows, tmp)
            hit, index = first_crossing(
                (t, h, y, dense), 1, armed, times, rows, par, 0.0, tmp, row, work, rising
            )
            hit = math.nan if index < 0 else hit
        if not math.isnan(hit):
            again = retake_bound(t, hit, t_new, retaken)
            if not math.isnan(again):  # the step again from t, to just past the end
                rows[SUBSTEPS, 0] = rows[0, 0]
                h_try, bound, retaken, hit = h_next, again, retaken + 1, math.nan
                continue
        t_old[count], hs[count] = t, h
        for c in range(n):  # element copies: a slice copy checks overlap and may allocate
            y_old[count, c] = y[c]
            y[c], f[c] = y_new[c], f_new[c]
        last_start = t
        count += 1
        t, h_try, bound = t_new, h_next, end
        if not math.isnan(hit):
            break
        if warped and last_start > 0.0 and t**4 - last_start**4 < last_start**4:
            break  # adaptive._warp_stops_paying: steps in time do as well from here
        armed[0] = armed[0] or waits(rows[SUBSTEPS, 0], -1)
    return STATUS_OK, count, t_old, hs, y_old, F, hit, t, y, last_start


@njit(cache=True, error_model="numpy")
def integrate(par, t0, y0, tau_max, rtol, atol, touch):
    """A contact piece from ``(t0, y0)`` until the force falls to zero or ``t0 + tau_max``.

    Parameters
    ----------
    par : numpy.ndarray
        Packed law and system (:func:`contactlab.kernels.power.pack`).
    t0 : float
        Start [s].
    y0 : numpy.ndarray
        State ``[x1, v1, x2, v2]`` at the start.
    tau_max : float
        Longest piece [s].
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the four states.
    touch : bool
        Whether the piece starts at a touch (warped start in ``s = tau**(1/4)``).

    Returns
    -------
    tuple
        ``(status, warped steps, steps, switch, hit)``: each ``steps`` is
        ``(count, t_old, h, y_old, F)`` (warped ones in ``s`` with five components,
        count 0 if none); ``switch`` the local time [s] where the warped steps hand over;
        ``hit`` the event time [s] (nan if the piece reached ``t0 + tau_max``), or, with
        ``STATUS_UNDERFLOW``, the time [s] at which the step size underflowed.
    """
    n = y0.size
    empty_w = (0, np.empty(0), np.empty(0), np.empty((0, n + 1)), np.empty((0, _DENSE, n + 1)))
    empty_t = (0, np.empty(0), np.empty(0), np.empty((0, n)), np.empty((0, _DENSE, n)))
    warp, switch, y, hit, first = empty_w, 0.0, y0.copy(), math.nan, -1.0
    if touch:
        f0 = np.empty(n)
        rhs(y, par, False, f0)
        first_in_s = initial_step(y, f0, rtol, atol, par, False) ** 0.25
        z0, z_tol = np.append(y, 0.0), np.append(atol, 1.0)
        status, count, t_o, hs, y_o, F, hit_s, s, z, s_old = _run(
            0.0, z0, first_in_s, tau_max**0.25, rtol, z_tol, par, True
        )
        if status != STATUS_OK:
            return status, warp, empty_t, switch, t0 + s**4
        warp = (count, t_o, hs, y_o, F)
        switch, y = s**4, z[:n].copy()
        first = switch - s_old**4
        if not math.isnan(hit_s):
            hit = t0 + hit_s**4
    steps = empty_t
    if math.isnan(hit) and switch < tau_max:
        t_start = t0 + switch
        if first < 0.0:
            f0 = np.empty(n)
            rhs(y, par, False, f0)
            first = initial_step(y, f0, rtol, atol, par, False)
        status, count, t_o, hs, y_o, F, hit, t_stop, _, _ = _run(
            t_start, y, first, t0 + tau_max, rtol, atol, par, False
        )
        if status != STATUS_OK:
            return status, warp, empty_t, switch, t_stop
        steps = (count, t_o, hs, y_o, F)
    return STATUS_OK, warp, steps, switch, hit
