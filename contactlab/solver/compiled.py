"""An impact on the compiled impact loop, with its pieces for the output grid.

Laws of one smooth branch without history whose force is linear (``k d + c d'``) run
the compiled event loop of :mod:`contactlab.kernels.impact_loop`, the loop the batch
solvers run on every row. It returns the pieces (start and state of each contact and
free flight) and the headline numbers, read while the pieces were solved; the pieces
become exact :class:`~contactlab.solver.segment.Segment` objects
(:mod:`contactlab.solver.exact`), which give the signals on the output grid and the
dense solution for the audit. An impact the loop does not take (modes too close to
defective, a first contact that does not end, too many contacts) is solved by the
Python pieces as before.
"""

import math

import numpy as np

from contactlab.kernels import impact_loop as loop
from contactlab.kernels import rules
from contactlab.kernels.modal import STATUS_OK, STATUS_TOO_FAST, row_parameters
from contactlab.solver.exact import contact_segment, contact_states, free_segment, free_states

__all__ = ["core_law", "solve_on_core"]


def core_law(law):
    """The branch of ``law`` the compiled loop takes, or None.

    A law of one branch without exits or history, entered again at zero overlap, whose
    force is ``k d + c d'`` (``k > 0``).
    """
    if law.prescribed or law.has_history or law.reentry(0.0) != (0.0, law.initial_branch):
        return None
    branch = law.branch(law.initial_branch, 0.0)
    if branch.exits or branch.linear is None:
        return None
    k, _, f0 = branch.linear
    return branch if k > 0.0 and f0 == 0.0 else None


def solve_on_core(system, branch, velocity, window):
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

    Returns
    -------
    tuple or None
        ``(segments, contact_intervals, events, window, headline)``, ``headline`` the
        numbers read while solving (keys of :data:`contactlab.result.HEADLINE`); None
        when the loop does not take this impact.
    """
    k, c, _ = branch.linear
    bodies = (system.m1, system.k1, system.c1, system.m2, system.rigid)
    par = row_parameters(k, 1.0, c, 0.0, *bodies, rules.MAX_SCAN_POINTS)
    out, pieces = np.empty(loop.RESULTS), np.empty((loop.PIECE_CAPACITY, 6))
    window = math.nan if window is None else window
    try:
        status = loop.solve_impact(par, True, velocity, 0.0, window, out, pieces)
    except (ArithmeticError, ValueError, np.linalg.LinAlgError):
        return None  # an overflowing matrix: the Python pieces say which parameter
    if status == STATUS_TOO_FAST:
        raise rules.too_fast_error("an event scan found no event")
    if status != STATUS_OK:
        return None
    segments, intervals, events = _pieces(system, branch, pieces[: int(out[loop.PIECES])], out)
    lobe_end = out[loop.RESPONSE_TIME]
    headline = {
        "_contact_peak": (float(out[loop.PEAK_CONTACT_AT]), float(out[loop.PEAK_CONTACT])),
        "sensor_lobe": (0.0, float(lobe_end)),
        "_sensor_peak": (float(out[loop.PEAK_SENSOR_AT]), float(out[loop.PEAK_SENSOR])),
        "impulse": float(out[loop.IMPULSE]),
        "rebound_velocity": float(out[loop.REBOUND]),
    }
    return segments, intervals, events, float(out[loop.WINDOW]), headline


def _pieces(system, branch, pieces, out):
    """Segments, contact intervals and event log of the recorded pieces."""
    segments, intervals, events = [], [], []
    ended, end = int(out[loop.CONTACTS]), max(float(out[loop.END]), float(out[loop.WINDOW]))
    for i, (t0, contact, *y0) in enumerate(pieces.tolist()):
        t1 = pieces[i + 1, 0] if i + 1 < len(pieces) else end
        if contact:
            segments.append(contact_segment(branch, t0, t1, contact_states(system, branch, y0)))
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
