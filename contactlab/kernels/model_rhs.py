"""The right-hand side the compiled DOP853 stepper integrates, for either contact model.

:mod:`contactlab.kernels.dop853` calls one ``rhs(z, par, warped, out)``: the
normal power-law contact (:func:`contactlab.kernels.power.rhs`, four states) or the
oblique impact (:func:`contactlab.kernels.oblique_rhs.rhs`, seven), told apart by
the packed parameters: the oblique ones hold :data:`oblique_rhs.OBLIQUE_PARAMETERS` (21
fields), the normal ones fewer (the law's 10, plus the normal impact loop's own 2; an
equality test on 10 once sent the loop's pieces to the oblique equations). A
stepper that took its right-hand side as an argument could not be cached on disk by
numba, so the choice is made here, once per evaluation.
"""

from contactlab.compiled import njit
from contactlab.kernels import oblique_rhs
from contactlab.kernels import power as power_rhs

__all__ = ["OBLIQUE_FIELDS", "rhs"]

OBLIQUE_FIELDS = len(oblique_rhs.OBLIQUE_PARAMETERS)
"""Length of an oblique impact's packed parameters; a normal contact's are shorter."""


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """Right-hand side into ``out`` (see the module docstring)."""
    if par.size < OBLIQUE_FIELDS:
        power_rhs.rhs(z, par, warped, out)
    else:
        oblique_rhs.rhs(z, par, warped, out)
