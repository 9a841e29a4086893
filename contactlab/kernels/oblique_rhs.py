"""Compiled (numba) right-hand side and event functions of the oblique impact.

The equations of :mod:`contactlab.solver.oblique` on the state ``y = [x1, v1, x2, v2, vt,
w, h]`` (a warped state carries ``s = tau**(1/4)`` as an eighth component, as in
:mod:`contactlab.kernels.power`): the normal side is the power-law contact of
:func:`contactlab.kernels.power.force`, the tangential side the law's
:class:`~contactlab.laws.tangential.TangentialForm`, the phase (stick 0, slide +1 or -1)
a field of the packed parameters. The parameters travel as one float array (:func:`pack`):
its first fields are those of :func:`contactlab.kernels.power.pack`, with the ``model``
field :data:`~contactlab.kernels.power.OBLIQUE_MODEL`, which tells the compiled DOP853
stepper to integrate these equations (:mod:`contactlab.kernels.model_rhs`).
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.power import C1, K1, M1, M2, MODEL, OBLIQUE_MODEL, RIGID, force, power
from contactlab.kernels.power import PARAMETERS as NORMAL_PARAMETERS

__all__ = [
    "OBLIQUE_PARAMETERS",
    "PHASE",
    "STICK",
    "contact_value",
    "direction",
    "elastic_force_rate",
    "events",
    "history_on_cap",
    "pack",
    "rhs",
    "slip",
    "trial_force",
]

OBLIQUE_PARAMETERS = (
    *NORMAL_PARAMETERS,
    "phase",
    "friction",
    "force_history",
    "rescaled",
    "kt",
    "kt_exponent",
    "eta",
    "eta_exponent",
    "radius",
    "inertia",
    "contact_arm",
)
"""Fields of the packed array of :func:`pack`, in order."""

(
    PHASE,
    FRICTION,
    FORCE_HISTORY,
    RESCALED,
    KT,
    KT_EXPONENT,
    ETA,
    ETA_EXPONENT,
    RADIUS,
    INERTIA,
    CONTACT_ARM,
) = range(len(NORMAL_PARAMETERS), len(OBLIQUE_PARAMETERS))
"""Indices of the oblique fields of :data:`OBLIQUE_PARAMETERS`."""

STICK = 0
"""Phase code of a sticking contact (sliding phases are +1 and -1, the sign of F)."""

DIFF_STEP = 1e-7
"""Relative step of the central differences of the normal law in :func:`slide_exit`."""


def pack(normal, tangential, radius, inertia, contact_arm):
    """Parameter array of the compiled oblique functions (phase 0: sticking).

    Parameters
    ----------
    normal : numpy.ndarray
        :func:`contactlab.kernels.power.pack` of the normal law and the system.
    tangential : contactlab.laws.tangential.TangentialForm
        The bound tangential law's formula.
    radius, inertia : float
        Grain radius [m] and moment of inertia [kg*m**2].
    contact_arm : bool
        Lever arm ``R - d`` (Kratos) instead of ``R``.
    """
    form = tangential
    normal = normal.copy()
    normal[MODEL] = OBLIQUE_MODEL
    return np.concatenate(
        (
            normal,
            [
                0.0,
                form.friction,
                1.0 if form.force_history else 0.0,
                1.0 if form.rescaled else 0.0,
                form.stiffness,
                form.stiffness_exponent,
                form.damping,
                form.damping_exponent,
                radius,
                inertia,
                1.0 if contact_arm else 0.0,
            ],
        )
    )


@njit(cache=True, error_model="numpy")
def _graded(d, coefficient, exponent):
    """``coefficient d**exponent``: a constant for exponent 0, else 0 at ``d <= 0``."""
    if exponent == 0.0:
        return coefficient
    if d <= 0.0 or coefficient == 0.0:
        return 0.0
    return coefficient * power(d, d, exponent, False)


@njit(cache=True, error_model="numpy")
def _graded_slope(d, coefficient, exponent):
    """d/dd of :func:`_graded`."""
    if exponent == 0.0 or d <= 0.0 or coefficient == 0.0:
        return 0.0
    if exponent == 0.5:
        return 0.5 * coefficient / math.sqrt(d)
    return exponent * coefficient * d ** (exponent - 1.0)


@njit(cache=True, error_model="numpy")
def arm(d, par):
    """Lever arm [m]: ``R`` or ``R - max(d, 0)``."""
    if par[CONTACT_ARM] > 0.0:
        return par[RADIUS] - max(d, 0.0)
    return par[RADIUS]


@njit(cache=True, error_model="numpy")
def slip(z, par):
    """Contact-point slip ``vt - arm w`` [m/s]."""
    return z[4] - arm(z[2] - z[0], par) * z[5]


@njit(cache=True, error_model="numpy")
def trial_force(h, d, s, par):
    """Tangential force before the Coulomb cap [N]
    (:meth:`~contactlab.laws.TangentialLaw.trial_force`)."""
    damping = _graded(d, par[ETA], par[ETA_EXPONENT]) * s
    if par[FORCE_HISTORY] > 0.0:
        return h - damping
    return -_graded(d, par[KT], par[KT_EXPONENT]) * h - damping


@njit(cache=True, error_model="numpy")
def history_rate(h, d, r, s, par):
    """``h'`` while sticking (:meth:`~contactlab.laws.TangentialLaw.history_rate`)."""
    if par[FORCE_HISTORY] == 0.0:
        return s
    rate = -_graded(d, par[KT], par[KT_EXPONENT]) * s
    if par[RESCALED] > 0.0 and r < 0.0 and d > 0.0:
        rate += h * r / (2.0 * d)
    return rate


@njit(cache=True, error_model="numpy")
def elastic_force_rate(h, d, r, s, par):
    """Time derivative of the elastic part of :func:`trial_force` along a sticking path
    [N/s] (:meth:`~contactlab.laws.TangentialLaw.elastic_force_rate`)."""
    if par[FORCE_HISTORY] > 0.0:
        return history_rate(h, d, r, s, par)
    elastic = -_graded(d, par[KT], par[KT_EXPONENT]) * s
    return elastic - _graded_slope(d, par[KT], par[KT_EXPONENT]) * r * h


@njit(cache=True, error_model="numpy")
def _trial_force_rate(h, d, r, s, s_rate, par):
    """Time derivative of :func:`trial_force` along a sticking path [N/s]."""
    elastic = elastic_force_rate(h, d, r, s, par)
    damping = _graded(d, par[ETA], par[ETA_EXPONENT]) * s_rate
    damping += _graded_slope(d, par[ETA], par[ETA_EXPONENT]) * r * s
    return elastic - damping


@njit(cache=True, error_model="numpy")
def history_on_cap(cap, d, s, par):
    """History that makes the trial force equal ``cap`` [N] (LAMMPS' rescaling; 0 where
    the stiffness vanishes)."""
    viscous = _graded(d, par[ETA], par[ETA_EXPONENT]) * s
    if par[FORCE_HISTORY] > 0.0:
        return cap + viscous
    kt = _graded(d, par[KT], par[KT_EXPONENT])
    return 0.0 if kt == 0.0 else -(cap + viscous) / kt


@njit(cache=True, error_model="numpy")
def _accelerations(x1, v1, n, par):
    """Sensor and grain normal accelerations [m/s**2] under the normal force ``n`` [N]."""
    a2 = -n / par[M2]
    if par[RIGID] > 0.0:
        return 0.0, a2
    return (n - par[K1] * x1 - par[C1] * v1) / par[M1], a2


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """``y' = f(y)`` in the phase ``par[PHASE]`` into ``out``, or ``dz/ds`` warped."""
    x1, v1, x2, v2, h = z[0], z[1], z[2], z[3], z[6]
    d, r = x2 - x1, v2 - v1
    n = force(d, r, par)
    lever = arm(d, par)
    s = z[4] - lever * z[5]
    phase = par[PHASE]
    if phase == STICK:
        tangential, dh = trial_force(h, d, s, par), history_rate(h, d, r, s, par)
    else:
        tangential, dh = phase * par[FRICTION] * max(n, 0.0), 0.0
    a1, a2 = _accelerations(x1, v1, n, par)
    out[0], out[1], out[2], out[3] = v1, a1, v2, a2
    out[4] = tangential / par[M2]
    out[5] = -lever * tangential / par[INERTIA]
    out[6] = dh
    if warped:
        w = 4.0 * z[7] ** 3
        for c in range(7):
            out[c] *= w
        out[7] = 1.0


@njit(cache=True, error_model="numpy")
def _normal_force_rate(d, r, r_rate, par):
    """dN/dt [N/s] from central differences of the normal law in overlap and rate."""
    hd = DIFF_STEP * abs(d) if d != 0.0 else 1e-300
    hr = DIFF_STEP * max(abs(r), 1e-12)
    n_d = (force(d + hd, r, par) - force(d - hd, r, par)) / (2.0 * hd)
    n_r = (force(d, r + hr, par) - force(d, r - hr, par)) / (2.0 * hr)
    return n_d * r + n_r * r_rate


@njit(cache=True, error_model="numpy")
def slide_exit(phase, z, par):
    """``sigma dF_trial/dt - mu dN/dt`` [N/s] along a sticking path from the sliding state
    ``z``: sliding goes on while >= 0 (see :mod:`contactlab.solver.oblique`)."""
    x1, v1, x2, v2, vt, w = z[0], z[1], z[2], z[3], z[4], z[5]
    d, r = x2 - x1, v2 - v1
    n = force(d, r, par)
    mu = par[FRICTION]
    cap = phase * mu * max(n, 0.0)
    lever = arm(d, par)
    s = vt - lever * w
    a1, a2 = _accelerations(x1, v1, n, par)
    h = history_on_cap(cap, d, s, par)
    # s' = F (1/m + arm**2/I) - arm' w, and arm' = -d' for the contact arm
    s_rate = cap * (1.0 / par[M2] + lever**2 / par[INERTIA])
    if par[CONTACT_ARM] > 0.0:
        s_rate += r * w
    rate = _trial_force_rate(h, d, r, s, s_rate, par)
    return phase * rate - mu * _normal_force_rate(d, r, a2 - a1, par)


@njit(cache=True, error_model="numpy")
def contact_value(n, d):
    """Contact-end event value: the normal force ``n`` [N] while the overlap ``d`` [m] is
    positive, a negative value once it is not (one-sided contact; Hunt-Crossley's factor
    that never reaches zero on unloading, issue 21)."""
    return n if d > 0.0 else min(n, 0.0) + d


@njit(cache=True, error_model="numpy")
def direction(j, phase):
    """Crossing direction of event ``j`` (:func:`contactlab.roots.crosses`): the contact
    end falls, the Coulomb limits of a sticking contact rise, the end of sliding falls."""
    return 1 if j > 0 and phase == STICK else -1


@njit(cache=True, error_model="numpy")
def events(z, par, phase, out):
    """Event values into ``out``; returns how many the phase has.

    Event 0 is the contact end; sticking, events 1 and 2 are the trial force reaching
    ``+mu N`` and ``-mu N``; sliding, event 1 is the end of sliding (:func:`slide_exit`).
    """
    d, r = z[2] - z[0], z[3] - z[1]
    n = force(d, r, par)
    out[0] = contact_value(n, d)
    if phase == STICK:
        tangential = trial_force(z[6], d, slip(z, par), par)
        mu = par[FRICTION]
        out[1] = tangential - mu * n
        out[2] = -tangential - mu * n
        return 3
    out[1] = slide_exit(phase, z, par)
    return 2
