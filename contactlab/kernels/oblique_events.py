"""Compiled event location inside one DOP853 step of the oblique impact.

The rule of issue 21 (docs/verification.md, findings 1-8), compiled: an *armed* event
(one that has waited, :func:`contactlab.roots.waits`, since its piece started) is read at
:data:`SUBSTEPS` + 1 points of the step; the first sign change between two of them is
located by Brent's method (:mod:`contactlab.kernels.brent`, ``brentq``'s tolerance) and
taken on its crossed side (:func:`contactlab.roots.crossed_side`); without one, a sampled
maximum towards zero whose curvature could carry it across is maximised on the step's
interpolant (:func:`_maximise`, scipy's bounded Brent minimiser) and a maximum that
reaches zero brackets the crossing. An event that has not waited and is strictly past zero
at the step's end (:func:`contactlab.roots.is_past`) left zero inside the step: it is
found as :func:`contactlab.roots.departure_root` finds it.

Event values at a time inside a step come from the step's interpolant, at its end from
the end state (``after``), so an event that lands exactly on zero there is found there.
The events are the model's (:func:`contactlab.kernels.model_rhs.events`): the normal
contact's compiled pieces (:mod:`contactlab.kernels.power_piece`) locate their one event,
the contact's end, here too.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.brent import brent_next, brent_start
from contactlab.kernels.dop853 import interpolate
from contactlab.kernels.model_rhs import events
from contactlab.kernels.oblique_rhs import direction
from contactlab.roots import DEPARTURE_SAMPLES, SIDE_STEPS

__all__ = ["GRAZE_XTOL", "SUBSTEPS", "first_crossing", "sample", "waits"]

SUBSTEPS = 8
"""Intervals per step on whose ends the event functions are read (9 points with the step's
ends): an event that crosses zero and back inside one step (a trial force grazing the
Coulomb limit while the tangential spring oscillates, issue 21) is seen there, or, where
the samples have a maximum towards zero, by maximising the event on the interpolant."""

GRAZE_XTOL = 1e-10
"""Relative tolerance [-] of the maximum's time in :func:`_maximise`."""

_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))
_SQRT_EPS = math.sqrt(2.2e-16)
_MAX_EVALUATIONS = 500
_DEPARTURE_TIMES = np.unique(
    np.concatenate((2.0 ** -np.arange(1.0, DEPARTURE_SAMPLES + 1.0), np.arange(1.0, 16.0) / 16.0))
)
"""Fractions of a step at which :func:`_departure` reads an event, in increasing order."""


@njit(cache=True, error_model="numpy")
def waits(value, sense):
    """:func:`contactlab.roots.waits` for a float and a direction ``sense``."""
    return value > 0.0 if sense < 0 else value < 0.0


@njit(cache=True, error_model="numpy")
def _happened(value, sense):
    return value <= 0.0 if sense < 0 else value >= 0.0


@njit(cache=True, error_model="numpy")
def sample(t_old, h, y_old, F, y_new, par, phase, times, rows, tmp):
    """The event values of a step ``(t_old, h, y_old, F)`` ending at ``y_new`` at its
    :data:`SUBSTEPS` + 1 sample times: ``times`` [s] and ``rows`` (their last row, the
    previous step's end, moves to the first); returns how many events the phase has."""
    rows[0] = rows[SUBSTEPS]
    for i in range(SUBSTEPS):
        times[i] = t_old + h * (i / SUBSTEPS)
    for i in range(1, SUBSTEPS):
        interpolate(F, y_old, i / SUBSTEPS, tmp)
        events(tmp, par, phase, rows[i])
    times[SUBSTEPS] = t_old + h
    return events(y_new, par, phase, rows[SUBSTEPS])


@njit(cache=True, error_model="numpy")
def _value(t, j, step, times, rows, par, phase, tmp, row):
    """Event ``j`` at time ``t`` inside the step ``(t_old, h, y_old, F)``: the sampled
    value where ``t`` is one of the samples ``times`` (the end state's at the end)."""
    for i in range(times.size):
        if t == times[i]:
            return rows[i, j]
    t_old, h, y_old, F = step
    interpolate(F, y_old, (t - t_old) / h, tmp)
    events(tmp, par, phase, row)
    return row[j]


@njit(cache=True, error_model="numpy")
def _root(lo, f_lo, hi, f_hi, j, step, times, rows, par, phase, tmp, row, work):
    """Root of event ``j`` on ``[lo, hi]`` (Brent, :func:`contactlab.roots.locate_root`)
    moved to its crossed side (:func:`contactlab.roots.crossed_side`) before ``hi``."""
    x, done = brent_start(work, lo, f_lo, hi, f_hi)
    while not done:
        x, done = brent_next(work, _value(x, j, step, times, rows, par, phase, tmp, row))
    sense = direction(j, int(phase))
    t = x
    for _ in range(SIDE_STEPS):
        if t >= hi:
            return hi
        if _happened(_value(t, j, step, times, rows, par, phase, tmp, row), sense):
            return t
        t = np.nextafter(t, math.inf)
    return hi


@njit(cache=True, error_model="numpy")
def _departure(j, step, times, rows, par, phase, tmp, row, work):
    """:func:`contactlab.roots.departure_root` on the step, for event ``j``."""
    t_old, h = step[0], step[1]
    sense = direction(j, int(phase))
    hi = times[-1]
    armed, f_armed = math.nan, 0.0
    for fraction in _DEPARTURE_TIMES:
        t = t_old + h * fraction
        if t <= t_old:
            continue
        value = _value(t, j, step, times, rows, par, phase, tmp, row)
        if math.isnan(armed):
            if waits(value, sense):
                armed, f_armed = t, value
        elif _happened(value, sense):
            return _root(armed, f_armed, t, value, j, step, times, rows, par, phase, tmp, row, work)
        else:
            armed, f_armed = t, value
    f_hi = rows[-1, j]
    if math.isnan(armed) or not _happened(f_hi, sense):
        return t_old  # it never waited, or waited only after it was past (the contact end)
    return _root(armed, f_armed, hi, f_hi, j, step, times, rows, par, phase, tmp, row, work)


@njit(cache=True, error_model="numpy")
def _left_zero(j, sense, rows):
    """Whether event ``j``, which has not waited, is strictly past zero at the step's end,
    or, for the contact's end (``j = 0``), at any sample: a phase that starts where the
    normal force is zero (a stick ending with it) and a plate's ringing that brings it
    back inside the step (docs/verification.md, finding 12)."""
    first = 1 if j == 0 else rows.shape[0] - 1
    for i in range(first, rows.shape[0]):
        if (rows[i, j] < 0.0) if sense < 0 else (rows[i, j] > 0.0):
            return True
    return False


@njit(cache=True, error_model="numpy")
def _maximise(sense, lo, hi, j, step, times, rows, par, phase, tmp, row):
    """Time of the largest ``sense * event j`` on ``[lo, hi]``: scipy's
    ``minimize_scalar(method="bounded")`` (Brent's golden section with parabolic steps),
    ported step for step, with ``xatol = GRAZE_XTOL (hi - lo)``."""
    xatol = GRAZE_XTOL * (hi - lo)
    a, b = lo, hi
    fulc = a + _GOLDEN * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = -sense * _value(x, j, step, times, rows, par, phase, tmp, row)
    num = 1
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = True
        if abs(e) > tol1:
            golden = False
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):
                rat = (p + 0.0) / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    rat = tol1 * (1.0 if xm - xf >= 0.0 else -1.0)
            else:
                golden = True
        if golden:
            e = (a - xf) if xf >= xm else (b - xf)
            rat = _GOLDEN * e
        x = xf + (1.0 if rat >= 0.0 else -1.0) * max(abs(rat), tol1)
        fu = -sense * _value(x, j, step, times, rows, par, phase, tmp, row)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = _SQRT_EPS * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= _MAX_EVALUATIONS:
            break
    return xf


@njit(cache=True, error_model="numpy")
def _grazing(j, rising, step, times, rows, par, phase, tmp, row, work):
    """Where event ``j``, on its waiting side at every sample (``rising``: the samples
    signed to cross from < 0 to >= 0), crosses between two of them; nan if it does not.
    See ``contactlab.solver.adaptive._grazing_root``."""
    sense = direction(j, int(phase))
    last = rising.size - 1
    for i in range(rising.size):
        left, right = max(i - 1, 0), min(i + 1, last)
        if rising[i] < rising[left] or rising[i] < rising[right]:
            continue
        if i == 0:
            a, b, c = rising[1], rising[0], rising[1]
        elif i == last:
            a, b, c = rising[last - 1], rising[last], rising[last - 1]
        else:
            a, b, c = rising[i - 1], rising[i], rising[i + 1]
        if b + abs(a - 2.0 * b + c) < 0.0:
            continue
        lo, hi = times[left], times[right]
        peak = _maximise(sense, lo, hi, j, step, times, rows, par, phase, tmp, row)
        f_peak = _value(peak, j, step, times, rows, par, phase, tmp, row)
        if sense * f_peak >= 0.0:
            f_lo = rows[left, j]
            return _root(lo, f_lo, peak, f_peak, j, step, times, rows, par, phase, tmp, row, work)
    return math.nan


@njit(cache=True, error_model="numpy")
def first_crossing(step, count, armed, times, rows, par, phase, tmp, row, work, rising):
    """Earliest event crossing inside one step: ``(time, index)``, index -1 if none.

    Parameters
    ----------
    step : tuple
        ``(t_old, h, y_old, F)``: the step's start [s], length [s], start state and
        interpolant coefficients.
    count : int
        Number of events of the phase.
    armed : numpy.ndarray
        Whether each event has waited since the piece started (bool).
    times : numpy.ndarray
        The :data:`SUBSTEPS` + 1 sample times [s], the step's ends included.
    rows : numpy.ndarray
        Event values at ``times`` (SUBSTEPS + 1, count or more).
    par : numpy.ndarray
        Packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`).
    phase : float
        Phase of the piece.
    tmp, row, work, rising : numpy.ndarray
        Scratch: a state, an event row, Brent's work array
        (:data:`contactlab.kernels.brent.WORK_SIZE`) and :data:`SUBSTEPS` + 1 floats.
    """
    best, best_j = math.inf, -1
    last = times.size - 1
    for j in range(count):
        sense = direction(j, int(phase))
        root = math.nan
        if not armed[j]:
            if _left_zero(j, sense, rows[: last + 1]):
                root = _departure(j, step, times, rows, par, phase, tmp, row, work)
        else:
            for i in range(last + 1):
                rising[i] = sense * rows[i, j]
            change = -1
            for i in range(last):
                if rising[i] < 0.0 and rising[i + 1] >= 0.0:
                    change = i
                    break
            if change >= 0:
                lo, hi = times[change], times[change + 1]
                f_lo, f_hi = rows[change, j], rows[change + 1, j]
                root = _root(lo, f_lo, hi, f_hi, j, step, times, rows, par, phase, tmp, row, work)
            else:
                root = _grazing(j, rising, step, times, rows, par, phase, tmp, row, work)
        if not math.isnan(root) and root < best:
            best, best_j = root, j
    return best, best_j
