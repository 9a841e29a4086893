"""The right-hand side the compiled DOP853 stepper integrates, for either contact model.

:mod:`contactlab.kernels.dop853` calls one ``rhs(z, par, warped, out)``: the normal
power-law contact (:func:`contactlab.kernels.power.rhs`, four states) or the oblique
impact (:func:`contactlab.kernels.oblique_rhs.rhs`, seven; with Kratos' elastic Coulomb
cap, :func:`contactlab.kernels.elastic_cap_rhs.rhs`), as the packed parameters' ``model``
field says (:data:`~contactlab.kernels.power.NORMAL_MODEL`,
:data:`~contactlab.kernels.power.OBLIQUE_MODEL` or
:data:`~contactlab.kernels.elastic_cap_rhs.ELASTIC_CAP_MODEL`, set by the packers). A stepper that
took its right-hand side as an argument could not be cached on disk by numba, so the
choice is made here, once per evaluation; :func:`events` chooses the event functions the
same way (:mod:`contactlab.kernels.oblique_events` locates them for either model). Both
are inlined into their callers: called, the choice cost the damped-Hertz DOP853 step 60 %
(763-890 ns against 466-592 ns before the choice existed, measured in one run).
"""

from contactlab.compiled import njit
from contactlab.kernels import elastic_cap_rhs, oblique_rhs
from contactlab.kernels import power as power_rhs

__all__ = ["events", "rhs"]


@njit(cache=True, error_model="numpy", inline="always")
def rhs(z, par, warped, out):
    """Right-hand side into ``out`` (see the module docstring)."""
    model = par[power_rhs.MODEL]
    if model == power_rhs.OBLIQUE_MODEL:
        oblique_rhs.rhs(z, par, warped, out)
    elif model == elastic_cap_rhs.ELASTIC_CAP_MODEL:
        elastic_cap_rhs.rhs(z, par, warped, out)
    else:
        power_rhs.rhs(z, par, warped, out)


@njit(cache=True, error_model="numpy", inline="always")
def events(z, par, phase, out):
    """Event values into ``out``; returns how many the model has in ``phase``.

    The normal contact has one, its end: the force formula
    (:func:`contactlab.kernels.power.force`, negative where the contact would pull); the
    oblique models' are :func:`contactlab.kernels.elastic_cap_rhs.events`.
    """
    if par[power_rhs.MODEL] == power_rhs.NORMAL_MODEL:
        out[0] = power_rhs.force(z[2] - z[0], z[3] - z[1], par)
        return 1
    return elastic_cap_rhs.events(z, par, phase, out)
