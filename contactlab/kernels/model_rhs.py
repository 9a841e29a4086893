"""The right-hand side the compiled DOP853 stepper integrates, for either contact model.

:mod:`contactlab.kernels.dop853` calls one ``rhs(z, par, warped, out)``: the normal
power-law contact (:func:`contactlab.kernels.power.rhs`, four states) or the oblique
impact (:func:`contactlab.kernels.oblique_rhs.rhs`, seven), as the packed parameters'
``model`` field says (:data:`~contactlab.kernels.power.NORMAL_MODEL` or
:data:`~contactlab.kernels.power.OBLIQUE_MODEL`, set by the packers). A stepper that
took its right-hand side as an argument could not be cached on disk by numba, so the
choice is made here, once per evaluation.
"""

from contactlab.compiled import njit
from contactlab.kernels import oblique_rhs
from contactlab.kernels import power as power_rhs

__all__ = ["rhs"]


@njit(cache=True, error_model="numpy")
def rhs(z, par, warped, out):
    """Right-hand side into ``out`` (see the module docstring)."""
    if par[power_rhs.MODEL] == power_rhs.OBLIQUE_MODEL:
        oblique_rhs.rhs(z, par, warped, out)
    else:
        power_rhs.rhs(z, par, warped, out)
