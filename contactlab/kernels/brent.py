"""Brent's root finder for compiled kernels, driven one function value at a time.

The batch kernels locate events and crossings with the same method and tolerance as the
single-impact solver (:func:`contactlab.roots.locate_root`, scipy's ``brentq`` with
``xtol = 1e-300`` and ``rtol = 4 eps``). Compiled code cannot call scipy, and a compiled
function that takes another function as an argument cannot be cached on disk, so the
algorithm is written in *reverse communication*: :func:`brent_start` and
:func:`brent_next` return the next abscissa to evaluate and whether the root is found,
and the caller evaluates its own function in between::

    x, done = brent_start(work, lo, f_lo, hi, f_hi)
    while not done:
        x, done = brent_next(work, f(x))

References
----------
Brent R.P. (1973) Algorithms for Minimization without Derivatives, Prentice-Hall, ch. 4.
scipy/optimize/Zeros/brentq.c (the variant ported here, step by step).
"""

import math

from contactlab.compiled import njit
from contactlab.roots import ROOT_RTOL

__all__ = ["ROOT_XTOL", "WORK_SIZE", "brent_next", "brent_start"]

ROOT_XTOL = 1e-300
"""Absolute tolerance [s], as :func:`contactlab.roots.locate_root` passes to brentq."""

WORK_SIZE = 9
"""Length of the work array the caller provides (float64)."""

MAX_ITERATIONS = 1000
"""Iteration cap, as :data:`contactlab.roots._ROOT_ITERATIONS`."""

_PRE, _CUR, _BLK, _FPRE, _FCUR, _FBLK, _SPRE, _SCUR, _COUNT = range(WORK_SIZE)


@njit(cache=True, error_model="numpy")
def brent_start(work, xa, fa, xb, fb):
    """Start a search on the bracket ``[xa, xb]`` with the function values at its ends.

    Returns
    -------
    (float, bool)
        The next abscissa, and whether it is already the root.
    """
    if fa == 0.0:
        return xa, True
    if fb == 0.0:
        return xb, True
    work[_PRE], work[_CUR], work[_BLK] = xa, xb, 0.0
    work[_FPRE], work[_FCUR], work[_FBLK] = fa, fb, 0.0
    work[_SPRE], work[_SCUR], work[_COUNT] = 0.0, 0.0, 0.0
    return _iterate(work)


@njit(cache=True, error_model="numpy")
def brent_next(work, f_new):
    """Continue a search with the function value at the abscissa last returned."""
    work[_FCUR] = f_new
    work[_COUNT] += 1.0
    if work[_COUNT] >= MAX_ITERATIONS:
        return work[_CUR], True
    return _iterate(work)


@njit(cache=True, error_model="numpy")
def _iterate(work):
    xpre, xcur, xblk = work[_PRE], work[_CUR], work[_BLK]
    fpre, fcur, fblk = work[_FPRE], work[_FCUR], work[_FBLK]
    spre, scur = work[_SPRE], work[_SCUR]
    if fpre != 0.0 and fcur != 0.0 and (math.copysign(1.0, fpre) != math.copysign(1.0, fcur)):
        xblk, fblk = xpre, fpre
        spre = scur = xcur - xpre
    if abs(fblk) < abs(fcur):
        xpre, xcur, xblk = xcur, xblk, xcur
        fpre, fcur, fblk = fcur, fblk, fcur
    delta = (ROOT_XTOL + ROOT_RTOL * abs(xcur)) / 2.0
    sbis = (xblk - xcur) / 2.0
    if fcur == 0.0 or abs(sbis) < delta:
        return xcur, True
    if abs(spre) > delta and abs(fcur) < abs(fpre):
        if xpre == xblk:  # interpolate
            stry = -fcur * (xcur - xpre) / (fcur - fpre)
        else:  # extrapolate
            dpre = (fpre - fcur) / (xpre - xcur)
            dblk = (fblk - fcur) / (xblk - xcur)
            stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
        if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
            spre, scur = scur, stry  # good short step
        else:
            spre = scur = sbis
    else:
        spre = scur = sbis
    xpre, fpre = xcur, fcur
    xcur += scur if abs(scur) > delta else (delta if sbis > 0.0 else -delta)
    work[_PRE], work[_CUR], work[_BLK] = xpre, xcur, xblk
    work[_FPRE], work[_FCUR], work[_FBLK] = fpre, fcur, fblk
    work[_SPRE], work[_SCUR] = spre, scur
    return xcur, False
