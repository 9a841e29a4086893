"""The compiled event loop of a normal impact: contact and free pieces until the window ends.

One loop serves :func:`contactlab.simulate_impact` (which asks it for the pieces, to
give the solution on its output grid) and the batch solvers of :mod:`contactlab.batch`
(the same loop on every row, without the pieces): contact pieces of a linear law in
modal form (:func:`contactlab.kernels.linear_impact.linear_contact`) or of a power law
by DOP853 (:func:`contactlab.kernels.hertz_impact.power_contact`), free flights exactly
(:func:`contactlab.kernels.modal.free_flight`), the window and contact cap of
:mod:`contactlab.kernels.rules`. The headline numbers are read as the pieces are solved
(:data:`RESULTS`), as :class:`contactlab.ImpactResult` defines them with threshold 0:
the sensor signal's first lobe from the touch to its first return to zero, the peaks
over the first contact and over that lobe, the impulse of every contact (the grain's
momentum change over it, the only force on the grain being the contact's), the
restitution after the last contact.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.brent import WORK_SIZE
from contactlab.kernels.hertz_impact import power_contact, power_setup
from contactlab.kernels.linear_impact import contact_modes, linear_contact
from contactlab.kernels.modal import (
    C1,
    C2,
    COND_LIMIT,
    CONTACT_PEAK,
    CONTACT_PEAK_TIME,
    IN_CONTACT,
    K1,
    LOBE_END,
    M1,
    M2,
    PIECE_START,
    READINGS,
    RIGID,
    SENSOR,
    SENSOR_PEAK,
    SENSOR_PEAK_TIME,
    STATUS_FALLBACK,
    STATUS_OK,
    STATUS_TOO_FAST,
    TOO_FAST,
    conjugates_once,
    fastest,
    free_flight,
    quadratic_modes,
    raise_peak,
    row_parameters,
    signal,
)
from contactlab.kernels.rules import (
    MAX_CONTACTS,
    MAX_SCAN_POINTS,
    contact_horizon,
    ringing_time,
    window_end,
)

__all__ = [
    "PIECE_CAPACITY",
    "PIECE_FIELDS",
    "RESULTS",
    "RESULT_FIELDS",
    "solve_impact",
    "solve_rows",
]

RESULT_FIELDS = (
    "contact_time",
    "response_time",
    "peak_contact_force",
    "peak_sensor_force",
    "restitution",
    "contacts",
    "peak_contact_time",
    "peak_sensor_time",
    "impulse",
    "window",
    "pieces",
    "rebound_velocity",
    "end",
)
"""What :func:`solve_impact` writes, in order: first contact's duration [s], the sensor
lobe's duration [s] (nan if it does not end in the window), the peak contact force [N]
and sensor signal [N], the restitution [-], the contacts [-] (the batch's six columns,
:data:`contactlab.batch.rows.RESULT_COLUMNS`), then the times [s] of the two peaks, the
impulse of the contacts [N*s], the window's end [s], the pieces recorded, the rebound
speed [m/s] and the time [s] where the loop stopped (the window's end, or the end of a
contact that outlasted it)."""

RESULTS = len(RESULT_FIELDS)
CONTACT_TIME, RESPONSE_TIME, PEAK_CONTACT, PEAK_SENSOR, RESTITUTION, CONTACTS = range(6)
PEAK_CONTACT_AT, PEAK_SENSOR_AT, IMPULSE, WINDOW, PIECES, REBOUND, END = range(6, RESULTS)

PIECE_FIELDS = ("t0", "contact", "horizon", "x1", "v1", "x2", "v2")
"""A recorded piece: its start [s], 1 for a contact (0 free), how far it was followed at
most [s], the state at its start."""

PIECE_CAPACITY = 2 * MAX_CONTACTS + 2
"""Rows of the piece record that one impact can fill (a contact and a free flight per
contact, and the last piece)."""


@njit(cache=True, error_model="numpy", inline="always")
def _record(pieces, n, t, contact, horizon, y):
    """Write piece ``n`` (if ``pieces`` has room: the batch passes none); returns n + 1."""
    if n < pieces.shape[0]:
        pieces[n, 0], pieces[n, 1], pieces[n, 2] = t, contact, horizon
        pieces[n, 3:] = y
    return n + 1


@njit(cache=True, error_model="numpy")
def _free_modes(par):
    """Modes of the free sensor ``(lam, vec, inv, nm, rate)`` (none on a wall) and their
    condition bound."""
    lam, vec = np.zeros(2, np.complex128), np.zeros((4, 2), np.complex128)
    inv = np.zeros((2, 4), np.complex128)
    nm, cond = 0, 0.0
    if par[RIGID] == 0.0:
        nm = 2
        cond = quadratic_modes(par[M1], par[C1], par[K1], 0, lam, vec, inv)
    rate = fastest(lam, nm)
    nm = conjugates_once(lam, vec, inv, nm)
    return (lam, vec, inv, nm, rate), cond


@njit(cache=True, error_model="numpy")
def solve_impact(par, linear, v0, rtol, window, out, pieces):
    """Solve one impact; write :data:`RESULTS` into ``out``; return the status.

    Parameters
    ----------
    par : numpy.ndarray
        Row parameters (:func:`contactlab.kernels.modal.row_parameters`), changed while
        solving (its ``IN_CONTACT`` field).
    linear : bool
        Whether the law is linear (``k2 d + c2 d'``: modal contact pieces) or a power law
        (DOP853 at ``rtol``).
    v0 : float
        Impact speed [m/s].
    rtol : float
        Relative tolerance of the power-law pieces (unused for a linear law).
    window : float
        Window [s]; nan for the default (:func:`contactlab.kernels.rules.window_end`
        after every contact).
    out : numpy.ndarray
        :data:`RESULTS` floats, written.
    pieces : numpy.ndarray
        (:data:`PIECE_CAPACITY`, 7) to record the pieces into (:data:`PIECE_FIELDS`), or
        (0, 7) to record none.

    Returns
    -------
    int
        :data:`~contactlab.kernels.modal.STATUS_OK`, or
        :data:`~contactlab.kernels.modal.STATUS_FALLBACK` for an impact this loop does
        not take (modes too close to defective, a first contact that does not end,
        :data:`~contactlab.kernels.rules.MAX_CONTACTS` contacts, a step size that
        underflows, no rise of the sensor signal in the first contact), or
        :data:`~contactlab.kernels.modal.STATUS_TOO_FAST` (modes too fast for an event
        scan of ``par[SCAN_CAP]`` points).
    """
    rigid = par[RIGID] > 0.0
    free_modes, cond = _free_modes(par)
    # a power law's pieces take no modes: the free sensor's stand in, not computed again
    modes, contact_cond = contact_modes(par) if linear else (free_modes, cond)
    if not max(cond, contact_cond if linear else 0.0) < COND_LIMIT:
        return STATUS_FALLBACK
    setup = power_setup(par, v0, rtol)
    ringing = ringing_time(par[M1], par[K1], rigid)
    y, work = np.array([0.0, 0.0, 0.0, v0]), np.zeros(WORK_SIZE)
    # [0] the sensor lobe is open, [1] the contact force's peak is wanted, [2] the signal
    # has not yet risen above the power-law pieces' noise floor (then the lobe opens)
    track = np.array([linear and not rigid, True, not linear and not rigid])
    best = np.zeros(READINGS)
    best[LOBE_END] = math.nan
    if linear:  # a damper's force jumps to c2 v0 at the touch
        best[CONTACT_PEAK] = max(par[C2] * v0, 0.0)
    auto = math.isnan(window)
    limit = math.inf if auto else max(window, 0.0)
    t, contacts, contact_time, rebound, impulse, n = 0.0, 0, math.nan, math.nan, 0.0, 0
    while True:
        par[IN_CONTACT] = 1.0
        if track[0]:  # a piece's start is a candidate for the sensor's peak
            raise_peak(best, SENSOR_PEAK, signal(SENSOR, y, par), t)
        horizon = (contact_horizon(limit) if contacts == 0 else limit) - t
        n = _record(pieces, n, t, 1.0, horizon, y)
        v_in = y[3]
        if linear:
            end = linear_contact(modes, par, t, y, horizon, track, best, work)
        else:
            end = power_contact(setup, par, t, y, horizon, track, best, work)
        if end == TOO_FAST:
            return STATUS_TOO_FAST
        if end < 0.0 or (math.isnan(end) and contacts == 0):
            return STATUS_FALLBACK
        if math.isnan(end):  # the window ends in this contact
            break
        t = end
        impulse += par[M2] * (v_in - y[3])
        if contacts == 0:
            contact_time = t
            track[1] = False
            if track[2]:  # no rise of the signal in the whole first contact
                return STATUS_FALLBACK
        if auto:
            limit = window_end(t, ringing)
        contacts += 1
        rebound = -y[3]
        if contacts >= MAX_CONTACTS:
            return STATUS_FALLBACK
        if limit - t <= 0.0:
            break
        n = _record(pieces, n, t, 0.0, limit - t, y)
        best[PIECE_START] = t
        tau = free_flight(y, limit - t, free_modes, par, track, best, work)
        if tau == TOO_FAST:
            return STATUS_TOO_FAST
        if tau < 0.0:  # free until the window ends
            break
        t += tau
    if track[0]:  # the lobe is still open at the window's end
        raise_peak(best, SENSOR_PEAK, signal(SENSOR, y, par), max(t, limit))
    out[END] = max(t, limit)
    out[CONTACT_TIME], out[PEAK_CONTACT] = contact_time, best[CONTACT_PEAK]
    out[PEAK_CONTACT_AT] = best[CONTACT_PEAK_TIME]
    if rigid:  # the signal is the contact force
        out[RESPONSE_TIME], out[PEAK_SENSOR] = contact_time, best[CONTACT_PEAK]
        out[PEAK_SENSOR_AT] = best[CONTACT_PEAK_TIME]
    else:
        out[RESPONSE_TIME], out[PEAK_SENSOR] = best[LOBE_END], best[SENSOR_PEAK]
        out[PEAK_SENSOR_AT] = best[SENSOR_PEAK_TIME]
    out[RESTITUTION], out[CONTACTS], out[IMPULSE] = rebound / v0, contacts, impulse
    out[WINDOW], out[PIECES], out[REBOUND] = limit, n, rebound
    return STATUS_OK


@njit(cache=True, error_model="numpy", nogil=True)
def solve_rows(m1, k1, c1, m2, a, b, v0, p, q, rtol, out, status):
    """The batch: :func:`solve_impact` on every row of a law ``a d**p + b |d|**q d'``
    (``p = 1, q = 0``: linear), default window, no pieces recorded; ``out`` (rows, 6)
    gets the first six :data:`RESULTS`, ``status`` (rows,) the status. GIL released."""
    results, none = np.empty(RESULTS), np.empty((0, len(PIECE_FIELDS)))
    linear = p == 1.0 and q == 0.0
    for i in range(m1.size):
        rigid = math.isinf(k1[i])
        par = row_parameters(a[i], p, b[i], q, m1[i], k1[i], c1[i], m2[i], rigid, MAX_SCAN_POINTS)
        status[i] = solve_impact(par, linear, v0[i], rtol, math.nan, results, none)
        out[i, :] = results[:6]
