"""DOP853 compiled with numba: the lean stepper of :mod:`contactlab.solver.dop853`, step
for step, for the power-law contact of :mod:`contactlab.kernels.power` and the oblique
impact of :mod:`contactlab.kernels.oblique_rhs` (:mod:`contactlab.kernels.model_rhs`).

The Python :class:`~contactlab.solver.dop853.Stepper` spends its time in interpreter
overhead: twelve small numpy operations per stage on a four-component state. The same
method here (scipy's coefficient tables, error norm, step-size control and Hairer's
initial step) costs about a microsecond per step. The dense output of each step
(:func:`interpolant`) has the Python stepper's layout, so
:class:`~contactlab.kernels.segments.DenseSteps` reads both; :func:`dense_states` is its
compiled evaluation on many times.

References
----------
Hairer E., Norsett S.P., Wanner G. (1993) Solving Ordinary Differential Equations I:
Nonstiff Problems, 2nd ed., Springer, Sec. II.4-II.6. scipy.integrate.DOP853.
"""

import math

import numpy as np
from scipy.integrate import DOP853 as _SCIPY

from contactlab.compiled import njit
from contactlab.kernels.model_rhs import NORMAL, rhs
from contactlab.kernels.power import rhs_row as power_rhs

__all__ = [
    "STAGES",
    "WORK_ROWS",
    "dense_states",
    "initial_step",
    "interpolant",
    "interpolate",
    "step",
]

STAGES = _SCIPY.n_stages
"""Stages of a DOP853 step (12); three more make the dense output."""

_DENSE_STAGES = STAGES + 1 + _SCIPY.A_EXTRA.shape[0]
"""Rows of the stage array: the stages, the slope at the step's end, three extra."""

WORK_ROWS = _DENSE_STAGES + 2
"""Rows of the work array ``K`` of :func:`step` and :func:`interpolant`: the stages
(:data:`STAGES` + 4) and two scratch rows, so that no step allocates memory."""

_TMP, _SCALE = _DENSE_STAGES, _DENSE_STAGES + 1
"""The scratch rows of ``K``: a stage's state, the error's scale. They are read by row
index, not through row views: a view costs a reference-count increment and decrement,
and its presence kept numba from pruning those of the step's arguments (18 a step)."""

_A = np.ascontiguousarray(_SCIPY.A, dtype=np.float64)
_B = np.ascontiguousarray(_SCIPY.B[np.newaxis], dtype=np.float64)
_E3 = np.ascontiguousarray(_SCIPY.E3, dtype=np.float64)
_E5 = np.ascontiguousarray(_SCIPY.E5, dtype=np.float64)
_D = np.ascontiguousarray(_SCIPY.D, dtype=np.float64)
_A_EXTRA = np.ascontiguousarray(_SCIPY.A_EXTRA, dtype=np.float64)
_EXTRA = _A_EXTRA.shape[0]
_ORDER = _SCIPY.error_estimator_order
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
_EXPONENT = -1.0 / (_ORDER + 1)


@njit(cache=True, error_model="numpy")
def _rms(x, scale):
    total = 0.0
    for i in range(x.size):
        total += (x[i] / scale[i]) ** 2
    return math.sqrt(total / x.size)


@njit(cache=True, error_model="numpy")
def initial_step(y, f, rtol, atol, par, warped):
    """Hairer's starting step (Sec. II.4), as :meth:`Stepper.initial_step`."""
    n = y.size
    scale = atol + np.abs(y) * rtol
    d0, d1 = _rms(y, scale), _rms(f, scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    f1 = np.empty(n)
    rhs(y + h0 * f, par, warped, f1)
    d2 = _rms(f1 - f, scale) / h0
    if max(d1, d2) <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (_ORDER + 1))
    return min(100.0 * h0, h1)


@njit(cache=True, error_model="numpy", inline="always")
def _stage_state(y, h, table, row, K, stages):
    """``K[_TMP] = y + h (table[row, :stages] @ K[:stages])``: a stage's state."""
    for c in range(y.size):
        acc = 0.0
        for s in range(stages):
            acc += table[row, s] * K[s, c]
        K[_TMP, c] = y[c] + h * acc


@njit(cache=True, error_model="numpy", inline="always")
def _error_norm(K, h, separate):
    """The step's error norm: scipy's (and Hairer's ``DOP853``) combination of the 5th- and
    3rd-order estimates over all components, or, with ``separate``, the same combination
    per component, then their rms (:meth:`contactlab.solver.dop853.Stepper.error_norm`),
    with the scale in ``K[_SCALE]``."""
    n = K.shape[1]
    e5 = e3 = total = 0.0
    for c in range(n):
        a5 = a3 = 0.0
        for s in range(STAGES + 1):
            a5 += _E5[s] * K[s, c]
            a3 += _E3[s] * K[s, c]
        a5, a3 = (a5 / K[_SCALE, c]) ** 2, (a3 / K[_SCALE, c]) ** 2
        e5 += a5
        e3 += a3
        if separate and a5 > 0.0:
            total += a5 * a5 / (a5 + 0.01 * a3)
    if separate:
        return abs(h) * math.sqrt(total / n)
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True, error_model="numpy", borrowed=True)
def step(t, y, f, h_try, t_bound, rtol, atol, par, warped, K, y_new, f_new, model):
    """One accepted step from ``(t, y)`` with ``f = f(y)``, not beyond ``t_bound``.

    Writes the new state and its slope into ``y_new`` and ``f_new`` and the stages into
    ``K`` ((:data:`WORK_ROWS`, n): rows 0..12 kept for :func:`interpolant`, the last two
    scratch). ``model`` is :data:`~contactlab.kernels.model_rhs.NORMAL` (the normal
    contact's :func:`contactlab.kernels.power.rhs`) or
    :data:`~contactlab.kernels.model_rhs.ANY_MODEL` (:func:`contactlab.kernels.model_rhs.rhs`),
    a constant where compiled (see :mod:`contactlab.kernels.model_rhs`).

    Returns
    -------
    (bool, float, float, float)
        Whether a step was made (False: the step size underflowed), the new time, the
        step size to try next and the step taken.
    """
    n = y.size
    min_step = 10.0 * abs(np.nextafter(t, math.inf) - t)
    h = max(h_try, min_step)
    rejected = False
    while True:
        if h < min_step:
            return False, t, h, 0.0
        t_new = min(t + h, t_bound)
        h = t_new - t
        for c in range(n):  # not K[0, :] = f: a slice copy checks overlap and allocates
            K[0, c] = f[c]
        for s in range(1, STAGES):
            _stage_state(y, h, _A, s, K, s)
            if model == NORMAL:  # a constant: numba keeps one branch (model_rhs)
                power_rhs(K, _TMP, par, warped, K, s)
            else:
                rhs(K[_TMP], par, warped, K[s])
        _stage_state(y, h, _B, 0, K, STAGES)
        if model == NORMAL:
            power_rhs(K, _TMP, par, warped, K, STAGES)
        else:
            rhs(K[_TMP], par, warped, K[STAGES])
        for c in range(n):
            y_new[c], f_new[c] = K[_TMP, c], K[STAGES, c]
            K[_SCALE, c] = atol[c] + max(abs(y[c]), abs(y_new[c])) * rtol
        error = _error_norm(K, h, warped)  # per component in s: Stepper.error_norm
        if error < 1.0:
            if error == 0.0:
                factor = _MAX_FACTOR
            else:
                factor = min(_MAX_FACTOR, _SAFETY * error**_EXPONENT)
            h_next = h * (min(1.0, factor) if rejected else factor)
            return True, t_new, h_next, h
        h *= max(_MIN_FACTOR, _SAFETY * error**_EXPONENT)
        rejected = True


@njit(cache=True, error_model="numpy", borrowed=True)
def interpolant(K, h, y_old, y, f_new, par, warped, F, model):
    """The step's 7th-order interpolant coefficients into ``F`` (7, n), as
    :meth:`Stepper.interpolant` (three extra stages into ``K``; ``model`` as in
    :func:`step`)."""
    n = y.size
    for i in range(_EXTRA):
        stage = STAGES + 1 + i
        _stage_state(y_old, h, _A_EXTRA, i, K, stage)
        if model == NORMAL:  # as in step
            power_rhs(K, _TMP, par, warped, K, stage)
        else:
            rhs(K[_TMP], par, warped, K[stage])
    for c in range(n):
        delta = y[c] - y_old[c]
        F[0, c] = delta
        F[1, c] = h * K[0, c] - delta
        F[2, c] = 2.0 * delta - h * (f_new[c] + K[0, c])
        for row in range(_D.shape[0]):
            acc = 0.0
            for s in range(_DENSE_STAGES):
                acc += _D[row, s] * K[s, c]
            F[3 + row, c] = h * acc


@njit(cache=True, error_model="numpy", inline="always")
def interpolate(F, y_old, x, out):
    """A step's interpolant at ``x = (t - t_old) / h`` into ``out``, as
    :func:`contactlab.kernels.segments.interpolate`."""
    rows = F.shape[0]
    for c in range(y_old.size):
        acc = 0.0
        for k in range(rows):
            acc += F[rows - 1 - k, c]
            acc *= x if k % 2 == 0 else 1.0 - x
        out[c] = acc + y_old[c]


@njit(cache=True, error_model="numpy", nogil=True)
def dense_states(t_old, h, y_old, F, times, out):
    """States at ``times`` [s] from per-step interpolants into ``out`` (len(times), n).

    ``F`` has the layout of :class:`~contactlab.kernels.segments.DenseSteps` (7, steps, n);
    a time before the first step or after the last is read on the nearest step, as the
    Python evaluation does.
    """
    last = h.size - 1
    rows, n = F.shape[0], y_old.shape[1]
    for i in range(times.size):
        j = min(max(np.searchsorted(t_old, times[i], side="right") - 1, 0), last)
        x = (times[i] - t_old[j]) / h[j]
        for c in range(n):  # interpolate(F[:, j], ...) inlined: a view a sample is slow
            acc = 0.0
            for k in range(rows):
                acc += F[rows - 1 - k, j, c]
                acc *= x if k % 2 == 0 else 1.0 - x
            out[i, c] = acc + y_old[j, c]
