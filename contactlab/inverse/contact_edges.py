"""Where a reconstructed contact force starts and ends.

A regularised reconstruction rounds the contact's corners: its force leaves zero before
the contact starts and returns to it after the contact ends, by about the width of the
smoothing. Reading the edges at a fixed fraction of the peak (2 %) then measures the
smoothing as much as the contact, and noise bumps after the contact of a few per cent of
the peak hold the reading open. :func:`significant_edges` reads them instead from the
reconstruction's own uncertainty:

1. The contact is the run of samples around the peak where the force is significantly
   above zero: more than :data:`SIGNIFICANCE_SIGMAS` of its standard deviation (the
   propagated noise, :func:`tikhonov_std`).
2. Each edge is refined by the flank's own shape: a line fitted by least squares to the
   flank between :data:`FLANK_LOW` and :data:`FLANK_HIGH` of the peak (or from the
   significance level, if that is higher) is extrapolated to zero. The flank's middle is
   where the rounding has least effect: the rounding bends its foot, the peak's curvature
   its top.
3. A force that jumps at the touch (a damped contact's ``c v``: the hard test grain's
   jumps to 42 % of its peak) has no flank to fit there: the rounding turns the jump
   into a ramp as wide as the smoothing, and the line through it reached zero 2-4 us
   before the touch (contact times 2-3 % long). Given the jump (``step``, a fraction of
   the peak; :func:`family_flanks` reads it from the contact family's shape), the
   start is where the rising force crosses half of it: a smoothing symmetric about the
   jump leaves it there.

References
----------
Hansen P.C. (2010) Discrete Inverse Problems: Insight and Algorithms. SIAM, ch. 4 (the
covariance ``sigma**2 G G^T`` of a Tikhonov solution ``f = G s``).
Aster R.C., Borchers B., Thurber C.H. (2013) Parameter Estimation and Inverse Problems,
2nd ed. Academic Press, sections 4.2-4.5 (resolution and covariance of a regularised
solution).
"""

import numpy as np
from scipy import linalg

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_onset import FAMILIES, force_shape
from contactlab.metrics import PulseMetrics, impulse, pulse_metrics, rise_time
from contactlab.validation import check_number

__all__ = [
    "DIP_FRACTION",
    "FLANK_HIGH",
    "FLANK_LOW",
    "SIGNIFICANCE_SIGMAS",
    "THRESHOLD_FRACTION",
    "THRESHOLD_SIGMAS",
    "TOUCH_SPAN",
    "family_flanks",
    "flank_shapes",
    "level_edges",
    "significant_edges",
    "tikhonov_std",
]

SIGNIFICANCE_SIGMAS = 3.0
"""A force is significantly above zero when it exceeds this many of its standard
deviations [-] (one-sided, 1.3e-3 for one Gaussian value)."""

FLANK_LOW = 0.1
"""Lowest level of the flank fitted, as a fraction of the peak [-]."""

FLANK_HIGH = 0.5
"""Highest level of the flank fitted, as a fraction of the peak [-]."""

THRESHOLD_FRACTION = 0.02
"""Level of :func:`level_edges` by default, as a fraction of the reconstructed peak."""

DIP_FRACTION = 0.05
"""A reconstructed force that dips under this fraction of its peak after it, without
reaching the threshold, ends its contact at the dip [-]: what follows is noise read as
force (1/f noise leaves bumps of 2-8 % of the peak after the contact at 20-30 sigma,
which held the contact open to +55 %; measured in ``docs/campaign.md``)."""

THRESHOLD_SIGMAS = 5.0
"""...raised to this many standard deviations of the reconstruction's own baseline."""

TOUCH_SPAN = 0.02
"""The jump of a family's force at the touch is read on its unit shape this fraction of
the contact's duration after the touch [-] (2 us for 100 us, about the reconstruction's
grid step: the span the smoothing cannot tell from a jump; a linear spring-dashpot's
force is within 1 % of its jump there, Hertz with Tsuji's damping rises as ``u**0.25``)."""


def tikhonov_std(h, penalty, noise):
    """Standard deviation of each value of an unconstrained Tikhonov solution.

    The solution of ``min ||h f - s||**2 + ||penalty f||**2`` is ``f = G s`` with
    ``G = (h^T h + penalty^T penalty)^-1 h^T``; data of independent noise of standard
    deviation ``noise`` give ``cov f = noise**2 G G^T`` (Aster et al. 2013, 4.2). For a
    whitened problem ``noise`` is the innovation's.

    Parameters
    ----------
    h : numpy.ndarray
        Model matrix (rows: data, columns: unknowns), whitened if the noise is coloured.
    penalty : numpy.ndarray
        The penalty matrix, lambda included.
    noise : float
        Standard deviation of the (whitened) data's noise [N].

    Returns
    -------
    numpy.ndarray
        ``sqrt(diag(cov f))`` [N], one per unknown.
    """
    normal = h.T @ h + penalty.T @ penalty
    gain = linalg.cho_solve(linalg.cho_factor(normal), h.T)
    return noise * np.sqrt(np.einsum("ij,ij->i", gain, gain))


def _flank_zero(t, force, levels, rising, exponent):
    """Time where a line fitted by least squares to the flank samples ``force`` between
    ``levels``, raised to ``1 / exponent``, crosses zero [s], or ``None`` when fewer than
    three samples lie there or the line does not rise (``rising``) or fall towards the
    peak."""
    low, high = levels
    inside = (force >= low) & (force <= high)
    if inside.sum() < 3:
        return None
    slope, intercept = np.polyfit(t[inside], force[inside] ** (1.0 / exponent), 1)
    if slope == 0.0 or (slope > 0.0) != rising:
        return None
    return -intercept / slope


def family_flanks(family, damping):
    """The edges' shapes of a contact family's force (:func:`significant_edges`).

    Parameters
    ----------
    family : str
        A name of :data:`contactlab.inverse.lobe_onset.FAMILIES` (the force
        ``d**n + 2 zeta d**m d'``).
    damping : float
        Its damping ratio ``zeta`` [-].

    Returns
    -------
    dict
        ``exponent``: the rising flank's power law, ``n`` (the overlap grows linearly
        at the touch); ``end_exponent``: the falling flank's, ``n`` undamped and 1
        damped (the grain leaves where ``d**n = -2 zeta d**m d'``, with ``d > 0``: the
        force crosses zero at a finite slope); ``step``: the force's jump at the touch
        over its peak, the unit shape :func:`contactlab.inverse.lobe_onset.force_shape`
        read :data:`TOUCH_SPAN` after the touch [-].
    """
    if family not in FAMILIES:
        raise ParameterError(f"family must be one of {sorted(FAMILIES)}, not {family!r}")
    n = FAMILIES[family][0]
    u, h = force_shape(family, float(damping))
    step = float(np.interp(TOUCH_SPAN, u, h)) if damping > 0.0 else 0.0
    return {"exponent": n, "end_exponent": n if damping == 0.0 else 1.0, "step": step}


def flank_shapes(exponent, family=None):
    """The flanks' keywords of :func:`significant_edges`: ``exponent`` [-], or where a
    contact ``family`` ``(name, damping ratio)`` is given, its :func:`family_flanks`."""
    if family is None:
        return {"exponent": exponent}
    if exponent != 1.0:
        raise ParameterError("give flank_exponent or contact_family, not both")
    if not isinstance(family, (tuple, list)) or len(family) != 2:
        raise ParameterError(
            f"contact_family must be a pair (family name, damping ratio), not {family!r}"
        )
    name, damping = family
    return family_flanks(
        name, check_number("contact_family damping", damping, low=0.0, low_open=False)
    )


def _half_step(t, force, level):
    """Time [s] where the rising ``force`` last crosses ``level`` before its end, by
    linear interpolation (``t[0]`` if it starts above it)."""
    under = np.flatnonzero(force[:-1] < level)
    if not under.size:
        return float(t[0])
    i = int(under[-1])
    return float(t[i] + (level - force[i]) * (t[i + 1] - t[i]) / (force[i + 1] - force[i]))


def significant_edges(
    t, force, std, sigmas=SIGNIFICANCE_SIGMAS, exponent=1.0, *, end_exponent=None, step=0.0
):
    """Pulse metrics of a reconstructed force, its edges read from its uncertainty.

    Parameters
    ----------
    t : numpy.ndarray
        Time [s], increasing.
    force : numpy.ndarray
        Reconstructed force [N] on ``t``.
    std : numpy.ndarray
        Its standard deviation [N] on ``t`` (zero where the force is zero by
        construction).
    sigmas : float, default :data:`SIGNIFICANCE_SIGMAS`
        Significance level [-].
    exponent : float, default 1.0
        The flanks' power law near the edges [-], ``F ~ |t - t_edge|**exponent``: the
        line is fitted to ``F**(1 / exponent)``. 1 for a force linear in the overlap
        (or with a viscous step), 1.5 for Hertz (the overlap is linear in time at the
        edges); a line on a Hertz flank reads its contact 6-8 % short.
    end_exponent : float, optional
        The falling flank's power law [-] where it differs (default ``exponent``; a
        damped contact's force ends at a finite slope: 1).
    step : float, default 0.0
        The force's jump at the touch over its peak [-] (:func:`family_flanks`). From
        the level the line would be fitted from (half the jump above
        :data:`FLANK_LOW` of the peak and the significance level) the start is the
        rising force's crossing of half the jump (module docstring); below, the line.

    Returns
    -------
    PulseMetrics
        ``start`` and ``end``: the flanks' lines at zero (module docstring), bounded by
        the significant run; ``peak`` the largest force; ``impulse`` the force's
        integral over the significant run and the edges; ``rise_time`` 10-90 % over it.

    Raises
    ------
    ParameterError
        If the peak is not significantly above zero.
    """
    top = int(np.argmax(force))
    peak = float(force[top])
    significant = force > sigmas * std
    if not significant[top]:
        raise ParameterError(
            f"the reconstructed force's peak ({peak:.3g} N) is not {sigmas:g} standard "
            f"deviations ({std[top]:.3g} N) above zero: no contact can be read"
        )
    below = np.flatnonzero(~significant[:top])
    first = int(below[-1]) + 1 if below.size else 0
    above = np.flatnonzero(~significant[top:])
    last = top + int(above[0]) - 1 if above.size else force.size - 1
    edges = []
    flanks = ((slice(first, top + 1), True, exponent), (slice(top, last + 1), False, end_exponent))
    for part, rising, power in flanks:
        floor = max(FLANK_LOW * peak, float(np.max(sigmas * std[part])))
        if rising and 0.5 * step * peak >= floor:  # half the jump is above the flank's foot
            edges.append(_half_step(t[part], force[part], 0.5 * step * peak))
            continue
        levels = (floor, max(FLANK_HIGH * peak, floor))
        edges.append(_flank_zero(t[part], force[part], levels, rising, power or exponent))
    # an extrapolation is kept only between the run's bounds and the peak: a flank too
    # short or too curved to fit keeps the significance crossing
    start = t[first] if edges[0] is None else min(max(edges[0], t[0]), t[top])
    end = t[last] if edges[1] is None else max(min(edges[1], t[-1]), t[top])
    lo, hi = min(start, t[first]), max(end, t[last])
    inside = (t >= lo) & (t <= hi)
    return PulseMetrics(
        start=float(start),
        end=float(end),
        duration=float(end - start),
        peak_time=float(t[top]),
        peak=peak,
        rise_time=rise_time(t[inside], force[inside]) if inside.sum() >= 2 else np.nan,
        impulse=impulse(t, force, lo, hi),
    )


def level_edges(t, force, threshold):
    """Pulse metrics of the lobe of the reconstructed force above ``threshold`` [N] that
    holds its peak, ended at its first dip under :data:`DIP_FRACTION` of the peak (the
    rule before :func:`significant_edges`; ``contact_edges="level"``).

    A lobe above the threshold before it is the window edge fitting noise as force: on
    a realistic record with 1/f noise as large as the white noise the force rose to
    2.3 % of its peak at the contact window's first knot, and the first lobe read there
    gave a contact of 0.15 us instead of 100 us (``docs/campaign.md``).
    """
    peak = int(np.argmax(force))
    before = np.flatnonzero(force[:peak] <= threshold)
    first = int(before[-1]) if before.size else 0
    return pulse_metrics(t[first:], _cut_at_dip(force, peak, threshold)[first:], threshold)


def _cut_at_dip(force, peak, threshold):
    """``force`` zeroed after its first dip after the peak that is under
    :data:`DIP_FRACTION` of the peak but stays above ``threshold`` (unchanged when the
    force falls to the threshold first)."""
    after = force[peak:]
    under = np.flatnonzero(after <= threshold)
    end = int(under[0]) if under.size else after.size
    inner = after[1 : end - 1]
    dips = np.flatnonzero(
        (inner < after[: end - 2]) & (inner <= after[2:end]) & (inner < DIP_FRACTION * after[0])
    )
    if not dips.size:
        return force
    return np.concatenate([force[: peak + dips[0] + 2], np.zeros(after.size - dips[0] - 2)])
