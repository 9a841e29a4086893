"""Composite Gauss-Legendre rules for integrals over the smooth pieces of a solution.

Impulses, works and energies are integrals of the dense solution over pieces that are
smooth inside and may behave like a fractional power of time at an end (a damped Hertz
force grows like ``t**0.25`` after a touch, a Mindlin force like ``sqrt`` of the overlap).
One rule serves :class:`contactlab.ImpactResult` and the audits (:mod:`contactlab.audit`):
64 Gauss-Legendre nodes per panel, panels at most one sensor period long, graded
geometrically towards the ends that need it.
"""

import math

import numpy as np

__all__ = ["gauss_rule", "panel_edges"]

GAUSS_NODES, GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(64)
"""Gauss-Legendre nodes and weights on [-1, 1] (one panel)."""

GRADING = np.array([0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-2, 0.1, 0.4])
"""Relative panel edges near a graded end of a piece (geometric grading)."""


def panel_edges(length, period, graded=False, graded_end=False):
    """Relative panel edges on [0, 1] of a piece.

    Parameters
    ----------
    length : float
        Length of the piece [s].
    period : float
        Longest panel [s] (``inf``: one panel).
    graded : bool, default False
        Grade the panels geometrically towards the start.
    graded_end : bool, default False
        Grade them towards the end as well.
    """
    n = max(1, math.ceil(length / period)) if math.isfinite(period) else 1
    edges = np.linspace(0.0, 1.0, n + 1)
    if graded:
        edges = np.union1d(GRADING, edges)
    if graded_end:
        edges = np.union1d(1.0 - GRADING, edges)
    return edges


def gauss_rule(lo, hi, period=math.inf, graded=False, graded_end=False):
    """Nodes [s] and weights [s] of the composite rule on [lo, hi] [s].

    ``weights @ f(nodes)`` integrates ``f`` over [lo, hi]; panels as in :func:`panel_edges`.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
    """
    edges = lo + (hi - lo) * panel_edges(hi - lo, period, graded, graded_end)
    half, mid = 0.5 * np.diff(edges), 0.5 * (edges[1:] + edges[:-1])
    nodes = (mid[:, None] + half[:, None] * GAUSS_NODES).ravel()
    weights = (half[:, None] * GAUSS_WEIGHTS).ravel()
    return nodes, weights
