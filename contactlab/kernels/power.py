"""Compiled (numba) contact force and right-hand side of the two-mass system under a
power-law contact.

Every Hertz-family law of :mod:`contactlab.laws` is one formula in overlap ``d`` [m] and
rate ``d'`` [m/s] (:class:`contactlab.laws.base.PowerForm`)::

    S2 = a sign(d) |d|**p + b D(d) d',   D(d) = |d|**q  (or sign(d) |d|**q if signed)

so one compiled right-hand side serves elastic Hertz (``b = 0``), Tsuji's damped Hertz
(``q = 1/4``), Kuwabara-Kono (``q = 1/2``) and Hunt-Crossley (``q = p``, signed). The
parameters travel as one float array (:func:`pack`), which keeps every compiled function
cacheable on disk (a compiled function that takes another function as an argument is
not).

State ``y = [x1, v1, x2, v2]`` as everywhere in :mod:`contactlab.solver`; a warped
state carries ``s = tau**(1/4)`` as a fifth component (see
:func:`contactlab.solver.adaptive.adaptive_contact`).
"""

import math

import numpy as np

from contactlab.compiled import njit

__all__ = [
    "C1",
    "DAMPING",
    "DAMPING_EXPONENT",
    "EXPONENT",
    "K1",
    "M1",
    "M2",
    "MODEL",
    "NORMAL_MODEL",
    "OBLIQUE_MODEL",
    "PARAMETERS",
    "RIGID",
    "SIGNED_DAMPING",
    "STIFFNESS",
    "force",
    "force_floor",
    "pack",
    "power",
    "rhs",
    "rhs_row",
]

PARAMETERS = ("a", "p", "b", "q", "signed", "m1", "k1", "c1", "m2", "rigid", "model")
"""Fields of the packed parameter array, in order (:func:`pack`); ``model`` says which
equations the compiled stepper integrates (:mod:`contactlab.kernels.model_rhs`)."""

(
    STIFFNESS,
    EXPONENT,
    DAMPING,
    DAMPING_EXPONENT,
    SIGNED_DAMPING,
    M1,
    K1,
    C1,
    M2,
    RIGID,
    MODEL,
) = range(len(PARAMETERS))
"""Indices of the fields of :data:`PARAMETERS` in the packed array."""

NORMAL_MODEL, OBLIQUE_MODEL = 0.0, 1.0
"""Values of the ``model`` field: the normal contact's equations (:func:`rhs`), or the
oblique impact's (:func:`contactlab.kernels.oblique_rhs.rhs`)."""


def pack(form, m1, k1, c1, m2, rigid):
    """Parameter array of the compiled functions.

    Parameters
    ----------
    form : contactlab.laws.base.PowerForm
        The contact law's formula.
    m1, k1, c1 : float
        Sensor moving mass [kg], stiffness [N/m], damping [N*s/m] (unused on a wall).
    m2 : float
        Grain mass [kg].
    rigid : bool
        Immovable wall (``x1 = v1 = 0`` throughout).

    Returns
    -------
    numpy.ndarray
        float64, ordered as :data:`PARAMETERS`.
    """
    return np.array(
        [
            form.stiffness,
            form.exponent,
            form.damping,
            form.damping_exponent,
            1.0 if form.signed_damping else 0.0,
            m1,
            k1,
            c1,
            m2,
            1.0 if rigid else 0.0,
            NORMAL_MODEL,
        ]
    )


@njit(cache=True, error_model="numpy", inline="always")
def _rooted(d, ad, root, p, signed):
    """:func:`power` given ``root = sqrt(|d|)``, which the common exponents share."""
    if p == 0.0:
        value = 1.0
    elif p == 1.0:
        value = ad
    elif p == 0.5:
        value = root
    elif p == 0.25:
        value = math.sqrt(root)
    elif p == 1.5:
        value = ad * root
    else:
        value = ad**p
    return math.copysign(value, d) if signed else value


@njit(cache=True, error_model="numpy")
def power(d, ad, p, signed):
    """``|d|**p``, or ``sign(d) |d|**p`` if signed, with the common exponents by roots."""
    return _rooted(d, ad, math.sqrt(ad), p, signed)


@njit(cache=True, error_model="numpy")
def force(d, r, par):
    """Contact-force formula [N] at overlap ``d`` [m] and rate ``r`` [m/s], not clipped
    (it turns negative where the contact would pull: the contact ends there). The two
    powers share one square root of the overlap (Hertz ``d**1.5`` with ``d**0.25`` or
    ``d**0.5`` damping: two roots a call where there were three)."""
    ad = abs(d)
    root = math.sqrt(ad)
    elastic = par[STIFFNESS] * _rooted(d, ad, root, par[EXPONENT], True)
    if par[DAMPING] == 0.0:
        return elastic
    signed = par[SIGNED_DAMPING] > 0.0
    return elastic + par[DAMPING] * _rooted(d, ad, root, par[DAMPING_EXPONENT], signed) * r


@njit(cache=True, error_model="numpy")
def force_floor(d_lo, d_hi, r_lo, r_hi, par):
    """Lower bound [N] of :func:`force` over overlaps ``d_lo <= d <= d_hi`` [m] and rates
    ``r_lo <= r <= r_hi`` [m/s], and the force's size there [N] (``|a| d_hi**p + |b|
    D(d_hi) max |r|``); the bound is ``-inf`` unless ``d_lo > 0``.

    For ``d > 0`` both ``d**p`` and ``D(d)`` grow with ``d`` (``p, q >= 0``), so the
    elastic term is least at an end of the overlaps and the damping term ``b D(d) r``,
    bilinear in ``(D, r)``, at a corner of the box.
    """
    if not d_lo > 0.0:
        return -math.inf, 0.0
    a, b = par[STIFFNESS], par[DAMPING]
    p, q, signed = par[EXPONENT], par[DAMPING_EXPONENT], par[SIGNED_DAMPING] > 0.0
    e_lo, e_hi = a * power(d_lo, d_lo, p, True), a * power(d_hi, d_hi, p, True)
    size = max(abs(e_lo), abs(e_hi))
    floor = min(e_lo, e_hi)
    if b != 0.0:
        g_lo, g_hi = b * power(d_lo, d_lo, q, signed), b * power(d_hi, d_hi, q, signed)
        floor += min(g_lo * r_lo, g_lo * r_hi, g_hi * r_lo, g_hi * r_hi)
        size += max(abs(g_lo), abs(g_hi)) * max(abs(r_lo), abs(r_hi))
    return floor, size


@njit(cache=True, error_model="numpy", borrowed=True)
def rhs_row(z, z_row, par, warped, out, row):
    """Right-hand side at the state ``z[z_row]`` into ``out[row]`` (both 2-D): ``y' =
    f(y)``, or ``dz/ds`` in the warped variable (``dy/ds = 4 s**3 f(y)``, ``ds/ds = 1``).

    The compiled stepper reads and writes its stages so (:mod:`contactlab.kernels.dop853`):
    a row view per stage cost a reference-count increment and decrement, 30 a
    damped-Hertz step.
    """
    x1, v1, x2, v2 = z[z_row, 0], z[z_row, 1], z[z_row, 2], z[z_row, 3]
    s2 = force(x2 - x1, v2 - v1, par)
    if par[RIGID] > 0.0:
        out[row, 0], out[row, 1] = 0.0, 0.0
    else:
        out[row, 0] = v1
        out[row, 1] = (s2 - par[K1] * x1 - par[C1] * v1) / par[M1]
    out[row, 2] = v2
    out[row, 3] = -s2 / par[M2]
    if warped:
        w = 4.0 * z[z_row, 4] ** 3
        for c in range(4):
            out[row, c] *= w
        out[row, 4] = 1.0


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """Right-hand side into ``out`` (:func:`rhs_row` into a 1-D array)."""
    rhs_row(z.reshape((1, z.size)), 0, par, warped, out.reshape((1, out.size)), 0)
