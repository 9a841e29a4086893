"""A tangential law as one formula: what the compiled oblique solver reads of it."""

from dataclasses import dataclass

__all__ = ["TangentialForm"]


@dataclass(frozen=True)
class TangentialForm:
    """A tangential law as one formula, for the compiled oblique solver
    (:mod:`contactlab.kernels.oblique_rhs`), as :class:`~contactlab.laws.base.PowerForm`
    is a normal law's.

    ``kt(d) = stiffness d**stiffness_exponent`` [N/m] and ``eta(d) = damping
    d**damping_exponent`` [N*s/m]; an exponent 0 is a constant at every overlap, a
    positive exponent is 0 at ``d <= 0``.

    Attributes
    ----------
    friction : float
        ``mu`` [-].
    stiffness : float
        ``k`` [N/m] (exponent 0) or ``k_mindlin`` [N/m**1.5] (exponent 0.5).
    stiffness_exponent : float
        0 or 0.5 [-].
    damping : float
        ``eta`` [N*s/m] (exponent 0) or ``2 gamma sqrt(m* k_mindlin)`` [N*s/m**1.25]
        (exponent 0.25).
    damping_exponent : float
        0 or 0.25 [-].
    force_history : bool
        Whether the history is a force (``"force"`` :attr:`TangentialLaw.history_kind`).
    rescaled : bool
        Whether the stored force is rescaled while the overlap shrinks
        (``history="incremental_rescaled"``).
    """

    friction: float
    stiffness: float
    stiffness_exponent: float
    damping: float
    damping_exponent: float
    force_history: bool
    rescaled: bool
