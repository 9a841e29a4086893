"""The linear (Kelvin-Voigt) contact piece of the compiled impact loop, in modal form.

A contact ``S2 = k2 d + c2 d'`` makes the coupled grain/sensor system linear
time-invariant: its piece is the modal solution in the force-scaled coordinates of
:func:`contactlab.solver.system.force_scales`, its end (the force falling through zero)
found by the scan of :func:`contactlab.kernels.modal.scan` and located by Brent's
method to the solver's tolerance. While it scans, the piece reads the headline numbers
(:data:`contactlab.kernels.modal.READINGS`): a peak is the largest of the local maxima
(roots of the signal's slope, found on the same scan) and the piece ends, read exactly
rather than refined from an output grid.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.modal import (
    C1,
    C2,
    CONTACT_END,
    K1,
    K2,
    M1,
    M2,
    PIECE_START,
    RIGID,
    TOO_FAST,
    conjugates_once,
    fastest,
    quadratic_modes,
    scan,
    start_piece,
    state,
)
from contactlab.kernels.rules import contact_matrix, scan_step

__all__ = ["contact_modes", "linear_contact"]


@njit(cache=True, error_model="numpy")
def _coupled_modes(par, lam, vec, inv):
    """Modes of the coupled system under the linear contact
    (:func:`contactlab.kernels.rules.contact_matrix`).

    Eigenvectors of the matrix in force-scaled coordinates
    (:func:`contactlab.solver.system.force_scales`), mapped back. Returns the condition
    bound ``|V|_F |V**-1|_F`` in the scaled coordinates.
    """
    m1, k1, m2, k = par[M1], par[K1], par[M2], par[K2]
    a = contact_matrix(m1, k1, par[C1], m2, k, par[C2], False).astype(np.complex128)
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
def contact_modes(par):
    """The modes of the linear contact piece: ``(lam, vec, inv, nm, rate)`` (one mode of
    each conjugate pair, :func:`contactlab.kernels.modal.conjugates_once`; ``rate`` the
    largest ``|lambda|`` [1/s]) and the condition bound of the mode shapes."""
    lam, vec = np.zeros(4, np.complex128), np.zeros((4, 4), np.complex128)
    inv = np.zeros((4, 4), np.complex128)
    if par[RIGID] > 0.0:
        nm = 2
        cond = quadratic_modes(par[M2], par[C2], par[K2], 2, lam, vec, inv)
    else:
        nm = 4
        cond = _coupled_modes(par, lam, vec, inv)
    rate = fastest(lam, nm)
    nm = conjugates_once(lam, vec, inv, nm)
    return (lam, vec, inv, nm, rate), cond


@njit(cache=True, error_model="numpy")
def linear_contact(modes, par, t, y, horizon, track, best, work):
    """One linear contact piece from ``(t, y)`` [s, state]; returns its end time [s]
    (nan: none within ``horizon`` [s]; :data:`~contactlab.kernels.modal.TOO_FAST` if
    its modes are too fast for the scan). ``y`` becomes the state at the end (at
    ``t + horizon`` if none); ``track`` and ``best`` as in
    :func:`contactlab.kernels.modal.scan`."""
    lam, vec, inv, nm, rate = modes
    zeros, coef, y0 = np.zeros(4), np.zeros(4, np.complex128), y.copy()
    start_piece(inv, nm, zeros, y0, coef)
    piece = (lam, vec, coef, nm, zeros, zeros, y0)
    best[PIECE_START] = t
    step = scan_step(rate, horizon)
    tau = scan(piece, par, 0.0, horizon, step, CONTACT_END, -1, track, best, y, work)
    if tau == TOO_FAST:
        return TOO_FAST
    state(horizon if tau < 0.0 else tau, lam, vec, coef, nm, zeros, zeros, y0, y)
    return math.nan if tau < 0.0 else t + tau
