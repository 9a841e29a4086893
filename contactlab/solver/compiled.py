"""An impact on the compiled impact loop, with its pieces for the output grid.

Laws of one smooth branch without history whose force is linear (``k d + c d'``, method
"exact") or a Hertz-family power law (method "adaptive") run the compiled event loop of
:mod:`contactlab.kernels.impact_loop`, the loop the batch solvers run on every row. It
returns the pieces (start, horizon and state of each contact and free flight) and the
headline numbers, read while the pieces were solved. The pieces become
:class:`~contactlab.kernels.segments.Segment` data, from which the result reads the
signals on the output grid and the dense solution for the audit: exact ones (modal
rates and weights, :mod:`contactlab.solver.exact`), and for a power-law contact the
interpolants of the same compiled DOP853 piece run again from its recorded start over
its recorded horizon (the same steps). An impact the loop does not take (modes too close
to defective, a first contact that does not end, too many contacts) is solved by the
Python pieces.
"""

import math

import numpy as np

from contactlab.kernels import impact_loop as loop
from contactlab.kernels import rules
from contactlab.kernels.modal import STATUS_OK, STATUS_TOO_FAST, row_parameters
from contactlab.kernels.power import SIGNED_DAMPING
from contactlab.solver.adaptive import adaptive_contact
from contactlab.solver.exact import contact_segment, contact_states, free_segment, free_states

__all__ = ["core_law", "solve_on_core"]


def core_law(law, method):
    """The branch of ``law`` the compiled loop takes with ``method``, or None.

    A law of one branch without exits or history, entered again at zero overlap, whose
    force is ``k d + c d'`` (``k > 0``, method "exact") or a Hertz-family
    :class:`~contactlab.laws.base.PowerForm` (elastic exponent 3/2, method "adaptive").
    """
    if law.prescribed or law.has_history or law.reentry(0.0) != (0.0, law.initial_branch):
        return None
    branch = law.branch(law.initial_branch, 0.0)
    if branch.exits:
        return None
    if method == "exact" and branch.linear is not None:
        k, _, f0 = branch.linear
        return branch if k > 0.0 and f0 == 0.0 else None
    if method == "adaptive" and branch.power is not None and branch.power.exponent == 1.5:
        return branch
    return None


def solve_on_core(system, branch, velocity, window, rtol):
    """Solve the impact on the compiled loop.

    Parameters
    ----------
    system : contactlab.solver.system.System
        Masses and sensor element.
    branch : contactlab.laws.base.Branch
        The law's branch (:func:`core_law`).
    velocity : float
        Impact speed [m/s].
    window : float or None
        Window [s], or None for the default.
    rtol : float
        Relative tolerance of a power-law contact's DOP853 pieces.

    Returns
    -------
    tuple or None
        ``(segments, contact_intervals, events, window, headline)``, ``headline`` the
        numbers read while solving (keys of :data:`contactlab.result.SOLVER_READINGS`); None
        when the loop does not take this impact.
    """
    bodies = (system.m1, system.k1, system.c1, system.m2, system.rigid)
    linear = branch.linear is not None
    if linear:
        k, c, _ = branch.linear
        par = row_parameters(k, 1.0, c, 0.0, *bodies, rules.MAX_SCAN_POINTS)
    else:
        form = branch.power
        law = (form.stiffness, form.exponent, form.damping, form.damping_exponent)
        par = row_parameters(*law, *bodies, rules.MAX_SCAN_POINTS)
        par[SIGNED_DAMPING] = 1.0 if form.signed_damping else 0.0
    out = np.empty(loop.RESULTS)
    pieces = np.empty((loop.PIECE_CAPACITY, len(loop.PIECE_FIELDS)))
    window = math.nan if window is None else window
    try:
        status = loop.solve_impact(par, linear, velocity, rtol, window, out, pieces)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError):
        return None  # an overflowing matrix: the Python pieces say which parameter
    if status == STATUS_TOO_FAST:
        raise rules.too_fast_error("an event scan found no event")
    if status != STATUS_OK:
        return None
    if linear:

        def contact(t0, t1, horizon, y0):
            return contact_segment(branch, t0, t1, contact_states(system, branch, y0))

    else:

        def contact(t0, t1, horizon, y0):
            y0 = np.array(y0)
            return adaptive_contact(system, branch, t0, y0, horizon, rtol, velocity)[0]

    segments, intervals, events = _pieces(system, contact, pieces[: int(out[loop.PIECES])], out)
    headline = {
        "_contact_peak": (float(out[loop.PEAK_CONTACT_AT]), float(out[loop.PEAK_CONTACT])),
        "sensor_lobe": (0.0, float(out[loop.RESPONSE_TIME])),
        "_sensor_peak": (float(out[loop.PEAK_SENSOR_AT]), float(out[loop.PEAK_SENSOR])),
        "impulse": float(out[loop.IMPULSE]),
        "rebound_velocity": float(out[loop.REBOUND]),
    }
    if not linear:
        # the grain's momentum change carries the integrator's error in its velocity
        # (2.7e-7 of the impulse at rtol 1e-6): the result integrates the force instead
        del headline["impulse"]
    return segments, intervals, events, float(out[loop.WINDOW]), headline


def _pieces(system, contact, pieces, out):
    """Segments, contact intervals and event log of the recorded pieces; ``contact(t0, t1,
    horizon, y0)`` is the segment of a contact piece."""
    segments, intervals, events = [], [], []
    ended, end = int(out[loop.CONTACTS]), max(float(out[loop.END]), float(out[loop.WINDOW]))
    for i, (t0, in_contact, horizon, *y0) in enumerate(pieces.tolist()):
        t1 = float(pieces[i + 1, 0]) if i + 1 < len(pieces) else end
        if in_contact:
            segments.append(contact(t0, t1, horizon, y0))
            if len(intervals) < ended:
                intervals.append((t0, t1))
                events.append((t1, "separation"))
            else:
                events.append((t1, "window end in contact"))
        else:
            segments.append(free_segment(t0, t1, free_states(system, y0)))
            if i + 1 < len(pieces):
                events.append((t1, "contact"))
    return segments, intervals, events
