"""Adaptive contact pieces: DOP853 with event location on its dense output."""

import math

import numpy as np
from scipy.optimize import minimize_scalar

from contactlab.kernels import power_piece
from contactlab.kernels.power import pack
from contactlab.kernels.segments import DenseStates, DenseSteps, Segment, interpolate
from contactlab.roots import crossed_side, departure_root, is_past, locate_root, waits
from contactlab.solver.dop853 import Stepper
from contactlab.solver.system import event_directions

__all__ = ["adaptive_contact"]


def adaptive_contact(system, branch, t0, y0, tau_max, rtol, velocity):
    """Contact piece on any branch with DOP853; returns (Segment, y_end, event or None).

    The integrator (:class:`contactlab.solver.dop853.Stepper`: DOP853, order 8 with error
    control) is stepped directly; after each step the event functions (force falling to
    zero, the branch's exits) are checked at the step end and a sign change is located on
    the step's 7th-order interpolant to machine precision.

    A piece that starts with a touch (zero overlap, approaching) begins in the variable
    ``s = (t - t0)**(1/4)``: Hertz-family forces go with fractional powers of the overlap
    (``d**0.25 d'`` in damped Hertz), which are not smooth in ``t`` at the touch but are
    in ``s``, so the integrator needs a few steps there instead of a dozen shrinking
    ones. It returns to ``t`` once a step in ``s`` spans less time than has elapsed
    (:func:`_warp_stops_paying`).

    A branch whose force is a :class:`~contactlab.laws.base.PowerForm` (every
    Hertz-family law) runs the same method compiled (:func:`compiled_piece`).
    """
    force = branch.force
    directions = event_directions(branch)
    exits = [e.value for e in branch.exits]

    def event_values(y):
        x1, v1, x2, v2 = y[:4].tolist()
        d, r = x2 - x1, v2 - v1
        return [float(force(d, r))] + [value(d, r) for value in exits]

    atol = power_piece.contact_tolerances(rtol, velocity)
    y = np.asarray(y0, dtype=float)
    touch = y[2] - y[0] == 0.0 and y[3] - y[1] > 0.0
    if branch.power is not None and not branch.exits:
        start, steps, switch, hit = compiled_piece(
            system, branch.power, t0, y, tau_max, rtol, atol, touch
        )
    else:
        start, steps, switch, hit = integrate_piece(
            system.rhs(force),
            t0,
            y,
            tau_max,
            rtol,
            atol,
            event_values,
            directions,
            touch,
            retaken=range(len(directions)),
        )
    t_end = t0 + tau_max if hit is None else hit[0]
    event = None if hit is None else ("end" if hit[1] == 0 else branch.exits[hit[1] - 1].target)
    states = DenseStates(t0, steps, start, switch)
    seg = Segment(t0, t_end, "contact", branch.name, states)
    return seg, states(t_end - t0)[0], event


def integrate_piece(
    fun, t0, y0, tau_max, rtol, atol, event_values, directions, touch, retaken=(0,)
):
    """DOP853 from ``t0`` until an event or ``t0 + tau_max``, started in ``s = tau**(1/4)``
    at a touch (see :func:`adaptive_contact`), for branches with exits; the oblique
    solver runs the same rule compiled (:mod:`contactlab.kernels.oblique_kernel`).

    Parameters
    ----------
    fun : callable
        Autonomous right-hand side ``fun(y) -> ndarray``.
    t0, y0 : float, array_like
        Start [s] and state.
    tau_max : float
        Longest piece [s].
    rtol, atol : float, ndarray
        Tolerances (``atol`` per state component).
    event_values : callable
        ``event_values(y) -> list`` of event function values; ``y`` carries ``s`` as an
        extra last component during the warped start.
    directions : list of int
        Crossing direction of each event (:func:`contactlab.roots.crosses`).
    touch : bool
        Whether the piece starts at a touch (warped start).
    retaken : collection of int, default (0,)
        Events whose crossing step is taken again to just past the crossing
        (:func:`_run`): the contact's end (event 0) always; the normal solver adds its
        branch exits, so that the state handed to the next branch is a step's end, not a
        point of an interpolant (an exit inside the warped start's long steps, read on the
        interpolant, was 54 rtol off Thornton's closed form; 0.6 rtol retaken).

    Returns
    -------
    (DenseSteps or None, DenseSteps or None, float, tuple or None)
        The warped steps (in ``s``), the steps in time, the local time where the first
        hand over to the second [s], and the first event ``(time [s], index)`` or None.
    """
    start, switch, y, hit, first = None, 0.0, np.asarray(y0, dtype=float), None, None
    if touch:
        # first step in s: the s of the step an integrator in t would start with
        first_in_s = Stepper(fun, t0, y, rtol, atol).initial_step() ** 0.25
        z0, z_tol = np.append(y, 0.0), np.append(atol, 1.0)
        warped = Stepper(_warped(fun), 0.0, z0, rtol, z_tol, first_step=first_in_s, separate=True)
        start, hit = _run(
            warped, tau_max**0.25, event_values, directions, retaken, _warp_stops_paying
        )
        switch, y = warped.t**4, warped.y[:-1]
        first = switch - warped.t_old**4  # carry on with the last step's length in t
        if hit is not None:
            hit = (t0 + hit[0] ** 4, hit[1])
    steps = None
    if hit is None and switch < tau_max:
        stepper = Stepper(fun, t0 + switch, y, rtol, atol, first_step=first)
        steps, hit = _run(stepper, t0 + tau_max, event_values, directions, retaken)
    return start, steps, switch, hit


def compiled_piece(system, form, t0, y0, tau_max, rtol, atol, touch):
    """:func:`integrate_piece` for a :class:`~contactlab.laws.base.PowerForm` force, compiled
    (:func:`contactlab.kernels.power_piece.integrate`); same returns, the only event being
    the contact's end (index 0)."""
    par = pack(form, system.m1, system.k1, system.c1, system.m2, system.rigid)
    status, warp, steps, switch, hit = power_piece.integrate(
        par, t0, y0, tau_max, rtol, atol, touch
    )
    if status != power_piece.STATUS_OK:
        raise RuntimeError(underflow_message(hit, rtol))
    return (
        _dense(warp),
        _dense(steps),
        switch,
        None if np.isnan(hit) else (hit, 0),
    )


def underflow_message(t, rtol):
    """What failed when no step could meet the tolerance, and what to try."""
    return (
        f"adaptive integration failed at t = {t:.6g} s: the step size fell below 10 floats "
        f"of t before a step met rtol = {rtol:.3g}; the contact is not resolvable at this "
        "tolerance there (loosen rtol, or check the parameters for a contact far stiffer "
        "or longer than intended)"
    )


def _dense(steps):
    count, t_old, h, y_old, F = steps
    if count == 0:
        return None
    return DenseSteps(t_old[:count], h[:count], y_old[:count], F[:count])


def _warped(fun):
    """Right-hand side in ``s``, with ``t = t0 + s**4``, for ``z = (y, s)``:
    ``dy/ds = 4 s**3 f(y)`` and ``ds/ds = 1``."""

    def g(z):
        out = np.empty(z.size)
        out[:-1] = fun(z[:-1])
        out[:-1] *= 4.0 * z[-1] ** 3
        out[-1] = 1.0
        return out

    return g


def _warp_stops_paying(s_old, s_new):
    """Whether to leave ``s = t**(1/4)`` for ``t``: once a step spans less time than has
    elapsed since the touch, steps in ``t`` (which near the touch grow in proportion to
    the elapsed time) do as well, without the warp's factor ``4 s**3``."""
    return s_old > 0.0 and s_new**4 - s_old**4 < s_old**4


def _run(stepper, end, event_values, directions, retaken, stop=None):
    """Step until ``end``, an event, or ``stop(t_old, t_new)``; returns (DenseSteps, hit).

    ``hit`` is ``(time, index)`` of the first event crossing, or None. A step across the
    crossing of an event in ``retaken`` is taken again to just past the crossing located
    on it, as long as :func:`contactlab.kernels.power_piece.retake_bound` says so. For the
    contact's end (event 0) this is needed: the force formula is not smooth where it
    changes sign, and DOP853's error estimate misses that (the root cause is written
    there).
    """
    steps, hit, before = [], None, event_values(stepper.y)
    armed = [bool(waits(v, d)) for v, d in zip(before, directions, strict=True)]
    bound, count = end, 0
    while stepper.t < end:
        if not stepper.step(bound):
            raise RuntimeError(underflow_message(stepper.t, stepper.rtol))
        step = (stepper.t_old, stepper.t - stepper.t_old, stepper.y_old, stepper.interpolant())
        after = event_values(stepper.y)
        hit = _first_crossing(step, before, after, directions, event_values, armed)
        if hit is not None and hit[1] in retaken:
            again = power_piece.retake_bound(stepper.t_old, hit[0], stepper.t, count)
            if not math.isnan(again):
                stepper.undo()  # and again, to just past the crossing just located
                bound, count = again, count + 1
                continue
        steps.append(step)
        bound = end
        if hit is not None or (stop is not None and stop(stepper.t_old, stepper.t)):
            break
        armed = [a or bool(waits(v, d)) for a, v, d in zip(armed, after, directions, strict=True)]
        before = after
    return DenseSteps(*zip(*steps, strict=True)), hit


SUBSTEPS = 8
"""Intervals per step on whose ends the event functions are read (9 points with the step's
ends): an event that crosses zero and back inside one step (a trial force grazing the
Coulomb limit while the tangential spring oscillates, issue 21) is seen there, or, where
the samples have a maximum towards zero, by maximising the event on the step's
interpolant."""


def _first_crossing(step, before, after, directions, event_values, armed):
    """Earliest event crossing inside one step ``(t_old, h, y_old, F)``: (time, index) or
    None. At the step's end the events take their end values (``after``), so an event
    that lands exactly on zero there is found there.

    An armed event (``armed[j]``: it has waited, :func:`contactlab.roots.waits`, since
    the piece started) is read at :data:`SUBSTEPS` + 1 points of the step: the first sign
    change between two of them is located to machine precision; without one, a sampled
    maximum towards zero whose curvature could carry it across is maximised on the
    interpolant (:func:`_grazing_root`). An event that has not waited (it started the
    piece at zero, such as the Coulomb limit at a touch, or a rounding past it) and is
    strictly past zero at the step's end (:func:`contactlab.roots.is_past`) crossed inside
    the step after leaving zero: :func:`contactlab.roots.departure_root` locates it.
    """
    t_old, h, y_old, F = step
    fractions = np.linspace(0.0, 1.0, SUBSTEPS + 1)
    times = t_old + h * fractions
    times[-1] = t_old + h
    rows = [before, *(event_values(interpolate(F, y_old, x)) for x in fractions[1:-1]), after]
    known = dict(zip(times.tolist(), rows, strict=True))

    def value(t, j):
        row = known.get(t)
        if row is None:
            return event_values(interpolate(F, y_old, (t - t_old) / h))[j]
        return row[j]

    found = []
    for j, (direction, ready) in enumerate(zip(directions, armed, strict=True)):
        fn = lambda t, j=j: value(t, j)  # noqa: E731
        if not ready:
            past = [is_past(row[j], direction) for row in (rows[1:] if j == 0 else rows[-1:])]
            if any(past):  # the contact's end: at any sample (oblique_events._left_zero)
                found.append((departure_root(fn, t_old, t_old + h, direction), j))
            continue
        rising = np.array([direction * row[j] for row in rows])  # crosses from < 0 to >= 0
        change = np.flatnonzero((rising[:-1] < 0.0) & (rising[1:] >= 0.0))
        if change.size:
            lo, hi = times[change[0]], times[change[0] + 1]
            found.append((crossed_side(fn, locate_root(fn, lo, hi), hi, direction), j))
            continue
        root = _grazing_root(fn, times, rising, direction)
        if root is not None:
            found.append((root, j))
    return min(found) if found else None


def _grazing_root(fn, times, rising, direction):
    """Where an event that stays on its waiting side at every sample crosses between two
    of them, or None.

    ``rising`` holds the samples signed so that the crossing is from < 0 to >= 0. Around
    each sampled maximum (the step's ends included) whose second difference could lift it
    to zero, the event is maximised on the neighbouring samples' interval (bounded Brent,
    :func:`scipy.optimize.minimize_scalar`); a maximum that reaches zero brackets the
    crossing with the interval's start.
    """
    last = rising.size - 1
    for i in range(rising.size):
        left, right = max(i - 1, 0), min(i + 1, last)
        if rising[i] < rising[left] or rising[i] < rising[right]:
            continue
        a, b, c = (
            (rising[1], rising[0], rising[1])
            if i == 0
            else ((rising[-2], rising[-1], rising[-2]) if i == last else rising[i - 1 : i + 2])
        )
        if b + abs(a - 2.0 * b + c) < 0.0:
            continue
        lo, hi = times[left], times[right]
        best = minimize_scalar(
            lambda t: -direction * fn(t),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": GRAZE_XTOL * (hi - lo)},
        )
        peak = float(best.x)
        if direction * fn(peak) >= 0.0:
            return crossed_side(fn, locate_root(fn, lo, peak), peak, direction)
    return None


GRAZE_XTOL = 1e-10
"""Relative tolerance [-] of the maximum's time in :func:`_grazing_root`."""
