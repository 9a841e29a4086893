"""Compiled kernel of :func:`contactlab.batch.linear_impacts`: one impact per row.

Each row is solved as :func:`contactlab.simulate_impact` solves a linear (Kelvin-Voigt)
impact with ``method="exact"`` (:mod:`contactlab.solver.exact`): contact and free pieces
in modal form (modes in the force-scaled coordinates of
:func:`contactlab.solver.system.force_scales`), each event found by scanning its exact
expression and located by Brent's method to the solver's tolerance
(:mod:`contactlab.batch.modal_kernel`), the same window
(:func:`contactlab.solver.impact.auto_window` after each separation) and the same contact
cap. While it goes, the kernel reads the headline numbers as
:class:`contactlab.ImpactResult` defines them: the sensor signal's first lobe from the
first rise above zero to the first return to it, the peaks over the first contact and
over that lobe, the restitution after the last contact. It reads them exactly rather
than refined from an output grid: a peak is the largest of the local maxima (roots of
the signal's slope, found on the same scan) and the piece ends.
"""

import math

import numpy as np

from contactlab.batch.modal_kernel import (
    C1,
    C2,
    COND_LIMIT,
    CONTACT_END,
    IN_CONTACT,
    K1,
    K2,
    M1,
    M2,
    SENSOR,
    STATUS_FALLBACK,
    STATUS_OK,
    conjugates_once,
    fastest,
    free_flight,
    quadratic_modes,
    row_parameters,
    scan,
    scan_step,
    signal,
    start_piece,
    state,
)
from contactlab.compiled import njit
from contactlab.solver.brent import WORK_SIZE
from contactlab.solver.impact import (
    FIRST_CONTACT_HORIZON,
    MAX_CONTACTS,
    RINGING_PERIODS,
    WINDOW_PER_CONTACT,
)

__all__ = ["solve_rows"]


@njit(cache=True, error_model="numpy")
def _contact_modes(par, lam, vec, inv):
    """Modes of the coupled system under the linear contact (``System.contact_matrix``).

    Eigenvectors of the matrix in force-scaled coordinates
    (:func:`contactlab.solver.system.force_scales`), mapped back. Returns the condition
    bound ``|V|_F |V**-1|_F`` in the scaled coordinates.
    """
    m1, k1, c1, m2, k, c = par[M1], par[K1], par[C1], par[M2], par[K2], par[C2]
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
def solve_row(m1, k1, c1, m2, k2, c2, v0, out):
    """Solve one impact; write the six outputs into ``out``; return the row status."""
    rigid = math.isinf(k1)
    par = row_parameters(k2, 1.0, c2, 0.0, m1, k1, c1, m2, rigid)
    lam_c, vec_c = np.zeros(4, np.complex128), np.zeros((4, 4), np.complex128)
    inv_c = np.zeros((4, 4), np.complex128)
    lam_f, vec_f = np.zeros(2, np.complex128), np.zeros((4, 2), np.complex128)
    inv_f = np.zeros((2, 4), np.complex128)
    if rigid:
        nm_c, nm_f = 2, 0
        cond = quadratic_modes(m2, c2, k2, 2, lam_c, vec_c, inv_c)
    else:
        nm_c, nm_f = 4, 2
        cond = max(
            _contact_modes(par, lam_c, vec_c, inv_c),
            quadratic_modes(m1, c1, k1, 0, lam_f, vec_f, inv_f),
        )
    if not cond < COND_LIMIT:
        return STATUS_FALLBACK
    rate_c, rate_f = fastest(lam_c, nm_c), fastest(lam_f, nm_f)
    nm_c = conjugates_once(lam_c, vec_c, inv_c, nm_c)
    nm_f = conjugates_once(lam_f, vec_f, inv_f, nm_f)
    ringing = 0.0 if rigid else RINGING_PERIODS * 2.0 * math.pi / math.sqrt(k1 / m1)
    zeros = np.zeros(4)
    coef_c = np.zeros(4, np.complex128)
    free_modes = (lam_f, vec_f, inv_f, nm_f, rate_f)
    y0, y, work = np.array([0.0, 0.0, 0.0, v0]), np.zeros(4), np.zeros(WORK_SIZE)
    track = np.array([not rigid, True])
    best = np.array([0.0, max(c2 * v0, 0.0), math.nan])
    lobe_end = math.nan
    t, limit, contacts, contact_time, rebound = 0.0, math.inf, 0, math.nan, math.nan
    while True:
        par[IN_CONTACT] = 1.0
        if track[0]:  # a piece's start is a candidate for the sensor's peak
            best[0] = max(best[0], signal(SENSOR, y0, par))
        start_piece(inv_c, nm_c, zeros, y0, coef_c)
        contact = (lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0)
        horizon = (FIRST_CONTACT_HORIZON if contacts == 0 else limit) - t
        tau = scan(
            contact,
            par,
            0.0,
            horizon,
            scan_step(rate_c, horizon),
            CONTACT_END,
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
            state(horizon, lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0, y)
            break
        state(tau, lam_c, vec_c, coef_c, nm_c, zeros, zeros, y0, y)
        t += tau
        if contacts == 0:
            contact_time = t
            track[1] = False
        limit = max(WINDOW_PER_CONTACT * t, t + ringing)  # auto_window, after every contact
        contacts += 1
        rebound = -y[3]
        if contacts >= MAX_CONTACTS:
            return STATUS_FALLBACK
        tau_max = limit - t
        if tau_max <= 0.0:
            break
        tau = free_flight(y, tau_max, free_modes, par, track, best, work)
        if not track[0] and math.isnan(lobe_end):
            lobe_end = t + best[2]
        if tau < 0.0:  # free until the window ends
            break
        t += tau
        y0 = y.copy()
    if track[0]:  # the lobe is still open at the window's end
        best[0] = max(best[0], signal(SENSOR, y, par))
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
    """Solve every row: ``out`` (rows, 6), ``status`` (rows,); GIL released."""
    for i in range(m1.size):
        status[i] = solve_row(m1[i], k1[i], c1[i], m2[i], k2[i], c2[i], v0[i], out[i])
