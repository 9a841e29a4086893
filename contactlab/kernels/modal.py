"""Modal pieces for the compiled batch kernels: scans, roots, modes and free flight.

A piece that is linear time-invariant (the free sensor with a grain in flight; the
coupled system under a linear contact) is ``y(tau) = base + slope tau +
Re(V (coef * exp(lam tau)))`` (modes ``lam``, mode shapes ``V`` with the rows of the
components the modes do not move set to zero, and ``coef = W (y0 - base)`` with
``W = V**-1``), and exactly ``y0`` at ``tau = 0`` as in
:class:`contactlab.kernels.segments.Trajectory`. Its events are found by scanning
their exact expressions on the points of
:func:`contactlab.solver.propagators.first_event` (step
:func:`contactlab.kernels.rules.scan_step`) and located by Brent's method to the solver's
tolerance (:mod:`contactlab.kernels.brent`); while it scans, :func:`scan` reads the
headline numbers as :class:`contactlab.ImpactResult` defines them (the sensor signal's
first lobe and its peak, the contact force's peak).

State ``y = [x1, v1, x2, v2]``. The row's parameters are one float array: the fields of
:func:`contactlab.kernels.power.pack` and a last one, ``IN_CONTACT``, set while a
contact piece is scanned (:func:`row_parameters`). The contact
law enters the event functions through :func:`contactlab.kernels.power.force`, so a
re-contact is found for any power-law contact; modal contact pieces are linear only
(the force slope of :func:`signal` is the linear law's).
"""

import cmath
import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.brent import brent_next, brent_start
from contactlab.kernels.power import (
    C1,
    DAMPING,
    K1,
    M1,
    M2,
    NORMAL_MODEL,
    PARAMETERS,
    RIGID,
    STIFFNESS,
    force,
)
from contactlab.kernels.rules import happened, scan_step
from contactlab.roots import SIDE_STEPS

__all__ = [
    "COND_LIMIT",
    "CONTACT_END",
    "RECONTACT",
    "SENSOR",
    "STATUS_FALLBACK",
    "STATUS_OK",
    "STATUS_TOO_FAST",
    "TOO_FAST",
    "falls",
    "free_flight",
    "may_exceed",
    "quadratic_modes",
    "recontact_horizon",
    "row_parameters",
    "scan",
    "signal",
    "state",
]

STATUS_OK, STATUS_FALLBACK, STATUS_TOO_FAST = 0, 1, 2
"""Row status of a batch kernel: solved; or handed to :func:`contactlab.simulate_impact`
(a row the kernel cannot take: modes too close to defective for the modal form, a first
contact that does not end, :data:`contactlab.kernels.rules.MAX_CONTACTS` contacts, a step
size that underflows); or refused, its modes too fast for an event scan of
:data:`contactlab.kernels.rules.MAX_SCAN_POINTS` points. A kernel writes the six numbers of
:data:`contactlab.batch.rows.RESULT_COLUMNS` for a solved row."""

COND_LIMIT = 1e7
"""Largest ``|V|_F |V**-1|_F`` (an upper bound of the eigenvector condition number) for
which a row is solved here; the single solver trusts the modal form up to a condition
number of 1e8 (:data:`contactlab.solver.propagators._COND_LIMIT`), so every row solved
here is modal there too, and rows beyond are handed to the single solver."""

_CHUNK = 256
"""Scan points per chunk, as :func:`contactlab.solver.propagators.first_event`."""

_TINY = np.finfo(np.float64).tiny

TOO_FAST = -2.0
"""What a scan returns when its piece's modes are too fast to follow (``SCAN_CAP``)."""

# signals the scans and root searches read off a state
CONTACT_END, RECONTACT, SENSOR, _SENSOR_SLOPE, _FORCE_SLOPE = range(5)
# fields of the row's parameter array
K2, C2 = STIFFNESS, DAMPING  # a linear contact's stiffness and damping, as in row_parameters
IN_CONTACT, SCAN_CAP = len(PARAMETERS), len(PARAMETERS) + 1
"""Run-time fields after the law's and system's: 1 while a contact piece is scanned; the
most scan points of one piece (:data:`contactlab.kernels.rules.MAX_SCAN_POINTS`)."""


SENSOR_PEAK, CONTACT_PEAK, LOBE_END, SENSOR_PEAK_TIME, CONTACT_PEAK_TIME, PIECE_START = range(6)
"""The readings an impact loop takes while it solves (its array ``best``): the largest
sensor signal S1 in its first lobe [N], the largest contact force S2 in the first contact
[N], the lobe's end [s], the times [s] of the two peaks, and the start [s] of the piece
being read (local times of a piece are read as ``best[PIECE_START] + tau``)."""

READINGS = 6
"""Length of the readings array ``best``."""


@njit(cache=True, error_model="numpy", inline="always")
def raise_peak(best, which, value, t):
    """Keep the larger of the peak ``best[which]`` and ``value`` [N] found at time ``t`` [s]
    (the earlier one on a tie); ``which`` is :data:`SENSOR_PEAK` or :data:`CONTACT_PEAK`."""
    if value > best[which]:
        best[which] = value
        best[which + 3] = t


@njit(cache=True, error_model="numpy", borrowed=True)
def state(tau, lam, vec, coef, nm, base, slope, y0, out):
    if tau == 0.0:
        for c in range(4):  # element copies: a slice copy checks overlap and may allocate
            out[c] = y0[c]
        return
    for c in range(4):
        out[c] = base[c] + slope[c] * tau
    for k in range(nm):
        e = coef[k] * cmath.exp(lam[k] * tau)
        for c in range(4):
            out[c] += (vec[c, k] * e).real


@njit(cache=True, error_model="numpy", inline="always")
def _state_from(tau, terms, vec, nm, base, slope, out):
    """State from its modal terms ``coef * exp(lam tau)`` (the scan's recurrence)."""
    for c in range(4):
        out[c] = base[c] + slope[c] * tau
    for k in range(nm):
        for c in range(4):
            out[c] += (vec[c, k] * terms[k]).real


@njit(cache=True, error_model="numpy", inline="always")
def signal(kind, y, par):
    """One signal at state ``y``: event functions, sensor signal, slopes of the signals."""
    d, r = y[2] - y[0], y[3] - y[1]
    k2, c2 = par[K2], par[C2]
    if kind == CONTACT_END:
        return force(d, r, par)
    if kind == RECONTACT:  # as contactlab.solver.exact.free_flight
        if d > 0.0:
            return force(d, r, par)
        return min(d, -_TINY)
    s2 = k2 * d + c2 * r if par[IN_CONTACT] > 0.0 else 0.0  # linear contact pieces only
    if par[RIGID] > 0.0:
        a1 = 0.0
    else:
        a1 = (s2 - par[K1] * y[0] - par[C1] * y[1]) / par[M1]
    if kind == SENSOR:
        return par[K1] * y[0] + par[C1] * y[1]
    if kind == _SENSOR_SLOPE:
        return par[K1] * y[1] + par[C1] * a1
    return k2 * r + c2 * (-s2 / par[M2] - a1)  # _FORCE_SLOPE


@njit(cache=True, error_model="numpy")
def _clipped_force(y, par):
    """Contact force S2 of a contact piece, never tensile (contactlab.solver.system.clipped)."""
    d = y[2] - y[0]
    if d < 0.0:
        return 0.0
    return max(par[K2] * d + par[C2] * (y[3] - y[1]), 0.0)


@njit(cache=True, error_model="numpy", borrowed=True)
def _crossed_side(kind, direction, t, hi, piece, par, y):
    """contactlab.roots.crossed_side: the first float from ``t`` where the event happened."""
    lam, vec, coef, nm, base, slope, y0 = piece
    for _ in range(SIDE_STEPS):
        if t >= hi:
            return hi
        state(t, lam, vec, coef, nm, base, slope, y0, y)
        if happened(signal(kind, y, par), direction):
            return t
        t = np.nextafter(t, math.inf)
    return hi


@njit(cache=True, error_model="numpy", borrowed=True)
def _root(kind, lo, f_lo, hi, f_hi, piece, par, y, work):
    """Root of one signal on ``[lo, hi]`` (Brent, the solver's tolerance)."""
    lam, vec, coef, nm, base, slope, y0 = piece
    x, done = brent_start(work, lo, f_lo, hi, f_hi)
    while not done:
        state(x, lam, vec, coef, nm, base, slope, y0, y)
        x, done = brent_next(work, signal(kind, y, par))
    return x


@njit(cache=True, error_model="numpy", borrowed=True)
def _refine_peak(slope_kind, peak, interval, piece, par, y, work, best):
    """A maximum between two scan points, raised into ``best[peak]`` if it is before the
    event: ``interval`` is ``(lo, slope at lo, hi, slope at hi, upto)`` [s] with the
    slope of ``slope_kind`` falling through zero on it; the maximum is its root (Brent),
    the value the sensor signal (``_SENSOR_SLOPE``) or the clipped contact force
    (``_FORCE_SLOPE``) there. Called only where the maximum may beat the best so far
    (:func:`may_exceed`), so the scan's hot loop stays a few comparisons a point."""
    lo, s_lo, hi, s_hi, upto = interval
    t_max = _root(slope_kind, lo, s_lo, hi, s_hi, piece, par, y, work)
    if t_max > upto:
        return
    lam, vec, coef, nm, base, slope, y0 = piece
    state(t_max, lam, vec, coef, nm, base, slope, y0, y)
    value = signal(SENSOR, y, par) if slope_kind == _SENSOR_SLOPE else _clipped_force(y, par)
    raise_peak(best, peak, value, best[PIECE_START] + t_max)


@njit(cache=True, error_model="numpy", borrowed=True)
def _read(event, y, par, track, values):
    """Signals of a scan point: [event, sensor signal, its slope, contact-force slope,
    contact force] (as :func:`_signal` and :func:`_clipped_force`, in one pass)."""
    values[0] = signal(event, y, par) if event >= 0 else 0.0
    d, r = y[2] - y[0], y[3] - y[1]
    raw = par[K2] * d + par[C2] * r
    force = raw if par[IN_CONTACT] > 0.0 else 0.0
    a1 = 0.0
    if par[RIGID] == 0.0:
        s1 = par[K1] * y[0] + par[C1] * y[1]
        a1 = (force - s1) / par[M1]
        values[1] = s1
        values[2] = par[K1] * y[1] + par[C1] * a1
    if track[1]:
        values[3] = par[K2] * r + par[C2] * (-force / par[M2] - a1)
        values[4] = 0.0 if d < 0.0 else max(raw, 0.0)


@njit(cache=True, error_model="numpy", inline="always")
def may_exceed(value, slope, best, h):
    """Whether a local maximum inside a scan interval of length ``h`` [s] can beat ``best``.

    The signal is concave about a maximum found between two scan points (31 per period
    of the fastest mode), so on the interval it stays below ``S(a) + S'(a) h``; twice
    that slope term is kept as a margin. Refining only the maxima that can win saves
    the root searches on the many lower ripples of a ringing sensor.
    """
    return value + 2.0 * slope * h >= best


@njit(cache=True, error_model="numpy", inline="always")
def falls(before, after):
    """Crossing from positive to non-positive (contactlab.roots.crosses, direction -1)."""
    return before > 0.0 and after <= 0.0


@njit(cache=True, error_model="numpy")
def scan(piece, par, tau0, tau_max, step, event, direction, track, best, y, work):
    """Scan one piece on ``(tau0, tau_max]`` as ``first_event`` does; returns the event time.

    A dip of the sensor signal between two scan points whose bottom may reach zero
    (the signal is convex there, so above ``S(a) + S'(a) h``) is refined: the lobe ends
    at the first crossing even when no scan point sees it. The scan points are those of
    ``first_event``; the modal terms are carried from one
    to the next by one complex product (about 256 eps relative after a chunk), as the
    scan only looks for sign changes; roots and peaks are evaluated directly.

    ``track`` (flags, updated): [0] the sensor lobe is open (look for its end and its
    maxima), [1] the contact force's maxima are wanted (first contact). ``best``
    (updated): the readings (:data:`READINGS`; the lobe's end is set when ``track[0]``
    turns False), with ``best[PIECE_START]`` the piece's start [s]. Returns the local
    time of the event, -1 when there is none (``event < 0`` scans for none), or
    :data:`TOO_FAST` when ``par[SCAN_CAP]`` points passed without the event.
    """
    lam, vec, coef, nm, base, slope, y0 = piece
    prev, cur = np.zeros(5), np.zeros(5)
    state(tau0, lam, vec, coef, nm, base, slope, y0, y)
    _read(event, y, par, track, prev)
    start, t_prev, points = tau0, tau0, 0
    terms, ratio = np.empty(nm, np.complex128), np.empty(nm, np.complex128)
    for k in range(nm):
        ratio[k] = cmath.exp(lam[k] * step)
    while start < tau_max:
        if points >= par[SCAN_CAP]:
            return TOO_FAST
        points += _CHUNK
        last = start
        for k in range(nm):  # modal terms at the chunk's start, then one product a point
            terms[k] = coef[k] * cmath.exp(lam[k] * start)
        for i in range(1, _CHUNK + 1):
            for k in range(nm):
                terms[k] *= ratio[k]
            tau = min(start + step * i, tau_max)
            if tau <= last:
                continue
            last = tau
            if tau < tau_max:
                _state_from(tau, terms, vec, nm, base, slope, y)
            else:
                state(tau, lam, vec, coef, nm, base, slope, y0, y)
            _read(event, y, par, track, cur)
            hit = -1.0
            if event >= 0:
                if direction < 0:
                    crossed = falls(prev[0], cur[0])
                else:
                    crossed = prev[0] < 0.0 and cur[0] >= 0.0
                if crossed:
                    hit = _root(event, t_prev, prev[0], tau, cur[0], piece, par, y, work)
                    hit = _crossed_side(event, direction, hit, tau, piece, par, y)
            upto = tau if hit < 0.0 else hit
            h = tau - t_prev
            # a maximum between the points, refined only where it may win: the checks stay
            # here, in the hot loop (a helper taking the readings and the piece as
            # arguments, even inlined, halved the batch's throughput: bench_core.py)
            if track[0] and falls(prev[2], cur[2]):  # [1] the sensor signal, [2] its slope
                if may_exceed(prev[1], prev[2], best[SENSOR_PEAK], h):
                    interval = (t_prev, prev[2], tau, cur[2], upto)
                    _refine_peak(_SENSOR_SLOPE, SENSOR_PEAK, interval, piece, par, y, work, best)
            if track[1] and falls(prev[3], cur[3]):  # [4] the contact force, [3] its slope
                if may_exceed(prev[4], prev[3], best[CONTACT_PEAK], h):
                    interval = (t_prev, prev[3], tau, cur[3], upto)
                    _refine_peak(_FORCE_SLOPE, CONTACT_PEAK, interval, piece, par, y, work, best)
            if track[0] and falls(prev[1], cur[1]):
                t_end = _root(SENSOR, t_prev, prev[1], tau, cur[1], piece, par, y, work)
                if t_end <= upto:
                    best[LOBE_END] = best[PIECE_START] + t_end
                    track[0] = False
            elif track[0] and prev[2] < 0.0 and cur[2] >= 0.0 and prev[1] + 2.0 * prev[2] * h <= 0:
                # a dip between two scan points that may reach zero: its bottom decides
                t_min = _root(_SENSOR_SLOPE, t_prev, prev[2], tau, cur[2], piece, par, y, work)
                state(t_min, lam, vec, coef, nm, base, slope, y0, y)
                bottom = signal(SENSOR, y, par)
                if t_min <= upto and bottom <= 0.0:
                    t_end = _root(SENSOR, t_prev, prev[1], t_min, bottom, piece, par, y, work)
                    best[LOBE_END] = best[PIECE_START] + t_end
                    track[0] = False
            if hit >= 0.0:
                return hit
            for c in range(5):  # as in state
                prev[c] = cur[c]
            t_prev = tau
        start = last
    return -1.0


@njit(cache=True, error_model="numpy")
def quadratic_modes(mass, damping, stiffness, row, lam, vec, inv):
    """Modes of ``m x'' + c x' + k x = 0`` on the components ``row, row + 1``.

    Eigenvectors ``(1, lambda)`` scaled to unit length, the roots in the
    cancellation-free form. Returns ``|V|_F |V**-1|_F`` of the unit eigenvectors in the
    force-scaled coordinates ``(k x, k v / omega)`` where the single solver measures it
    (:func:`contactlab.solver.system.force_scales`).
    """
    disc = damping * damping - 4.0 * mass * stiffness
    if disc >= 0.0:
        q = -0.5 * (damping + math.sqrt(disc))
        lam[0], lam[1] = complex(q / mass), complex(stiffness / q)
    else:
        im = 0.5 * math.sqrt(-disc) / mass
        lam[0], lam[1] = complex(-0.5 * damping / mass, im), complex(-0.5 * damping / mass, -im)
    if lam[0] == lam[1]:  # critical damping: one defective mode, no modal form
        return math.inf
    a0 = 1.0 / math.sqrt(1.0 + abs(lam[0]) ** 2)
    a1 = 1.0 / math.sqrt(1.0 + abs(lam[1]) ** 2)
    det = a0 * a1 * (lam[1] - lam[0])
    vec[row, 0], vec[row + 1, 0] = a0, a0 * lam[0]
    vec[row, 1], vec[row + 1, 1] = a1, a1 * lam[1]
    inv[0, row], inv[0, row + 1] = a1 * lam[1] / det, -a1 / det
    inv[1, row], inv[1, row + 1] = -a0 * lam[0] / det, a0 / det
    omega = math.sqrt(stiffness / mass)
    b0 = 1.0 / math.sqrt(1.0 + abs(lam[0] / omega) ** 2)
    b1 = 1.0 / math.sqrt(1.0 + abs(lam[1] / omega) ** 2)
    return 2.0 / abs(b0 * b1 * (lam[1] - lam[0]) / omega)


@njit(cache=True, error_model="numpy")
def conjugates_once(lam, vec, inv, nm):
    """Keep one mode of each complex-conjugate pair, its shape doubled; returns the
    number of modes kept (first in the arrays).

    The state is real, so a pair's two terms are complex conjugates and their sum is
    twice the real part of one (as :class:`contactlab.kernels.segments.Trajectory`
    does): half the exponentials. A mode whose imaginary part is round-off of a real
    eigenvalue (below 1e-10 of its size) counts as real and stays.
    """
    kept = 0
    for k in range(nm):
        real = abs(lam[k].imag) <= 1e-10 * abs(lam[k])
        if not real and lam[k].imag < 0.0:
            continue
        weight = 1.0 if real else 2.0
        lam[kept] = lam[k]
        for c in range(4):
            vec[c, kept] = weight * vec[c, k]
            inv[kept, c] = inv[k, c]
        kept += 1
    return kept


@njit(cache=True, error_model="numpy")
def fastest(lam, nm):
    rate = 0.0
    for k in range(nm):
        rate = max(rate, abs(lam[k]))
    return rate


@njit(cache=True, error_model="numpy")
def start_piece(inv, nm, base, y0, coef):
    for k in range(nm):
        acc = 0j
        for c in range(4):
            acc += inv[k, c] * (y0[c] - base[c])
        coef[k] = acc


@njit(cache=True, error_model="numpy")
def recontact_horizon(y, m1, k1, rigid, threshold):
    """Latest local time [s] at which a free grain can reach the plate again.

    The free plate's displacement never exceeds ``sqrt(2 E / k1)``, ``E`` its energy at
    the start of the flight ``y`` (damping only removes energy; ``m1`` [kg], ``k1``
    [N/m]), and a receding grain (``v2 < 0``) moves away at constant speed: beyond the
    returned time the overlap cannot reach ``threshold`` [m]. Infinite for a grain that
    is not receding.
    """
    x1, v1, x2, v2 = y[0], y[1], y[2], y[3]
    if v2 >= 0.0:
        return math.inf
    reach = 0.0 if rigid else math.sqrt(m1 * v1**2 / k1 + x1**2)
    return max((x2 + reach - threshold) / -v2, 0.0)


@njit(cache=True, error_model="numpy")
def row_parameters(a, p, b, q, m1, k1, c1, m2, rigid, scan_cap):
    """Parameter array of a row with the force ``a d**p + b |d|**q d'``: the fields of
    :func:`contactlab.kernels.power.pack` (unsigned damping), then ``IN_CONTACT`` (1) and
    ``SCAN_CAP`` (``scan_cap``, scan points)."""
    rigid = 1.0 if rigid else 0.0
    return np.array([a, p, b, q, 0.0, m1, k1, c1, m2, rigid, NORMAL_MODEL, 1.0, scan_cap])


@njit(cache=True, error_model="numpy")
def free_flight(y, tau_max, free_modes, par, track, best, work):
    """Free flight from the separation state ``y`` until a re-contact or ``tau_max`` [s].

    As :func:`contactlab.solver.exact.free_flight`: the plate rings freely
    (``free_modes = (lam, vec, inv, nm, rate)``, none on a wall), the grain flies at
    constant speed, a re-contact is the contact force rising through zero (or the
    overlap through zero) and is looked for until the grain can no longer reach the
    plate (:func:`recontact_horizon`); the sensor lobe is followed (``track``, ``best``
    as in :func:`scan`) to the window's end. The end state is written into ``y``.

    Returns
    -------
    float
        Local time of the re-contact [s], -1 when the flight lasts to ``tau_max``, or
        :data:`TOO_FAST`.
    """
    lam, vec, inv, nm, rate = free_modes
    par[IN_CONTACT] = 0.0
    y_sep = y.copy()
    if track[0]:
        raise_peak(best, SENSOR_PEAK, signal(SENSOR, y_sep, par), best[PIECE_START])
    base, slope = np.zeros(4), np.zeros(4)
    base[2], base[3], slope[2] = y_sep[2], y_sep[3], y_sep[3]
    coef = np.zeros(max(nm, 1), np.complex128)
    start_piece(inv, nm, base, y_sep, coef)
    free = (lam, vec, coef, nm, base, slope, y_sep)
    search = min(tau_max, recontact_horizon(y_sep, par[M1], par[K1], par[RIGID] > 0.0, 0.0))
    tau = scan(free, par, 0.0, search, scan_step(rate, search), RECONTACT, 1, track, best, y, work)
    if tau == -1.0 and track[0] and search < tau_max:
        step = scan_step(rate, tau_max - search)
        if scan(free, par, search, tau_max, step, -1, 1, track, best, y, work) == TOO_FAST:
            return TOO_FAST
    if tau == TOO_FAST:
        return TOO_FAST
    state(tau_max if tau < 0.0 else tau, lam, vec, coef, nm, base, slope, y_sep, y)
    return tau
