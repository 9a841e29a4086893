"""The right-hand side the compiled DOP853 stepper integrates, for either contact model.

:mod:`contactlab.kernels.dop853` calls one ``rhs(z, par, warped, out)``: the
normal power-law contact (:func:`contactlab.kernels.power.rhs`, four states) or the
oblique impact (:func:`contactlab.kernels.oblique_rhs.rhs`, seven), told apart by the
number of states (not by the packed parameters' length: the normal impact loop appends
its own fields to the law's, which once sent normal pieces to the oblique equations). A
stepper that took its right-hand side as an argument could not be cached on disk by
numba, so the choice is made here, once per evaluation.
"""

from contactlab.compiled import njit
from contactlab.kernels import oblique_rhs
from contactlab.kernels import power as power_rhs

__all__ = ["NORMAL_STATES", "rhs"]

NORMAL_STATES = 4
"""States of the normal contact ``(x1, v1, x2, v2)``; the oblique impact has seven."""


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """Right-hand side into ``out`` (see the module docstring)."""
    if z.size == NORMAL_STATES:
        power_rhs.rhs(z, par, warped, out)
    else:
        oblique_rhs.rhs(z, par, warped, out)
