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
    grid : callable or None
        ``grid(tau, step, out)`` writes the states (n, 4) at uniformly spaced local times
        ``tau`` [s] (spacing ``step``) into ``out``: a faster path to the output grid where
        the piece has one (exact pieces); None otherwise.
    """

    t0: float
    t1: float
    kind: str
    branch: str | None
    states: Callable
    force: Callable
    grid: Callable | None = None

    def states_on_grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        if self.grid is not None:
            self.grid(tau, step, out)
        else:
            out[...] = self.states(tau)
        return out
