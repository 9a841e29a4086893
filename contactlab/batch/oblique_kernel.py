"""Compiled kernel of the batched oblique impacts: rows through the single solver's loop.

Every row is packed into the parameters of :func:`contactlab.kernels.oblique_rhs.pack`
(Tsuji's damped Hertz normal law, :class:`~contactlab.laws.Mindlin` tangential law) and
solved by :func:`contactlab.kernels.oblique_kernel.solve_contact`, the compiled phase loop
of :func:`contactlab.simulate_oblique`, without keeping the steps' interpolants; the
rebound numbers are read from the end state as :class:`~contactlab.ObliqueResult` reads
them.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.kernels import oblique_rhs as ob
from contactlab.kernels import power as pw
from contactlab.kernels.oblique_kernel import STATUS_OK, solve_contact, tolerances

__all__ = ["OUTPUTS", "solve_rows"]

OUTPUTS = 8
"""Numbers per row (the order of :data:`contactlab.batch.oblique.OBLIQUE_RESULTS`)."""


@njit(cache=True, error_model="numpy")
def _parameters(par, m1, k1, c1, m2, radius, inertia, k_hertz, eta, k_mindlin, mu, options):
    """Fill ``par`` for one row; ``options`` = (force history, rescaled, tied damping,
    contact arm) as 0/1 floats."""
    par[:] = 0.0
    rigid = math.isinf(k1)
    par[pw.STIFFNESS], par[pw.EXPONENT] = k_hertz, 1.5
    par[pw.DAMPING], par[pw.DAMPING_EXPONENT] = eta, 0.25
    par[pw.M1], par[pw.K1], par[pw.C1], par[pw.M2] = m1, k1, c1, m2
    par[pw.RIGID], par[pw.MODEL] = (1.0 if rigid else 0.0), pw.OBLIQUE_MODEL
    par[ob.FRICTION], par[ob.KT], par[ob.KT_EXPONENT] = mu, k_mindlin, 0.5
    par[ob.FORCE_HISTORY], par[ob.RESCALED] = options[0], options[1]
    if options[2] > 0.0:  # Mindlin.for_contact: 2 gamma sqrt(m k_mindlin), damping_ratio
        gamma = eta / (2.0 * math.sqrt(1.5 * m2 * k_hertz))
        par[ob.ETA] = 2.0 * gamma * math.sqrt(m2 * k_mindlin)
    par[ob.ETA_EXPONENT] = 0.25
    par[ob.RADIUS], par[ob.INERTIA], par[ob.CONTACT_ARM] = radius, inertia, options[3]


@njit(cache=True, error_model="numpy", nogil=True)
def solve_rows(m1, k1, c1, m2, k_hertz, eta, k_mindlin, mu, v0, radius, angle, spin, *rest):
    """Solve rows into ``out`` (rows, :data:`OUTPUTS`) with a status per row.

    The columns are those of :data:`contactlab.batch.oblique.OBLIQUE_INPUTS`; ``rest`` is
    ``(inertia_factor, options, rtol, out, status)`` (``options`` as in
    :func:`_parameters`): the status is :data:`~contactlab.kernels.oblique_kernel.STATUS_OK`
    or the kernel's failure code (the row is then handed back to
    :func:`contactlab.simulate_oblique`).
    """
    kappa, options, rtol, out, status = rest
    par = np.empty(len(ob.OBLIQUE_PARAMETERS))
    y0 = np.zeros(7)
    for i in range(m2.size):
        inertia = kappa * m2[i] * radius[i] ** 2
        _parameters(
            par,
            m1[i],
            k1[i],
            c1[i],
            m2[i],
            radius[i],
            inertia,
            k_hertz[i],
            eta[i],
            k_mindlin[i],
            mu[i],
            options,
        )
        vn, vt = v0[i] * math.cos(angle[i]), v0[i] * math.sin(angle[i])
        y0[3], y0[4], y0[5] = vn, vt, spin[i]
        atol = tolerances(rtol, v0[i], vn, m2[i] * v0[i] / 1e-6, options[0] > 0.0, radius[i])
        code, _, y, table, count, _, _ = solve_contact(par, y0, rtol, atol, False)
        status[i] = code
        if code != STATUS_OK:
            continue
        rebound, vt_out, w_out = -y[3], y[4], y[5]
        slip_before = vt - radius[i] * spin[i]
        slip_after = vt_out - radius[i] * w_out
        out[i, 0] = table[count - 1, 1]
        out[i, 1] = rebound / vn
        out[i, 2] = vt_out
        out[i, 3] = w_out
        out[i, 4] = math.atan2(vt_out, rebound)
        out[i, 5] = math.atan2(slip_after, rebound)
        out[i, 6] = slip_after / slip_before if slip_before != 0.0 else math.nan
        out[i, 7] = count
