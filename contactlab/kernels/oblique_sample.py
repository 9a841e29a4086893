"""The solved contact of an oblique impact as data: its phases, their steps and the states
and forces at any time.

:class:`ContactPhases` holds what the phase loop kept (each phase's start, end and code,
every step's interpolant, the packed parameters: arrays only) and evaluates states and
forces at many times in one compiled pass (:func:`sample`): the output grid of
:class:`~contactlab.ObliqueResult`, its peaks and its audit's quadrature nodes. Both
phase loops fill it: the compiled one (:func:`contactlab.kernels.oblique_kernel.solve_contact`,
LAMMPS' cap) and the Python one of :mod:`contactlab.solver.oblique` (Kratos' elastic cap),
whose pieces :func:`contactlab.solver.oblique_phases.piece_phases` packs the same way.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.oblique_rhs import FRICTION, STICK, arm, trial_force
from contactlab.kernels.power import RIGID, force

__all__ = ["ContactPhases", "sample"]


@njit(cache=True, error_model="numpy")
def _step_index(t_old, lo, hi, t, j):
    """The index in ``lo:hi`` of the last start ``t_old`` at or before ``t`` (the nearest
    one outside them), searched from ``j`` (the last one found: the times are mostly
    increasing)."""
    if j < lo or j >= hi or t < t_old[j]:
        j = lo + np.searchsorted(t_old[lo:hi], t, side="right") - 1
    while j + 1 < hi and t_old[j + 1] <= t:
        j += 1
    return min(max(j, lo), hi - 1)


@njit(cache=True, error_model="numpy")
def _interpolate(F, y_old, j, x, out, i, first):
    """Step ``j``'s interpolant at ``x`` into ``out[i, first:7]``: the seven-row form of
    :func:`contactlab.kernels.dop853.interpolate`, written out (a loop over the rows
    with a view per sample is several times slower on the output grid)."""
    u = 1.0 - x
    for c in range(first, 7):
        acc = F[j, 6, c] * x
        acc = (acc + F[j, 5, c]) * u
        acc = (acc + F[j, 4, c]) * x
        acc = (acc + F[j, 3, c]) * u
        acc = (acc + F[j, 2, c]) * x
        acc = (acc + F[j, 1, c]) * u
        acc = (acc + F[j, 0, c]) * x
        out[i, c] = acc + y_old[j, c]


@njit(cache=True, error_model="numpy")
def sample(par, table, warp, steps, times, states, raw, normal, tangential, slip):
    """States and forces of the contact at ``times`` [s] (each in ``[0, t_end]``).

    Parameters
    ----------
    par : numpy.ndarray
        Packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`).
    table : numpy.ndarray
        The phases (count, 8) of :func:`contactlab.kernels.oblique_kernel.solve_contact`.
    warp, steps : tuple
        The kept steps ``(count, t_old, h, y_old, F)`` in ``s`` and in time.
    times : numpy.ndarray
        Times [s], any order (increasing is fastest).
    states : numpy.ndarray
        Out: states (len(times), 7).
    raw, normal, tangential : numpy.ndarray
        Out: the normal law's unclipped formula, the normal force (>= 0) and the
        tangential force on the grain [N].
    slip : numpy.ndarray
        Out: the contact-point slip [m/s].
    """
    last = table.shape[0] - 1
    starts = table[:, 0].copy()
    _, w_t, w_h, w_y, w_F = warp
    _, s_t, s_h, s_y, s_F = steps
    mu = par[FRICTION]
    first = 2 if par[RIGID] > 0.0 else 0  # on a wall x1 = v1 = 0: not interpolated
    states[:, :first] = 0.0
    jw = js = k = -1
    for i in range(times.size):
        t = times[i]
        k = _step_index(starts, 0, last + 1, t, k)
        t0, phase, switch = table[k, 0], table[k, 2], table[k, 3]
        w0, w1, s0, s1 = int(table[k, 4]), int(table[k, 5]), int(table[k, 6]), int(table[k, 7])
        tau = t - t0
        if w1 > w0 and (s1 == s0 or tau < switch):
            s = math.sqrt(math.sqrt(max(tau, 0.0)))
            jw = _step_index(w_t, w0, w1, s, jw)
            _interpolate(w_F, w_y, jw, (s - w_t[jw]) / w_h[jw], states, i, first)
        else:
            js = _step_index(s_t, s0, s1, t, js)
            _interpolate(s_F, s_y, js, (t - s_t[js]) / s_h[js], states, i, first)
        d = states[i, 2] - states[i, 0]
        raw[i] = force(d, states[i, 3] - states[i, 1], par)
        normal[i] = max(raw[i], 0.0)
        slip[i] = states[i, 4] - arm(d, par) * states[i, 5]
        if phase == STICK:
            tangential[i] = trial_force(states[i, 6], d, slip[i], par)
        else:
            tangential[i] = phase * mu * normal[i]


class ContactPhases:
    """The phases of one contact and their dense states.

    Parameters
    ----------
    par : numpy.ndarray
        Packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`).
    table : numpy.ndarray
        Rows ``(t0, t1, phase, switch, warped steps lo, hi, steps lo, hi)`` of the phases.
    warp, steps : tuple
        The kept steps (see :func:`sample`).
    """

    def __init__(self, par, table, warp, steps):
        self._par, self._table, self._warp, self._steps = par, table, warp, steps

    @property
    def end(self):
        """End of the contact [s]."""
        return float(self._table[-1, 1])

    def phases(self):
        """``[(start [s], end [s], phase code), ...]``: stick 0, slide +1 or -1."""
        return [(t0, t1, int(code)) for t0, t1, code in self._table[:, :3].tolist()]

    def __call__(self, times, out=None):
        """States (n, 7), unclipped normal formula, normal and tangential force [N] and the
        contact-point slip [m/s] (n,) at ``times`` [s] inside the contact, into ``out``
        (arrays of these shapes) if given."""
        times = np.ascontiguousarray(times, dtype=float)
        if out is None:
            out = (np.empty((times.size, 7)), *np.empty((4, times.size)))
        sample(self._par, self._table, self._warp, self._steps, times, *out)
        return out
