"""Composite Gauss-Legendre rules for integrals over the smooth pieces of a solution.

Impulses, works and energies are integrals of the dense solution over pieces that are
smooth inside and may behave like a fractional power of time at an end (a damped Hertz
force grows like ``t**0.25`` after a touch, a Mindlin force like ``sqrt`` of the overlap).
One rule serves :class:`contactlab.ImpactResult` and the audits (:mod:`contactlab.audit`):
64 Gauss-Legendre nodes per panel, panels at most one sensor period long, graded
geometrically towards the ends that need it. The rule is compiled
(:mod:`contactlab.kernels.gauss`), so that compiled loops over many pieces use the same
one.
"""

import math

from contactlab.kernels import gauss
from contactlab.kernels.gauss import GAUSS_NODES, GAUSS_WEIGHTS, GRADING

__all__ = ["GAUSS_NODES", "GAUSS_WEIGHTS", "GRADING", "gauss_rule", "panel_edges"]


def panel_edges(length, period, graded=False, graded_end=False):
    """Relative panel edges on [0, 1] of a piece ``length`` [s] long, panels at most
    ``period`` [s] (``inf``: one panel), graded towards the start and/or the end:
    :func:`contactlab.kernels.gauss.panel_edges`, without grading by default."""
    return gauss.panel_edges(float(length), float(period), bool(graded), bool(graded_end))


def gauss_rule(lo, hi, period=math.inf, graded=False, graded_end=False):
    """Nodes [s] and weights [s] of the composite rule on [lo, hi] [s].

    ``weights @ f(nodes)`` integrates ``f`` over [lo, hi]; panels as in :func:`panel_edges`.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
    """
    lo, hi = float(lo), float(hi)
    return gauss.rule(lo, hi, panel_edges(hi - lo, period, graded, graded_end))
