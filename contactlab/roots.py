"""Roots of event functions to machine precision, shared by the solver and the results.

The solver locates events (contact ends, branch changes, re-contacts) and the results
locate threshold crossings of the signals with the same rule: one crossing definition
(:func:`crosses`), one bracketed root finder (:func:`locate_root`), one tolerance.
"""

import math

import numpy as np
from scipy.optimize import brentq

__all__ = [
    "ROOT_RTOL",
    "SIDE_STEPS",
    "crossed_side",
    "crosses",
    "departure_root",
    "earliest_root",
    "has_happened",
    "is_past",
    "locate_root",
    "waits",
]

ROOT_RTOL = 4 * np.finfo(float).eps
"""Relative tolerance of event roots and crossings: the smallest brentq accepts."""

_ROOT_ITERATIONS = 1000
"""Iteration cap of :func:`locate_root`: Brent's method needs at most about the square of
the bisection count (here ~60**2) on functions that vanish like ``x**1.5`` at the root (a
Hertz force at zero overlap), where its interpolation steps are slow; 100, scipy's
default, is not always enough."""


def locate_root(fn, lo, hi):
    """Root of ``fn`` in the bracket [lo, hi] [s] to machine precision (brentq).

    Parameters
    ----------
    fn : callable
        Scalar function with a sign change (or a zero) on the bracket.
    lo, hi : float
        Bracket [s].

    Returns
    -------
    float
    """
    return brentq(fn, lo, hi, xtol=1e-300, rtol=ROOT_RTOL, maxiter=_ROOT_ITERATIONS)


def crosses(before, after, direction):
    """Whether an event function crossed zero between two values (floats or arrays).

    ``direction`` -1: from positive to non-positive; +1: from negative to non-negative. A
    value exactly 0 before never counts (the event that started the piece).
    """
    return (before > 0) & (after <= 0) if direction < 0 else (before < 0) & (after >= 0)


def waits(value, direction):
    """Whether an event function is strictly on its not-yet-happened side (floats or arrays):
    ``value > 0`` for a falling event (``direction < 0``), ``value < 0`` for a rising one."""
    return value > 0 if direction < 0 else value < 0


def has_happened(value, direction):
    """Whether an event function is on its crossed side: ``value <= 0`` falling,
    ``value >= 0`` rising (the complement of :func:`waits`)."""
    return value <= 0 if direction < 0 else value >= 0


def is_past(value, direction):
    """Whether an event function is strictly beyond zero on its crossed side: ``value < 0``
    falling, ``value > 0`` rising (an event that stays exactly at zero, such as the
    Coulomb limit of a contact without slip or friction, is not past)."""
    return value < 0 if direction < 0 else value > 0


DEPARTURE_SAMPLES = 60
"""Halvings of the bracket, towards its start, at which :func:`departure_root` looks for
the point where an event leaves zero (a touch at ``2**-60`` of the first step is below
any physical time scale)."""


def departure_root(fn, lo, hi, direction):
    """First crossing on [lo, hi] [s] of an event that starts the bracket at zero (or past).

    :func:`crosses` ignores a start value of exactly 0 (the event that started a piece).
    An event of the *new* piece may also start at 0 (the Coulomb limit at a touch, where
    the friction force and its cap both vanish) or a rounding past it (the limit a
    rescaled history was set to), and then cross in the first step. Such an event is
    armed where it first waits (:func:`waits`): the bracket is sampled at ``lo + (hi -
    lo) 2**-k`` (k = ``DEPARTURE_SAMPLES`` ... 1) and at sixteenths, in time order, and the
    root is located between the first waiting sample and the first happened sample after
    it (or ``hi``).

    Parameters
    ----------
    fn : callable
        Event function of time [s].
    lo, hi : float
        Bracket [s]; ``fn`` is past zero (:func:`is_past`) at ``hi`` or, for a contact's
        end, at a sample inside it.
    direction : int
        Crossing direction, as in :func:`crosses`.

    Returns
    -------
    float
        The crossing (on its crossed side, :func:`crossed_side`), or ``lo`` when the event
        never waits inside the bracket (it has happened at the start).
    """
    span = hi - lo
    times = sorted(
        {lo + span * 2.0**-k for k in range(1, DEPARTURE_SAMPLES + 1)}
        | {lo + span * j / 16.0 for j in range(1, 16)}
    )
    armed = None
    for t in times:
        if t <= lo:
            continue
        value = fn(t)
        if armed is None:
            if waits(value, direction):
                armed = t
        elif has_happened(value, direction):
            return crossed_side(fn, locate_root(fn, armed, t), hi, direction)
        else:
            armed = t
    if armed is None or not has_happened(fn(hi), direction):
        return lo  # it never waited, or waited only after it was past (a contact's end)
    return crossed_side(fn, locate_root(fn, armed, hi), hi, direction)


def earliest_root(events, value, lo, hi, directions):
    """Earliest root on the bracket [lo, hi] [s] among several event functions.

    Parameters
    ----------
    events : iterable of int
        Indices of the events that crossed zero on the bracket.
    value : callable
        ``value(t, j)``: event ``j`` at time ``t`` [s].
    lo, hi : float
        Bracket [s].
    directions : sequence of int
        Crossing direction of every event (indexed like ``value``), as in :func:`crosses`.

    Returns
    -------
    (float, int)
        Time of the earliest root [s] and its event: the root of :func:`locate_root`,
        moved to the first float at which the event has happened (:func:`crossed_side`).
    """
    found = []
    for j in events:
        fn = lambda t, j=j: value(t, j)  # noqa: E731
        found.append((crossed_side(fn, locate_root(fn, lo, hi), hi, directions[j]), int(j)))
    return min(found)


SIDE_STEPS = 64
"""Floats stepped over by :func:`crossed_side` before it takes the bracket's end (brentq's
root is within ``ROOT_RTOL``, a few floats, of the crossing)."""


def crossed_side(fn, t, hi, direction):
    """The first float from ``t`` on (at most ``hi``) where an event has happened.

    A root located to machine precision may sit just before the crossing (a contact force
    still 1e-17 N positive). The next piece starts from the state there, and its own
    events read it: a free flight that starts with a positive contact force sees no
    re-contact when the grain strikes again within one scan step (found by the batch
    solver's comparison). So events are taken on their crossed side: ``fn <= 0`` falling
    (``direction < 0``), ``fn >= 0`` rising.
    """
    for _ in range(SIDE_STEPS):
        if t >= hi:
            return hi
        v = fn(t)
        if (v <= 0.0) if direction < 0 else (v >= 0.0):
            return t
        t = math.nextafter(t, math.inf)
    return hi
