"""Exactly solvable pieces: linear contact branches and free flight.

Every piece here is linear time-invariant, so its state is the modal solution (or the
matrix exponential), kept as data (:mod:`contactlab.kernels.segments`), and its events are
roots of the exact expressions, scanned and located by
:func:`~contactlab.solver.propagators.first_event`.
"""

import numpy as np

from contactlab.kernels.modal import recontact_horizon
from contactlab.kernels.rules import scan_step
from contactlab.kernels.segments import AffineStates, LinearStates, Segment
from contactlab.solver.propagators import first_event
from contactlab.solver.system import event_directions, overlap_rate

__all__ = [
    "affine_states",
    "contact_segment",
    "contact_states",
    "exact_contact",
    "free_flight",
    "free_segment",
    "free_states",
]


def _branch_events(branch, contact_force):
    """Event functions of a contact piece (vectorised over states) and their directions."""
    directions = event_directions(branch)

    def values(states):
        d, r = overlap_rate(states)
        cols = [contact_force(d, r)] + [e.value(d, r) for e in branch.exits]
        return np.column_stack(cols)

    return values, directions


def affine_states(system, a, b, y0):
    """Exact states under a prescribed contact force ``S2 = a + b tau`` [N] from the state
    ``y0``: the sensor's free flow about the particular solution ``x1 = p + q tau`` of
    ``m1 x1'' + c1 x1' + k1 x1 = a + b tau``, i.e. ``q = b / k1`` and
    ``p = a / k1 - c1 b / k1**2`` (:class:`~contactlab.kernels.segments.AffineStates`)."""
    y0 = tuple(float(v) for v in y0)
    if system.rigid:
        return AffineStates(y0, a, b, system.m2, None)
    q = b / system.k1
    p = a / system.k1 - system.c1 * b / system.k1**2
    flow = system.sensor_flow
    sensor = flow.trajectory([y0[0] - p, y0[1] - q])
    return AffineStates(y0, a, b, system.m2, sensor, p, q, flow.fastest_rate)


def contact_states(system, branch, y0):
    """Exact states of a contact piece on a linear branch from the state ``y0``: the flow
    of ``k d + c d' + f0`` about its equilibrium ``d = -f0 / k``
    (:class:`~contactlab.kernels.segments.LinearStates`)."""
    k, c, f0 = branch.linear
    if k == 0.0 and c == 0.0:
        return affine_states(system, f0, 0.0, y0)
    flow = system.contact_flow(k, c)
    offset = np.array([0.0, 0.0, -f0 / k, 0.0])
    z0 = np.asarray(y0, dtype=float) - offset
    trajectory = flow.trajectory(z0[2:] if system.rigid else z0)
    return LinearStates(trajectory, offset, system.rigid, flow.fastest_rate)


def contact_segment(branch, t0, t1, states):
    """The :class:`~contactlab.kernels.segments.Segment` of a contact piece over [t0, t1]
    [s] with its ``states``."""
    return Segment(t0, t1, "contact", branch.name, states)


def free_states(system, y0):
    """Exact states of a free flight (no contact force) from the state ``y0``."""
    return affine_states(system, 0.0, 0.0, y0)


def free_segment(t0, t1, states):
    """The :class:`~contactlab.kernels.segments.Segment` of a free flight over [t0, t1] [s]
    with its ``states``."""
    return Segment(t0, t1, "free", None, states)


def exact_contact(system, branch, t0, y0, tau_max):
    """Exact contact piece on a linear branch; returns (Segment, y_end, event or None)."""
    states = contact_states(system, branch, y0)
    values, directions = _branch_events(branch, branch.force)
    hit = first_event(
        lambda tau: values(states(tau)), tau_max, scan_step(states.rate, tau_max), directions
    )
    tau_end = tau_max if hit is None else hit[0]
    event = None if hit is None else ("end" if hit[1] == 0 else branch.exits[hit[1] - 1].target)
    return contact_segment(branch, t0, t0 + tau_end, states), states(tau_end)[0], event


def free_flight(system, law, max_overlap, t0, y0, tau_max):
    """Free flight until the plate and grain touch again; returns (Segment, y_end, hit)."""
    states = free_states(system, y0)
    if law.prescribed or tau_max <= 0.0:
        return free_segment(t0, t0 + tau_max, states), None, None
    threshold, entry = law.reentry(max_overlap)
    entry_force = law.branch(entry, max_overlap).force

    def values(tau):
        d, r = overlap_rate(states(tau))
        # below the threshold: its distance, kept negative at the threshold itself, where
        # grain and plate touch without contact (so a receding grain is no crossing)
        below = np.minimum(d - threshold, -np.finfo(float).tiny)
        return np.where(d > threshold, entry_force(d, r), below)[:, None]

    horizon = recontact_horizon(
        np.asarray(y0, float), system.m1, system.k1, system.rigid, threshold
    )
    search = min(tau_max, horizon)  # 0: receding from a wall, nothing to scan
    hit = (
        None if search <= 0.0 else first_event(values, search, scan_step(states.rate, search), [+1])
    )
    tau_end = tau_max if hit is None else hit[0]
    seg = free_segment(t0, t0 + tau_end, states)
    return seg, states(tau_end)[0], None if hit is None else entry
