"""Composite Gauss-Legendre rules on graded panels, compiled.

The rule of :mod:`contactlab.quadrature` (which calls :func:`panel_edges` from here):
64 Gauss-Legendre nodes per panel, panels at most one sensor period long, graded
geometrically towards the ends of a piece that behave like a fractional power of time (a
damped Hertz force grows like ``t**0.25`` after a touch, a Mindlin force like ``sqrt`` of
the overlap). Compiled so that a compiled loop over many pieces (the oblique audit's
lever-arm moment, :func:`contactlab.kernels.oblique_sample.arm_moment`) builds its nodes
without a Python call per piece.
"""

import math

import numpy as np

from contactlab.compiled import njit

__all__ = ["GAUSS_NODES", "GAUSS_WEIGHTS", "GRADING", "panel_edges", "rule"]

GAUSS_NODES, GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(64)
"""Gauss-Legendre nodes and weights on [-1, 1] (one panel)."""

GRADING = np.array([0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-2, 0.1, 0.4])
"""Relative panel edges near a graded end of a piece (geometric grading)."""


@njit(cache=True, error_model="numpy")
def panel_edges(length, period, graded, graded_end):
    """Relative panel edges on [0, 1] of a piece (sorted, each once).

    Parameters
    ----------
    length : float
        Length of the piece [s].
    period : float
        Longest panel [s] (``inf``: one panel).
    graded : bool
        Grade the panels geometrically towards the start (:data:`GRADING`).
    graded_end : bool
        Grade them towards the end as well (``1 - GRADING``).
    """
    n = max(1, math.ceil(length / period)) if math.isfinite(period) else 1
    edges = np.empty(n + 1)
    step = 1.0 / n
    for i in range(n):  # numpy.linspace(0, 1, n + 1)'s values, to the last bit
        edges[i] = i * step + 0.0
    edges[n] = 1.0
    if graded:
        edges = np.unique(np.concatenate((GRADING, edges)))
    if graded_end:
        edges = np.unique(np.concatenate((1.0 - GRADING, edges)))
    return edges


@njit(cache=True, error_model="numpy")
def rule(lo, hi, edges):
    """Nodes [s] and weights [s] of the composite rule on [lo, hi] [s] whose panels have
    the relative ``edges`` (:func:`panel_edges`): ``weights @ f(nodes)`` integrates ``f``.
    The nodes are non-decreasing."""
    panels, size = edges.size - 1, GAUSS_NODES.size
    nodes, weights = np.empty(panels * size), np.empty(panels * size)
    length = hi - lo
    for p in range(panels):
        a, b = lo + length * edges[p], lo + length * edges[p + 1]
        half, mid = 0.5 * (b - a), 0.5 * (b + a)
        for m in range(size):
            nodes[p * size + m] = mid + half * GAUSS_NODES[m]
            weights[p * size + m] = half * GAUSS_WEIGHTS[m]
    return nodes, weights
