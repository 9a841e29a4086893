"""The solved contact of an oblique impact: its phases and their states at any time.

:func:`compiled_contact` runs :func:`contactlab.kernels.oblique_kernel.solve_contact`;
:class:`ContactPhases` holds what it kept (each phase's start, end and code, and every
step's interpolant) and evaluates states and forces at many times in one compiled pass
(:func:`sample`): the output grid of :class:`~contactlab.ObliqueResult`, its peaks and its
audit's quadrature nodes. :class:`PiecePhases` gives the same view of the contact the
Python phase loop solves (Kratos' elastic Coulomb cap, not compiled yet).
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.errors import ParameterError
from contactlab.kernels.oblique_kernel import (
    MAX_PHASES,
    STATUS_CHATTER,
    STATUS_OPEN,
    STATUS_UNDERFLOW,
    solve_contact,
)
from contactlab.kernels.oblique_rhs import FRICTION, STICK, arm, trial_force
from contactlab.kernels.power import RIGID, force
from contactlab.solver.adaptive import underflow_message

__all__ = ["ContactPhases", "PiecePhases", "compiled_contact", "sample"]


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


def compiled_contact(model, y0, rtol, atol, velocity):
    """The contact from the touch ``y0`` to the separation, compiled; returns
    (:class:`ContactPhases`, y_end).

    Parameters
    ----------
    model : contactlab.solver.oblique.ObliqueModel
        The impact (its :meth:`~contactlab.solver.oblique.ObliqueModel.pack`).
    y0 : numpy.ndarray
        State at the touch.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances (:func:`contactlab.kernels.oblique_kernel.tolerances`).
    velocity : float
        Impact speed [m/s] (for the messages).
    """
    par = model.pack()
    status, failed, y_end, table, count, warp, steps = solve_contact(
        par, np.asarray(y0, dtype=float), rtol, atol, True
    )
    if status == STATUS_UNDERFLOW:
        raise RuntimeError(underflow_message(failed, rtol))
    if status == STATUS_OPEN:
        raise ParameterError(
            f"the contact had not ended after {failed:.4g} s, so this is not an impact: "
            f"check the units of the grain (mass {model.system.m2:.4g} kg), the laws' "
            f"parameters and the velocity ({velocity:.4g} m/s)"
        )
    if status == STATUS_CHATTER:
        raise RuntimeError(f"more than {MAX_PHASES} stick/slip switches in one contact")
    return ContactPhases(par, table[:count], warp, steps), y_end


class PiecePhases:
    """:class:`ContactPhases`' view of the contact solved in Python: pieces with ``t0``,
    ``t1``, ``phase`` (its force's sign, 0 sticking) and dense ``states``."""

    def __init__(self, model, pieces):
        self._model, self._pieces = model, pieces

    @property
    def end(self):
        """End of the contact [s]."""
        return self._pieces[-1].t1

    def phases(self):
        """``[(start [s], end [s], phase code), ...]``: stick 0, slide +1 or -1."""
        return [(p.t0, p.t1, p.phase) for p in self._pieces]

    def __call__(self, times, out=None):
        """As :meth:`ContactPhases.__call__`."""
        times = np.asarray(times, dtype=float)
        if out is None:
            out = (np.empty((times.size, 7)), *np.empty((4, times.size)))
        states, raw, normal, tangential, slip = out
        model = self._model
        for piece in self._pieces:
            inside = (times >= piece.t0) & (times < piece.t1)
            if piece is self._pieces[-1]:
                inside |= times >= piece.t1
            if not inside.any():
                continue
            st = piece.states(times[inside] - piece.t0)
            d, r = st[:, 2] - st[:, 0], st[:, 3] - st[:, 1]
            states[inside], raw[inside] = st, model.normal(d, r)
            normal[inside] = np.maximum(raw[inside], 0.0)
            slip[inside] = model.slip(st)
            if piece.phase == STICK:
                tangential[inside] = model.law.trial_force(st[:, 6], d, slip[inside])
            else:
                tangential[inside] = piece.phase * model.law.friction * normal[inside]
        return out
