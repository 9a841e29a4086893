"""A piece of an impact solution between two events."""

from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["Segment"]


@dataclass(frozen=True)
class Segment:
    """A piece of the solution between two events.

    Attributes
    ----------
    t0, t1 : float
        Start and end [s].
    kind : str
        ``"contact"``, ``"free"`` or ``"pulse"`` (prescribed force).
    branch : str or None
        Law branch in contact pieces.
    states : callable
        ``states(tau) -> (n, 4)`` array ``[x1, v1, x2, v2]`` at local times ``tau`` [s].
    force : callable
        ``force(tau, states) -> (n,)`` contact force S2 [N], never negative.
    """

    t0: float
    t1: float
    kind: str
    branch: str | None
    states: Callable
    force: Callable
