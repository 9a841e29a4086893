"""Compiled kernel of :func:`contactlab.batch.linear_impacts`: one impact per row.

Each row is solved as :func:`contactlab.simulate_impact` solves a linear (Kelvin-Voigt)
impact with ``method="exact"`` (:mod:`contactlab.solver.exact`): contact and free pieces
in modal form (modes in the force-scaled coordinates of
:func:`contactlab.solver.system.force_scales`), each event found by scanning its exact
expression on the same points (:func:`contactlab.solver.propagators.first_event`, step
:func:`contactlab.solver.system.scan_step`) and located by Brent's method to the same
tolerance (:mod:`contactlab.solver.brent`), the same window
(:func:`contactlab.solver.impact.auto_window` after each separation) and the same contact
cap. While it goes, the kernel reads the headline numbers as
:class:`contactlab.ImpactResult` defines them: the sensor signal's first lobe from the
first rise above zero to the first return to it, the peaks over the first contact and
over that lobe, the restitution after the last contact. It reads them exactly rather
than refined from an output grid: a peak is the largest of the local maxima (roots of
the signal's slope, found on the same scan) and the piece ends.

State everywhere ``y = [x1, v1, x2, v2]``; a piece is ``y(tau) = base + slope tau +
Re(V (coef * exp(lam tau)))`` (modes ``lam``, mode shapes ``V`` with the rows of the
components the modes do not move set to zero, and ``coef = W (y0 - base)`` with
``W = V**-1``), and exactly ``y0`` at ``tau = 0`` as in
:class:`contactlab.solver.propagators.Trajectory`.
"""

import cmath
import math

import numpy as np
from numba import njit

from contactlab.roots import SIDE_STEPS
from contactlab.solver.brent import WORK_SIZE, brent_next, brent_start
from contactlab.solver.impact import (
    FIRST_CONTACT_HORIZON,
    MAX_CONTACTS,
    RINGING_PERIODS,
    WINDOW_PER_CONTACT,
)
from contactlab.solver.system import SCAN_STEPS_PER_RADIAN

__all__ = ["OUTPUTS", "STATUS_FALLBACK", "STATUS_MAX_CONTACTS", "STATUS_OK", "solve_rows"]

OUTPUTS = 6
"""contact time, response time, peak contact force, peak sensor force, restitution,
contacts (the order of ``out``)."""

STATUS_OK, STATUS_FALLBACK, STATUS_MAX_CONTACTS = 0, 1, 2
"""Row status: solved; to be solved by :func:`contactlab.simulate_impact` (modes too
close to defective for the modal form, or a first contact that does not end); stopped
at :data:`contactlab.solver.impact.MAX_CONTACTS` contacts as the single solver stops."""

_COND_LIMIT = 1e7
"""Largest ``|V|_F |V**-1|_F`` (an upper bound of the eigenvector condition number) for
which a row is solved here; the single solver trusts the modal form up to a condition
number of 1e8 (:data:`contactlab.solver.propagators._COND_LIMIT`), so every row solved
here is modal there too, and rows beyond are handed to the single solver."""

_CHUNK = 256
"""Scan points per chunk, as :func:`contactlab.solver.propagators.first_event`."""

_TINY = np.finfo(np.float64).tiny

# signals the scans and root searches read off a state
_CONTACT_END, _RECONTACT, _SENSOR, _SENSOR_SLOPE, _FORCE_SLOPE = range(5)
# fields of the row's parameter array
_M1, _K1, _C1, _M2, _K2, _C2, _RIGID, _IN_CONTACT = range(8)


@njit(cache=True, error_model="numpy")
def _state(tau, lam, vec, coef, nm, base, slope, y0, out):
    if tau == 0.0:
        out[:] = y0
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
def _signal(kind, y, par):
    """One signal at state ``y``: event functions, sensor signal, slopes of the signals."""
    d, r = y[2] - y[0], y[3] - y[1]
    k2, c2 = par[_K2], par[_C2]
    if kind == _CONTACT_END:
        return k2 * d + c2 * r
    if kind == _RECONTACT:  # as contactlab.solver.exact.free_flight
        if d > 0.0:
            return k2 * d + c2 * r
        return min(d, -_TINY)
    force = k2 * d + c2 * r if par[_IN_CONTACT] > 0.0 else 0.0
    if par[_RIGID] > 0.0:
        a1 = 0.0
    else:
        a1 = (force - par[_K1] * y[0] - par[_C1] * y[1]) / par[_M1]
    if kind == _SENSOR:
        return par[_K1] * y[0] + par[_C1] * y[1]
    if kind == _SENSOR_SLOPE:
        return par[_K1] * y[1] + par[_C1] * a1
    return k2 * r + c2 * (-force / par[_M2] - a1)  # _FORCE_SLOPE


@njit(cache=True, error_model="numpy")
def _clipped_force(y, par):
    """Contact force S2 of a contact piece, never tensile (contactlab.solver.system.clipped)."""
    d = y[2] - y[0]
    if d < 0.0:
        return 0.0
    return max(par[_K2] * d + par[_C2] * (y[3] - y[1]), 0.0)


@njit(cache=True, error_model="numpy")
def _crossed_side(kind, direction, t, hi, piece, par, y):
    """contactlab.roots.crossed_side: the first float from ``t`` where the event happened."""
    lam, vec, coef, nm, base, slope, y0 = piece
    for _ in range(SIDE_STEPS):
        if t >= hi:
            return hi
        _state(t, lam, vec, coef, nm, base, slope, y0, y)
        v = _signal(kind, y, par)
        if (v <= 0.0) if direction < 0 else (v >= 0.0):
            return t
        t = np.nextafter(t, math.inf)
    return hi


@njit(cache=True, error_model="numpy")
def _root(kind, lo, f_lo, hi, f_hi, piece, par, y, work):
    """Root of one signal on ``[lo, hi]`` (Brent, the solver's tolerance)."""
    lam, vec, coef, nm, base, slope, y0 = piece
    x, done = brent_start(work, lo, f_lo, hi, f_hi)
    while not done:
        _state(x, lam, vec, coef, nm, base, slope, y0, y)
        x, done = brent_next(work, _signal(kind, y, par))
    return x


@njit(cache=True, error_model="numpy", inline="always")
def _read(event, y, par, track, values):
    """Signals of a scan point: [event, sensor signal, its slope, contact-force slope,
    contact force] (as :func:`_signal` and :func:`_clipped_force`, in one pass)."""
    values[0] = _signal(event, y, par) if event >= 0 else 0.0
    d, r = y[2] - y[0], y[3] - y[1]
    raw = par[_K2] * d + par[_C2] * r
    force = raw if par[_IN_CONTACT] > 0.0 else 0.0
    a1 = 0.0
    if par[_RIGID] == 0.0:
        s1 = par[_K1] * y[0] + par[_C1] * y[1]
        a1 = (force - s1) / par[_M1]
        values[1] = s1
        values[2] = par[_K1] * y[1] + par[_C1] * a1
    if track[1]:
        values[3] = par[_K2] * r + par[_C2] * (-force / par[_M2] - a1)
        values[4] = 0.0 if d < 0.0 else max(raw, 0.0)


@njit(cache=True, error_model="numpy", inline="always")
def _may_exceed(value, slope, best, h):
    """Whether a local maximum inside a scan interval of length ``h`` [s] can beat ``best``.

    The signal is concave about a maximum found between two scan points (31 per period
    of the fastest mode), so on the interval it stays below ``S(a) + S'(a) h``; twice
    that slope term is kept as a margin. Refining only the maxima that can win saves
    the root searches on the many lower ripples of a ringing sensor.
    """
    return value + 2.0 * slope * h >= best


@njit(cache=True, error_model="numpy", inline="always")
def _falls(before, after):
    """Crossing from positive to non-positive (contactlab.roots.crosses, direction -1)."""
    return before > 0.0 and after <= 0.0


@njit(cache=True, error_model="numpy")
def _scan(piece, par, tau0, tau_max, step, event, direction, track, best, y, work):
    """Scan one piece on ``(tau0, tau_max]`` as ``first_event`` does; returns the event time.

    A dip of the sensor signal between two scan points whose bottom may reach zero
    (the signal is convex there, so above ``S(a) + S'(a) h``) is refined: the lobe ends
    at the first crossing even when no scan point sees it. The scan points are those of
    ``first_event``; the modal terms are carried from one
    to the next by one complex product (about 256 eps relative after a chunk), as the
    scan only looks for sign changes; roots and peaks are evaluated directly.

    ``track`` (flags, updated): [0] the sensor lobe is open (look for its end and its
    maxima), [1] the contact force's maxima are wanted (first contact). ``best``
    (updated): [0] largest sensor signal so far, [1] largest contact force, [2] lobe end
    (local time, found when ``track[0]`` turns False). Returns the local time of the
    event, or -1 when there is none (``event < 0`` scans for none).
    """
    lam, vec, coef, nm, base, slope, y0 = piece
    prev, cur = np.zeros(5), np.zeros(5)
    _state(tau0, lam, vec, coef, nm, base, slope, y0, y)
    _read(event, y, par, track, prev)
    start, t_prev = tau0, tau0
    terms, ratio = np.empty(nm, np.complex128), np.empty(nm, np.complex128)
    for k in range(nm):
        ratio[k] = cmath.exp(lam[k] * step)
    while start < tau_max:
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
                _state(tau, lam, vec, coef, nm, base, slope, y0, y)
            _read(event, y, par, track, cur)
            hit = -1.0
            if event >= 0:
                if direction < 0:
                    crossed = _falls(prev[0], cur[0])
                else:
                    crossed = prev[0] < 0.0 and cur[0] >= 0.0
                if crossed:
                    hit = _root(event, t_prev, prev[0], tau, cur[0], piece, par, y, work)
                    hit = _crossed_side(event, direction, hit, tau, piece, par, y)
            upto = tau if hit < 0.0 else hit
            h = tau - t_prev
            if track[0] and _falls(prev[2], cur[2]) and _may_exceed(prev[1], prev[2], best[0], h):
                t_max = _root(_SENSOR_SLOPE, t_prev, prev[2], tau, cur[2], piece, par, y, work)
                if t_max <= upto:
                    _state(t_max, lam, vec, coef, nm, base, slope, y0, y)
                    best[0] = max(best[0], _signal(_SENSOR, y, par))
            if track[0] and _falls(prev[1], cur[1]):
                t_end = _root(_SENSOR, t_prev, prev[1], tau, cur[1], piece, par, y, work)
                if t_end <= upto:
                    best[2] = t_end
                    track[0] = False
            elif track[0] and prev[2] < 0.0 and cur[2] >= 0.0 and prev[1] + 2.0 * prev[2] * h <= 0:
                # a dip between two scan points that may reach zero: its bottom decides
                t_min = _root(_SENSOR_SLOPE, t_prev, prev[2], tau, cur[2], piece, par, y, work)
                _state(t_min, lam, vec, coef, nm, base, slope, y0, y)
                bottom = _signal(_SENSOR, y, par)
                if t_min <= upto and bottom <= 0.0:
                    best[2] = _root(_SENSOR, t_prev, prev[1], t_min, bottom, piece, par, y, work)
                    track[0] = False
            if track[1] and _falls(prev[3], cur[3]) and _may_exceed(prev[4], prev[3], best[1], h):
                t_max = _root(_FORCE_SLOPE, t_prev, prev[3], tau, cur[3], piece, par, y, work)
                if t_max <= upto:
                    _state(t_max, lam, vec, coef, nm, base, slope, y0, y)
                    best[1] = max(best[1], _clipped_force(y, par))
            if hit >= 0.0:
                return hit
            prev[:] = cur
            t_prev = tau
        start = last
    return -1.0


@njit(cache=True, error_model="numpy")
def _scan_step(rate, tau_max):
    """contactlab.solver.system.scan_step."""
    if rate == 0.0:
        return tau_max / 64.0
    return min(tau_max / 64.0, 1.0 / (SCAN_STEPS_PER_RADIAN * rate))


@njit(cache=True, error_model="numpy")
def _quadratic_modes(mass, damping, stiffness, row, lam, vec, inv):
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
def _contact_modes(par, lam, vec, inv):
    """Modes of the coupled system under the linear contact (``System.contact_matrix``).

    Eigenvectors of the matrix in force-scaled coordinates
    (:func:`contactlab.solver.system.force_scales`), mapped back. Returns the condition
    bound ``|V|_F |V**-1|_F`` in the scaled coordinates.
    """
    m1, k1, c1, m2, k, c = par[_M1], par[_K1], par[_C1], par[_M2], par[_K2], par[_C2]
    a = np.zeros((4, 4), dtype=np.complex128)
    a[0, 1] = 1.0
    a[1, 0], a[1, 1], a[1, 2], a[1, 3] = -(k1 + k) / m1, -(c1 + c) / m1, k / m1, c / m1
    a[2, 3] = 1.0
    a[3, 0], a[3, 1], a[3, 2], a[3, 3] = k / m2, c / m2, -k / m2, -c / m2
    scale = np.array([k1, k1 / math.sqrt(k1 / m1), k, k / math.sqrt(k / m2)])
    for i in range(4):
        for j in range(4):
            a[i, j] *= scale[i] / scale[j]
    w, v = np.linalg.eig(a)
    w_inv = np.linalg.inv(v)
    cond = math.sqrt(np.sum(np.abs(v) ** 2) * np.sum(np.abs(w_inv) ** 2))
    lam[:] = w
    for i in range(4):
        for j in range(4):
            vec[i, j] = v[i, j] / scale[i]
            inv[i, j] = w_inv[i, j] * scale[j]
    return cond


@njit(cache=True, error_model="numpy")
def _conjugates_once(lam, vec, inv, nm):
    """Keep one mode of each complex-conjugate pair, its shape doubled; returns the
    number of modes kept (first in the arrays).

    The state is real, so a pair's two terms are complex conjugates and their sum is
    twice the real part of one (as :class:`contactlab.solver.propagators.Trajectory`
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
def _fastest(lam, nm):
    rate = 0.0
    for k in range(nm):
        rate = max(rate, abs(lam[k]))
    return rate


@njit(cache=True, error_model="numpy")
def _start_piece(inv, nm, base, y0, coef):
    for k in range(nm):
        acc = 0j
        for c in range(4):
            acc += inv[k, c] * (y0[c] - base[c])
        coef[k] = acc


@njit(cache=True, error_model="numpy")
def _recontact_horizon(y, par):
    """contactlab.solver.exact._recontact_horizon (threshold 0)."""
    x1, v1, x2, v2 = y[0], y[1], y[2], y[3]
    if v2 >= 0.0:
        return math.inf
    reach = 0.0 if par[_RIGID] > 0.0 else math.sqrt(par[_M1] * v1**2 / par[_K1] + x1**2)
    return max((x2 + reach - 0.0) / -v2, 0.0)


@njit(cache=True, error_model="numpy")
def solve_row(m1, k1, c1, m2, k2, c2, v0, out):
    """Solve one impact; write the six outputs into ``out``; return the row status."""
    rigid = math.isinf(k1)
    par = np.array([m1, k1, c1, m2, k2, c2, 1.0 if rigid else 0.0, 1.0])
    lam_c, vec_c = np.zeros(4, np.complex128), np.zeros((4, 4), np.complex128)
    inv_c = np.zeros((4, 4), np.complex128)
    lam_f, vec_f = np.zeros(2, np.complex128), np.zeros((4, 2), np.complex128)
    inv_f = np.zeros((2, 4), np.complex128)
    if rigid:
        nm_c, nm_f = 2, 0
        cond = _quadratic_modes(m2, c2, k2, 2, lam_c, vec_c, inv_c)
    else:
        nm_c, nm_f = 4, 2
        cond = max(
            _contact_modes(par, lam_c, vec_c, inv_c),
            _quadratic_modes(m1, c1, k1, 0, lam_f, vec_f, inv_f),
        )
    if not cond < _COND_LIMIT:
        return STATUS_FALLBACK
    rate_c, rate_f = _fastest(lam_c, nm_c), _fastest(lam_f, nm_f)
    nm_c = _conjugates_once(lam_c, vec_c, inv_c, nm_c)
    nm_f = _conjugates_once(lam_f, vec_f, inv_f, nm_f)
    ringing = 0.0 if rigid else RINGING_PERIODS * 2.0 * math.pi / math.sqrt(k1 / m1)
    zeros = np.zeros(4)
    coef_c, coef_f = np.zeros(4, np.complex128), np.zeros(2, np.complex128)
    base, slope = np.zeros(4), np.zeros(4)
    y0, y, work = np.array([0.0, 0.0, 0.0, v0]), np.zeros(4), np.zeros(WORK_SIZE)
    track = np.array([not rigid, True])
    best = np.array([0.0, max(c2 * v0, 0.0), math.nan])
    lobe_end = math.nan
    t, limit, contacts, contact_time, rebound = 0.0, math.inf, 0, math.nan, math.nan
    while True:
        par[_IN_CONTACT] = 1.0
        if track[0]:  # a piece's start is a candidate for the sensor's peak
            best[0] = max(best[0], _signal(_SENSOR, y0, par))
        _start_piece(inv_c, nm_c, zeros, y0, coef_c)
        contact = (lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0)
        horizon = (FIRST_CONTACT_HORIZON if contacts == 0 else limit) - t
        tau = _scan(
            contact,
            par,
            0.0,
            horizon,
            _scan_step(rate_c, horizon),
            _CONTACT_END,
            -1,
            track,
            best,
            y,
            work,
        )
        if not track[0] and math.isnan(lobe_end):
            lobe_end = t + best[2]
        if tau < 0.0:  # the window ends in this contact
            if contacts == 0:
                return STATUS_FALLBACK
            _state(horizon, lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0, y)
            break
        _state(tau, lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0, y)
        t += tau
        if contacts == 0:
            contact_time = t
            track[1] = False
        limit = max(WINDOW_PER_CONTACT * t, t + ringing)  # auto_window, after every contact
        contacts += 1
        rebound = -y[3]
        if contacts >= MAX_CONTACTS:
            return STATUS_FALLBACK
        par[_IN_CONTACT] = 0.0
        y_sep = y.copy()
        if track[0]:
            best[0] = max(best[0], _signal(_SENSOR, y_sep, par))
        base[2], base[3], slope[2] = y_sep[2], y_sep[3], y_sep[3]
        _start_piece(inv_f, nm_f, base, y_sep, coef_f)
        free = (lam_f, vec_f, coef_f, nm_f, base, slope, y_sep)
        tau_max = limit - t
        if tau_max <= 0.0:
            break
        search = min(tau_max, _recontact_horizon(y_sep, par))
        tau = _scan(
            free, par, 0.0, search, _scan_step(rate_f, search), _RECONTACT, 1, track, best, y, work
        )
        if tau < 0.0 and track[0] and search < tau_max:
            step = _scan_step(rate_f, tau_max - search)
            _scan(free, par, search, tau_max, step, -1, 1, track, best, y, work)
        if not track[0] and math.isnan(lobe_end):
            lobe_end = t + best[2]
        if tau < 0.0:  # free until the window ends
            _state(tau_max, lam_f, vec_f, coef_f, nm_f, base, slope, y_sep, y)
            break
        _state(tau, lam_f, vec_f, coef_f, nm_f, base, slope, y_sep, y)
        t += tau
        y0 = y.copy()
    if track[0]:  # the lobe is still open at the window's end
        best[0] = max(best[0], _signal(_SENSOR, y, par))
    out[0] = contact_time
    out[2] = best[1]
    if rigid:
        out[1], out[3] = contact_time, best[1]
    else:
        out[1], out[3] = lobe_end, best[0]
    out[4] = rebound / v0
    out[5] = contacts
    return STATUS_OK


@njit(cache=True, error_model="numpy", nogil=True)
def solve_rows(m1, k1, c1, m2, k2, c2, v0, out, status):
    """Solve every row: ``out`` (rows, OUTPUTS), ``status`` (rows,); GIL released."""
    for i in range(m1.size):
        status[i] = solve_row(m1[i], k1[i], c1[i], m2[i], k2[i], c2[i], v0[i], out[i])
