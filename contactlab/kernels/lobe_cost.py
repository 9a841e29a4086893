"""The lobe fit's residual compiled: the whitened unit signal, its amplitude fitted off
the drift line and the residual sum of squares, in one call per onset (or per scan).

:class:`contactlab.inverse.lobe_model.LobeModel` fits ``A h((t - t0) / tau)`` through
the sensor plus a line to a window by variable projection: for each ``(t0, tau)`` that
Nelder-Mead or the onset scan tries, the unit signal (:func:`~contactlab.kernels.
held_force.held_signal`) is whitened by the record's autoregressive filter, sampled at
the window's times (:func:`~contactlab.kernels.held_force.sampled_signal`), projected off
the line's orthonormal basis, and the amplitude and the residual follow by two dot
products. In numpy each of those steps was a call with its own overhead, and the scans
looped over onsets in Python: about 90 us an evaluation, 14 000 evaluations and 42 000
scanned onsets on the 1.5 M-sample realistic record (``benchmarks/bench_family_read.py``).

The whitening and the sampling are the numpy code's element-wise arithmetic in its order
(equal to the last bit); the projection and the dot products are sums in a loop, not
BLAS's blocked sums, so the residual differs from the numpy one in its last bits
(``tests/contactlab/inverse/test_lobe_cost.py`` bounds it).
"""

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels.held_force import held_signal, sampled_signal

__all__ = ["fitted_rss", "scanned_rss", "white_signal"]


@njit(cache=True, error_model="numpy")
def white_signal(r, ar, fine):
    """``r(s) - sum_k ar[k - 1] r(s - k dt)`` on the fine grid, the sample step ``dt``
    being ``fine`` grid steps and ``r`` zero before its start (numpy's slice arithmetic,
    one coefficient after the other).

    Parameters
    ----------
    r : numpy.ndarray
        The unit signal on its fine grid [-].
    ar : numpy.ndarray
        The autoregressive coefficients of the record's noise [-] (empty: white).
    fine : int
        Fine grid steps per sample [-].

    Returns
    -------
    numpy.ndarray
        The whitened signal [-].
    """
    white = r.copy()
    for k in range(ar.size):
        shift = (k + 1) * fine
        a = ar[k]
        for i in range(r.size - 1, shift - 1, -1):
            white[i] = white[i] - a * r[i - shift]
    return white


@njit(cache=True, error_model="numpy")
def _projected(values, skip, basis, y_off, y_rss):
    """Amplitude and residual sum of squares of ``values[skip:]`` fitted to ``y`` off the
    basis' span (``y_off``: ``y`` projected off it; ``y_rss``: its sum of squares);
    ``(nan, inf)`` where the signal has no part off the span."""
    n = values.size - skip
    c0 = 0.0
    c1 = 0.0
    for i in range(n):
        c0 += basis[i, 0] * values[skip + i]
        c1 += basis[i, 1] * values[skip + i]
    norm = 0.0
    dot = 0.0
    for i in range(n):
        off = values[skip + i] - (basis[i, 0] * c0 + basis[i, 1] * c1)
        norm += off * off
        dot += off * y_off[i]
    if not norm > 0.0:  # no force inside the window
        return np.nan, np.inf
    amplitude = dot / norm
    return amplitude, max(y_rss - amplitude * amplitude * norm, 0.0)


@njit(cache=True, error_model="numpy")
def scanned_rss(t, onsets, s, r, skip, basis, y_off, y_rss):
    """The residual sum of squares at each onset of a scan, one unit signal.

    Parameters
    ----------
    t : numpy.ndarray
        The window's sample times [s].
    onsets : numpy.ndarray
        The force's starts tried [s].
    s, r : numpy.ndarray
        The whitened unit signal's grid [s] and values [-] (:func:`white_signal`).
    skip : int
        Samples the whitening filter needs before the window (its order) [-].
    basis : numpy.ndarray
        Orthonormal basis of the whitened drift line, ``(samples - skip, 2)`` [-].
    y_off : numpy.ndarray
        The whitened record projected off ``basis`` [N].
    y_rss : float
        Its sum of squares [N**2].

    Returns
    -------
    numpy.ndarray
        The residual sum of squares at each onset [N**2]; ``inf`` where no force lies
        inside the window.
    """
    rss = np.empty(onsets.size)
    for k in range(onsets.size):
        rss[k] = _projected(sampled_signal(t, onsets[k], s, r), skip, basis, y_off, y_rss)[1]
    return rss


@njit(cache=True, error_model="numpy")
def fitted_rss(t0, tau, t, step, count, u, h, b, a, ar, fine, basis, y_off, y_rss):
    """Amplitude [N] and residual sum of squares [N**2] of one ``(t0, tau)`` [s] on the
    window's times ``t`` [s]: the unit signal of ``tau``
    (:func:`~contactlab.kernels.held_force.held_signal` with ``step``, ``count``, the
    shape ``u, h`` and the sensor's filter ``b, a``), whitened by ``ar`` (:func:`white_signal`
    with ``fine``), sampled at ``t - t0`` and fitted off the drift line as in
    :func:`scanned_rss` (``skip`` is ``ar``'s order). ``(nan, inf)`` where no force lies
    inside the window."""
    s, r = held_signal(step, count, tau, u, h, b, a)
    white = white_signal(r, ar, fine)
    return _projected(sampled_signal(t, t0, s, white), ar.size, basis, y_off, y_rss)


@njit(cache=True, error_model="numpy")
def _rss_at(x0, x1, t, step, count, u, h, b, a, ar, fine, basis, y_off, y_rss):
    """:meth:`~contactlab.inverse.lobe_model.LobeModel.rss`: ``inf`` where the duration
    ``x1`` is not positive."""
    if not x1 > 0.0:
        return np.inf
    return fitted_rss(x0, x1, t, step, count, u, h, b, a, ar, fine, basis, y_off, y_rss)[1]


@njit(cache=True)
def _sorted(sim, fsim):
    """The simplex and its values sorted by value, as ``numpy.argsort`` (introsort: an
    insertion sort on three, stable; NaN last) and ``numpy.take`` order them."""
    order = np.arange(fsim.size)
    for i in range(1, fsim.size):
        k = order[i]
        j = i - 1
        while j >= 0 and (
            fsim[k] < fsim[order[j]] or (fsim[order[j]] != fsim[order[j]] and fsim[k] == fsim[k])
        ):
            order[j + 1] = order[j]
            j -= 1
        order[j + 1] = k
    return sim[order].copy(), fsim[order].copy()


@njit(cache=True)
def _spread(values):
    """``numpy.max(numpy.abs(values))``, NaN if any is NaN."""
    largest = 0.0
    for v in values.ravel():
        if v != v:
            return np.nan
        largest = max(largest, abs(v))
    return largest


@njit(cache=True, error_model="numpy")
def simplex_fit(simplex, xatol, fatol, maxfun, problem):
    """``scipy.optimize.minimize(rss, simplex[0], method="Nelder-Mead",
    options={"initial_simplex": simplex, "xatol": xatol, "fatol": fatol})`` of the lobe
    fit's residual (:func:`fitted_rss`) over the onset and duration, in one compiled
    call: scipy's algorithm (reflection 1, expansion 2, contraction 0.5, shrink 0.5, its
    stopping tests and its ``maxfun = maxiter`` of 200 per variable, its order of
    operations and of the sorted vertices), so that its result is scipy's to the last
    bit (``tests/contactlab/inverse/test_lobe_cost.py``).

    Parameters
    ----------
    simplex : numpy.ndarray
        ``(3, 2)`` starting vertices ``(t0 [s], tau [s])``.
    xatol : float
        Largest spread of the vertices at convergence [s].
    fatol : float
        Largest spread of their residuals at convergence [N**2].
    maxfun : int
        Most residuals evaluated (and iterations) [-].
    problem : tuple
        The arguments of :func:`fitted_rss` after ``(t0, tau)``.

    Returns
    -------
    x : numpy.ndarray
        The best vertex ``(t0, tau)``.
    fun : float
        Its residual sum of squares [N**2].
    """
    sim = simplex.copy()
    fsim = np.full(3, np.inf)
    calls = 0
    for k in range(3):
        if calls >= maxfun:
            break
        calls += 1
        fsim[k] = _rss_at(sim[k, 0], sim[k, 1], *problem)
    sim, fsim = _sorted(sim, fsim)
    sim, fsim = _sorted(sim, fsim)
    iterations = 1
    while calls < maxfun and iterations < maxfun:
        if _spread(sim[1:] - sim[0]) <= xatol and _spread(fsim[0] - fsim[1:]) <= fatol:
            break
        out = False  # scipy's _MaxFuncCallError: the iteration stops where it is
        xbar = (sim[0] + sim[1]) / 2
        worst = sim[2].copy()
        xr = 2 * xbar - worst
        if calls >= maxfun:
            out = True
        else:
            calls += 1
            fxr = _rss_at(xr[0], xr[1], *problem)
            if fxr < fsim[0]:
                xe = 3 * xbar - 2 * worst
                if calls >= maxfun:
                    out = True
                else:
                    calls += 1
                    fxe = _rss_at(xe[0], xe[1], *problem)
                    if fxe < fxr:
                        sim[2], fsim[2] = xe, fxe
                    else:
                        sim[2], fsim[2] = xr, fxr
            elif fxr < fsim[1]:
                sim[2], fsim[2] = xr, fxr
            else:
                shrink = False
                outside = fxr < fsim[2]  # the contraction: outside, else inside
                xc = 1.5 * xbar - 0.5 * worst if outside else 0.5 * xbar + 0.5 * worst
                if calls >= maxfun:
                    out = True
                else:
                    calls += 1
                    fxc = _rss_at(xc[0], xc[1], *problem)
                    accepted = fxc <= fxr if outside else fxc < fsim[2]  # scipy's tests
                    if accepted:
                        sim[2], fsim[2] = xc, fxc
                    else:
                        shrink = True
                if shrink:
                    for j in range(1, 3):
                        sim[j] = sim[0] + 0.5 * (sim[j] - sim[0])
                        if calls >= maxfun:
                            out = True
                            break
                        calls += 1
                        fsim[j] = _rss_at(sim[j, 0], sim[j, 1], *problem)
        if not out:
            iterations += 1
        sim, fsim = _sorted(sim, fsim)
    return sim[0].copy(), np.min(fsim)
