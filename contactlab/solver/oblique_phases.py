"""The solved contact of an oblique impact as data
(:class:`~contactlab.kernels.oblique_sample.ContactPhases`).

:func:`compiled_contact` runs the compiled phase loop of the law's Coulomb cap
(:func:`contactlab.kernels.oblique_kernel.solve_contact` for LAMMPS' cap,
:func:`contactlab.kernels.elastic_cap.solve_contact` for Kratos' elastic one) and keeps
its phases and steps, which the result evaluates with one compiled sampler
(:func:`contactlab.kernels.oblique_sample.sample`).
"""

import math

import numpy as np

from contactlab.errors import ParameterError
from contactlab.kernels import elastic_cap
from contactlab.kernels.elastic_cap_rhs import ELASTIC_CAP_MODEL
from contactlab.kernels.oblique_kernel import (
    MAX_PHASES,
    STATUS_CHATTER,
    STATUS_OPEN,
    STATUS_UNDERFLOW,
    solve_contact,
)
from contactlab.kernels.oblique_sample import ContactPhases
from contactlab.kernels.power import MODEL
from contactlab.solver.adaptive import underflow_message

__all__ = ["compiled_contact", "grid_signals"]


def compiled_contact(model, y0, rtol, atol, velocity):
    """The contact from the touch ``y0`` to the separation, compiled; returns
    (:class:`ContactPhases`, y_end).

    Parameters
    ----------
    model : contactlab.solver.oblique.ObliqueModel
        The impact (its :meth:`~contactlab.solver.oblique.ObliqueModel.pack`).
    y0 : numpy.ndarray
        State at the touch.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances (:func:`contactlab.kernels.oblique_kernel.tolerances`).
    velocity : float
        Impact speed [m/s] (for the messages).
    """
    par = model.pack()
    kratos = par[MODEL] == ELASTIC_CAP_MODEL
    solve = elastic_cap.solve_contact if kratos else solve_contact
    status, failed, y_end, table, count, warp, steps = solve(
        par, np.asarray(y0, dtype=float), rtol, atol, True
    )
    if status == STATUS_UNDERFLOW:
        raise RuntimeError(underflow_message(failed, rtol))
    if status == STATUS_OPEN:
        raise ParameterError(
            f"the contact had not ended after {failed:.4g} s, so this is not an impact: "
            f"check the units of the grain (mass {model.system.m2:.4g} kg), the laws' "
            f"parameters and the velocity ({velocity:.4g} m/s)"
        )
    if status == STATUS_CHATTER:
        raise RuntimeError(f"more than {MAX_PHASES} stick/slip switches in one contact")
    return ContactPhases(par, table[:count], warp, steps), y_end


def grid_signals(contact, free, final, duration, sample_rate):
    """The signals of an oblique impact on its output grid, for
    :class:`~contactlab.ObliqueResult`: compiled in one pass
    (:meth:`ContactPhases.grid <contactlab.kernels.oblique_sample.ContactPhases.grid>`),
    but a sensor plate's free ringing after the contact.

    Parameters
    ----------
    contact : contactlab.kernels.oblique_sample.ContactPhases
        The solved contact.
    free : contactlab.kernels.segments.Segment or None
        The free flight after it on a sensor; None on a wall (the grain's flight is
        written by the compiled pass).
    final : numpy.ndarray
        State (7,) at the separation.
    duration, sample_rate : float
        Window [s] and sample rate [Hz].

    Returns
    -------
    tuple
        Times (n,) [s], states (n, 7), the normal law's unclipped formula (0 after the
        contact), normal and tangential force [N] and slip [m/s] (n,).
    """
    n = math.floor(duration * sample_rate * (1 + 1e-12)) + 1
    block = np.empty((12, n))  # one allocation: states (7 rows), raw, N, T, slip, times
    inside = contact.grid(final, sample_rate, block)
    if free is not None and inside < n:
        block[:4, inside:] = free.states(block[11, inside:] - free.t0).T
    return (block[11], block[:7].T, *block[7:11])
