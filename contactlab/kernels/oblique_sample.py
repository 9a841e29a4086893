"""The solved contact of an oblique impact as data: its phases, their steps and the states
and forces at any time.

:class:`ContactPhases` holds what the phase loop kept (each phase's start, end and code,
every step's interpolant, the packed parameters: arrays only) and evaluates states and
forces at many times in one compiled pass (:func:`sample`): the output grid of
:class:`~contactlab.ObliqueResult`, its peaks and its audit's quadrature nodes. Both
compiled phase loops fill it: LAMMPS' cap's (:func:`contactlab.kernels.oblique_kernel.
solve_contact`) and Kratos' elastic cap's (:func:`contactlab.kernels.elastic_cap.
solve_contact`, whose phase codes are the slides' signs).
"""

import math

import numpy as np
from numba.np.unsafe.ndarray import to_fixed_tuple

from contactlab.compiled import njit
from contactlab.errors import ParameterError
from contactlab.kernels.gauss import panel_edges, rule
from contactlab.kernels.oblique_rhs import FRICTION, OBLIQUE_PARAMETERS, STICK, arm, trial_force
from contactlab.kernels.oblique_rhs import slip as slip_of
from contactlab.kernels.power import RIGID, force

__all__ = ["ContactPhases", "arm_moment", "grid", "grid_worst", "peak_forces", "sample"]

PARAMETER_COUNT = len(OBLIQUE_PARAMETERS)
"""Fields of the packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`)."""


@njit(cache=True, error_model="numpy")
def _before(times, i, stop, t0, bound):
    """The first index in ``i:stop`` whose ``times - t0`` is not below ``bound``
    (``stop`` if none)."""
    while i < stop and times[i] - t0 < bound:
        i += 1
    return i


@njit(cache=True, error_model="numpy")
def _held(f0, f1, f2, f3, f4, f5, f6, y):
    """Whether a component's interpolant is its start value ``y`` to the last bit: all its
    coefficients zero (the history while sliding) and ``y`` not ``-0.0``.

    The interpolant then adds a sum of signed zeros (finite ``x``: a step's length is
    positive) to ``y``, which leaves a nonzero ``y`` and ``+0.0`` as they are; only for
    ``-0.0`` would the sign of the sum decide."""
    zero = f0 == 0.0 and f1 == 0.0 and f2 == 0.0 and f3 == 0.0 and f4 == 0.0
    return zero and f5 == 0.0 and f6 == 0.0 and (y != 0.0 or math.copysign(1.0, y) > 0.0)


@njit(cache=True, error_model="numpy")
def _interpolate(F, y_old, j, span, times, warped_from, first, states, xs):
    """Step ``j``'s interpolant (``F`` (steps, 7, n), ``y_old`` (steps, n)) at
    ``times[lo:hi]`` into ``states[first:7, lo:hi]``: the seven-row form of
    :func:`contactlab.kernels.dop853.interpolate`, written out, a component at a time
    over the samples (a loop the compiler vectorises; the same operations in the same
    order as sample by sample).

    ``span`` is ``(lo, hi, t_old, h)``; ``warped_from`` the phase's start [s] if the step
    is in ``s = tau**(1/4)``, nan if in time; ``xs`` scratch (len(times),)."""
    lo, hi, t_old, h = span
    if math.isnan(warped_from):
        for m in range(lo, hi):
            xs[m] = (times[m] - t_old) / h
    else:
        for m in range(lo, hi):
            xs[m] = (math.sqrt(math.sqrt(max(times[m] - warped_from, 0.0))) - t_old) / h
    for c in range(first, 7):
        f0, f1, f2, f3 = F[j, 0, c], F[j, 1, c], F[j, 2, c], F[j, 3, c]
        f4, f5, f6, y = F[j, 4, c], F[j, 5, c], F[j, 6, c], y_old[j, c]
        if _held(f0, f1, f2, f3, f4, f5, f6, y):
            states[c, lo:hi] = y
            continue
        for m in range(lo, hi):
            x = xs[m]
            u = 1.0 - x
            acc = f6 * x
            acc = (acc + f5) * u
            acc = (acc + f4) * x
            acc = (acc + f3) * u
            acc = (acc + f2) * x
            acc = (acc + f1) * u
            acc = (acc + f0) * x
            states[c, m] = acc + y


@njit(cache=True, error_model="numpy")
def _forces(par, phase, lo, hi, states, raw, normal, tangential, slip):
    """Normal and tangential forces and slip of ``states[:, lo:hi]`` in ``phase``."""
    par = to_fixed_tuple(par, PARAMETER_COUNT)  # in registers: no reload after each store
    mu = par[FRICTION]
    for m in range(lo, hi):
        d = states[2, m] - states[0, m]
        raw[m] = force(d, states[3, m] - states[1, m], par)
        normal[m] = max(raw[m], 0.0)
        slip[m] = states[4, m] - arm(d, par) * states[5, m]
        if phase == STICK:
            tangential[m] = trial_force(states[6, m], d, slip[m], par)
        else:
            tangential[m] = phase * mu * normal[m]


@njit(cache=True, error_model="numpy")
def _warped_end(w_t, j, i, stop, times, t0):
    """The first index in ``i:stop`` whose ``s = (t - t0)**(1/4)`` reaches ``w_t[j]``."""
    while i < stop and math.sqrt(math.sqrt(max(times[i] - t0, 0.0))) < w_t[j]:
        i += 1
    return i


@njit(cache=True, error_model="numpy")
def sample(par, table, warp, steps, times, states, raw, normal, tangential, slip):
    """States and forces of the contact at ``times`` [s] (non-decreasing, each in
    ``[0, t_end]``); returns False, and fills nothing, if ``times`` decrease somewhere.

    Step by step: each phase's samples run through its warped steps (``s =
    tau**(1/4)``, up to the hand-over at ``switch``), then its steps in time; a sample is
    read on the last step that starts at or before it (the first one before the first
    start).

    Parameters
    ----------
    par : numpy.ndarray
        Packed parameters (:func:`contactlab.kernels.oblique_rhs.pack`).
    table : numpy.ndarray
        The phases (count, 8) of :func:`contactlab.kernels.oblique_kernel.solve_contact`.
    warp, steps : tuple
        The kept steps ``(count, t_old, h, y_old, F)`` in ``s`` and in time.
    times : numpy.ndarray
        Times [s], non-decreasing.
    states : numpy.ndarray
        Out: states (7, >= len(times)), a row per component (the out arrays may be
        longer than ``times``: their first len(times) columns are written).
    raw, normal, tangential : numpy.ndarray
        Out: the normal law's unclipped formula, the normal force (>= 0) and the
        tangential force on the grain [N].
    slip : numpy.ndarray
        Out: the contact-point slip [m/s] (the scratch of the interpolation variable
        until a phase's forces are read).
    """
    n = times.size
    for i in range(1, n):
        if times[i] < times[i - 1]:
            return False
    _, w_t, w_h, w_y, w_F = warp
    _, s_t, s_h, s_y, s_F = steps
    first = 2 if par[RIGID] > 0.0 else 0  # on a wall x1 = v1 = 0: not interpolated
    states[:first, :n] = 0.0
    xs, last, i = slip, table.shape[0] - 1, 0
    for k in range(last + 1):
        stop = n if k == last else _before(times, i, n, 0.0, table[k + 1, 0])
        t0, phase, switch = table[k, 0], table[k, 2], table[k, 3]
        w0, w1, s0, s1 = int(table[k, 4]), int(table[k, 5]), int(table[k, 6]), int(table[k, 7])
        start = i
        if w1 > w0:
            warped = stop if s1 == s0 else _before(times, i, stop, t0, switch)
            for j in range(w0, w1):
                end = warped if j + 1 == w1 else _warped_end(w_t, j + 1, i, warped, times, t0)
                span = (i, end, w_t[j], w_h[j])
                _interpolate(w_F, w_y, j, span, times, t0, first, states, xs)
                i = end
        for j in range(s0, s1):
            end = stop if j + 1 == s1 else _before(times, i, stop, 0.0, s_t[j + 1])
            _interpolate(s_F, s_y, j, (i, end, s_t[j], s_h[j]), times, math.nan, first, states, xs)
            i = end
        _forces(par, phase, start, stop, states, raw, normal, tangential, slip)
    return True


@njit(cache=True, error_model="numpy")
def grid(par, table, warp, steps, final, sample_rate, block):
    """An oblique impact's output grid, in one pass: times, the sampled contact, and after
    it the free flight.

    The times are ``arange(n) / sample_rate``; inside the contact (times before its end
    ``t1``) the states and forces come from :func:`sample`; after it the grain keeps its
    end velocities ``final[3:6]`` and no force acts. On a wall the grain's normal flight
    ``x2 = x2(t1) + v2(t1) (t - t1)`` is written here too; a sensor's plate rings, and the
    caller writes its four normal rows after the contact
    (:func:`contactlab.solver.oblique_phases.grid_signals`).

    Parameters
    ----------
    par, table, warp, steps
        The solved contact, as in :func:`sample`.
    final : numpy.ndarray
        State (7,) at the separation.
    sample_rate : float
        Output sample rate [Hz].
    block : numpy.ndarray
        Out (12, n): the states (rows 0-6), the normal law's unclipped formula, normal and
        tangential force [N], contact-point slip [m/s] and times [s] (rows 7-11).

    Returns
    -------
    int
        The number of samples inside the contact (the first after it).
    """
    n = block.shape[1]
    times = block[11]
    for i in range(n):
        times[i] = i
    for i in range(n):  # apart: a loop the compiler vectorises
        times[i] /= sample_rate
    end = table[table.shape[0] - 1, 1]
    inside = 0
    while inside < n and times[inside] < end:
        inside += 1
    if inside:
        raw, normal, tangential, slip = block[7], block[8], block[9], block[10]
        sample(par, table, warp, steps, times[:inside], block[:7], raw, normal, tangential, slip)
    after = slip_of(final, par)
    x2, v2, vt, w = final[2], final[3], final[4], final[5]
    rigid = par[RIGID] > 0.0
    if rigid:
        block[:2, inside:] = 0.0
        for m in range(inside, n):
            block[2, m] = (times[m] - end) * v2 + x2
        block[3, inside:] = v2
    block[4, inside:] = vt
    block[5, inside:] = w
    block[6:10, inside:] = 0.0
    block[10, inside:] = after
    return inside


@njit(cache=True, error_model="numpy")
def _scratch(n):
    """Out arrays of :func:`sample` for ``n`` times: states (7, n), then the unclipped
    normal formula, the normal and tangential forces and the slip (n,)."""
    return np.empty((7, n)), np.empty(n), np.empty(n), np.empty(n), np.empty(n)


@njit(cache=True, error_model="numpy")
def peak_forces(par, table, warp, steps, nodes):
    """Largest normal force and largest magnitude of the tangential force [N] on
    ``nodes`` times per phase, ``numpy.linspace(t0, t1, nodes, endpoint=False)`` of each,
    read on its own phase (arguments as :func:`sample`; a nan wins, as in ``max``).

    Phase by phase into one scratch of ``nodes`` samples: the 170 phases of a Kratos
    saw-tooth contact would otherwise allocate 7.7 MB a call, which the allocator maps
    and the first writes fault in."""
    times = np.empty(nodes)
    states, raw, normal, tangential, slip = _scratch(nodes)
    largest_normal, largest_tangential = -math.inf, -math.inf
    for k in range(table.shape[0]):
        t0, spacing = table[k, 0], (table[k, 1] - table[k, 0]) / nodes
        for m in range(nodes):
            times[m] = m * spacing + t0
        sample(par, table[k : k + 1], warp, steps, times, states, raw, normal, tangential, slip)
        largest_normal = _larger(largest_normal, normal.max())
        largest_tangential = _larger(largest_tangential, np.abs(tangential).max())
    return largest_normal, largest_tangential


@njit(cache=True, error_model="numpy")
def _larger(best, value):
    """The larger of ``best`` and ``value``; nan once either is nan."""
    return value if not math.isnan(best) and (value > best or math.isnan(value)) else best


@njit(cache=True, error_model="numpy")
def arm_moment(par, table, warp, steps, period):
    """``integral max(d, 0) F dt`` [N*m*s] over the contact: the overlap ``d`` [m] times
    the tangential force ``F`` [N], Gauss-Legendre phase by phase (arguments as
    :func:`sample`; rule of :mod:`contactlab.kernels.gauss`: 64 nodes a panel, panels at
    most ``period`` [s] long).

    With the lever arm ``R - d`` this is what the torque arm's shortening adds to
    ``I dw + m R dvt`` (:meth:`contactlab.ObliqueResult.audit`'s angular momentum).
    Inside a phase the integrand is smooth; it behaves like a fractional power of time
    only at the touch and the separation (the overlap's powers in the forces), so a
    phase's panels are graded towards its start when the touch lies within one phase
    length before it, towards its end when the separation lies within one phase length
    after it (the first and last phases always). Against every phase graded at both
    ends (the Python audit before, 15 panels a phase): within 1e-8 of the moment over
    104 impacts, at the dense output's own error (docs/architecture.md)."""
    total, end = 0.0, table[table.shape[0] - 1, 1]
    for k in range(table.shape[0]):
        t0, t1 = table[k, 0], table[k, 1]
        length = t1 - t0
        edges = panel_edges(length, period, t0 < length, end - t1 < length)
        nodes, weights = rule(t0, t1, edges)
        states, raw, normal, tangential, slip = _scratch(nodes.size)
        sample(par, table[k : k + 1], warp, steps, nodes, states, raw, normal, tangential, slip)
        for m in range(nodes.size):
            total += weights[m] * (max(states[2, m] - states[0, m], 0.0) * tangential[m])
    return total


@njit(cache=True, error_model="numpy")
def _beats(value, best):
    """Whether ``value`` replaces ``best`` as the largest: larger, or the first nan (which
    nothing replaces: ``numpy.argmax``'s rule)."""
    return value > best or (math.isnan(value) and not math.isnan(best))


@njit(cache=True, error_model="numpy")
def grid_worst(t, inside, raw, normal, tangential, friction):
    """The worst one-sided force and Coulomb excess on an output grid, in one pass.

    Parameters
    ----------
    t : numpy.ndarray
        Times [s].
    inside : int
        How many samples, from the first, lie inside the contact.
    raw, normal, tangential : numpy.ndarray
        The normal law's unclipped formula, the normal force and the tangential force [N].
    friction : float
        Coulomb friction coefficient [-].

    Returns
    -------
    tuple
        ``(largest -raw [N] inside, its time [s], largest |T| - friction N [N], its time
        [s])``: the first time of each largest value (nan wins, as in ``numpy.argmax``);
        ``-inf`` and nan where there are no samples.
    """
    one_sided, one_sided_at, excess, excess_at = -math.inf, math.nan, -math.inf, math.nan
    for i in range(t.size):
        if i < inside and _beats(-raw[i], one_sided):
            one_sided, one_sided_at = -raw[i], t[i]
        value = abs(tangential[i]) - friction * normal[i]
        if _beats(value, excess):
            excess, excess_at = value, t[i]
    return one_sided, one_sided_at, excess, excess_at


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
        contact-point slip [m/s] (n,) at non-decreasing ``times`` [s] inside the contact,
        into ``out`` if given (states (7, >= n), a row per component, and four (>= n,)
        arrays: the first n columns are written; the states come back as the transpose of
        the first n)."""
        times = np.ascontiguousarray(times, dtype=float)
        n = times.size
        if out is None:
            out = (np.empty((7, n)), *np.empty((4, n)))
        elif out[0].shape[0] != 7 or min(out[0].shape[1], *(a.size for a in out[1:])) < n:
            raise ParameterError(f"out must hold states (7, >= {n}) and four (>= {n},) arrays")
        if not sample(self._par, self._table, self._warp, self._steps, times, *out):
            raise ParameterError("times must be non-decreasing [s]")
        return (out[0][:, :n].T, *(a[:n] for a in out[1:]))

    def grid(self, final, sample_rate, block):
        """The output grid into ``block`` (12, n) (:func:`grid`); returns the number of
        samples inside the contact."""
        return grid(self._par, self._table, self._warp, self._steps, final, sample_rate, block)

    def arm_moment(self, period):
        """``integral max(d, 0) F dt`` [N*m*s] over the contact, Gauss-Legendre phase by
        phase with panels at most ``period`` [s] long (:func:`arm_moment`)."""
        return arm_moment(self._par, self._table, self._warp, self._steps, float(period))

    def peaks(self, nodes):
        """Largest normal force and largest magnitude of the tangential force [N] on
        ``nodes`` equally spaced times per phase (:func:`peak_forces`)."""
        return peak_forces(self._par, self._table, self._warp, self._steps, nodes)
