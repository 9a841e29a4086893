"""The paper's explicit Euler integration, kept as the reference method.

Keska et al. (2021) integrated the two-mass model with a simple explicit Euler scheme at
``dt = 1e-10 s`` in their GKWK program. This module reproduces that method faithfully:
both positions and velocities advance with the rates of the *old* state, the force law
is evaluated once per step, and events are step-limited (the contact ends at the first
step where the force is no longer positive). It is pure Python, about a microsecond or
two per step: for checks and benchmarks on short windows, not for studies.
"""

import math

import numpy as np

from contactlab.kernels.segments import SampledStates, Segment

__all__ = ["solve_euler"]

_MAX_RECORDS = 200_000
"""States kept for output; the rest of the steps are integrated but not stored."""


def _contact_force_fn(law, system, velocity, branch):
    """Scalar force of the current branch (fast path for linear branches)."""
    if law.prescribed:
        return None
    if branch.linear is not None:
        k, c, f0 = branch.linear
        return lambda d, r: k * d + c * r + f0
    return lambda d, r: float(branch.force(d, r))


def solve_euler(system, law, velocity, window, time_step):
    """Integrate with explicit Euler; returns (segments, intervals, log, window).

    Parameters
    ----------
    system : contactlab.solver.system.System
        Masses and sensor element.
    law : ContactLaw or PlasticTrapezoid
        Contact law.
    velocity : float
        Impact speed [m/s].
    window : float or None
        End time [s]; None stops at twice the first contact time.
    time_step : float
        Euler step [s].
    """
    m1, k1, c1, m2, rigid = system.m1, system.k1, system.c1, system.m2, system.rigid
    x1 = v1 = x2 = 0.0
    v2 = velocity
    pulse = law.force_at if law.prescribed else None
    branch = law.branch(law.initial_branch, 0.0) if not law.prescribed else None
    force = _contact_force_fn(law, system, velocity, branch)
    exits = [] if branch is None else list(branch.exits)
    max_overlap, in_contact, start = 0.0, True, 0.0
    previous_exit = [e.value(0.0, velocity) for e in exits]
    intervals, log = [], []
    n_max = math.inf if window is None else round(window / time_step)
    stride = 1 if window is None else max(1, n_max // _MAX_RECORDS)
    rec_t, rec_y, rec_f = [], [], []
    n = 0
    while n <= n_max:
        t = n * time_step
        d, r = x2 - x1, v2 - v1
        s2 = 0.0
        if in_contact:
            s2 = float(pulse(t, m2, velocity)) if pulse else force(d, r)
            ended = t >= law.contact_time if pulse else (s2 <= 0.0 and n > 0)
            if ended:
                in_contact, s2 = False, 0.0
                intervals.append((start, t))
                log.append((t, "separation"))
                if window is None:
                    n_max = 2 * n
                if pulse is None:
                    threshold, entry = law.reentry(max_overlap)
            elif exits:
                for e, before in zip(exits, previous_exit, strict=True):
                    now = e.value(d, r)
                    if (before > 0 >= now) if e.direction < 0 else (before < 0 <= now):
                        if branch.loading:
                            max_overlap = max(max_overlap, d)
                        log.append((t, f"branch {branch.name} -> {e.target}"))
                        branch = law.branch(e.target, max_overlap)
                        break
                else:
                    if branch.loading:
                        max_overlap = max(max_overlap, d)
                force = _contact_force_fn(law, system, velocity, branch)
                exits = list(branch.exits)
                previous_exit = [e.value(d, r) for e in exits]
        elif pulse is None and d > threshold:
            entry_branch = law.branch(entry, max_overlap)
            entry_force = _contact_force_fn(law, system, velocity, entry_branch)
            if entry_force(d, r) > 0.0:
                in_contact, start, branch, force = True, t, entry_branch, entry_force
                exits = list(branch.exits)
                previous_exit = [e.value(d, r) for e in exits]
                log.append((t, "contact"))
                s2 = force(d, r)
        if n % stride == 0:
            rec_t.append(t)
            rec_y.append((x1, v1, x2, v2))
            rec_f.append(max(s2, 0.0))
        a2 = -s2 / m2
        a1 = 0.0 if rigid else (s2 - k1 * x1 - c1 * v1) / m1
        x1, v1, x2, v2 = (
            x1 + v1 * time_step,
            v1 + a1 * time_step,
            x2 + v2 * time_step,
            v2 + a2 * time_step,
        )
        n += 1
    if in_contact:
        log.append((t, "window end in contact"))
    states = SampledStates(np.asarray(rec_t), np.asarray(rec_y), np.asarray(rec_f))
    end = states.t[-1]
    return [Segment(0.0, end, "euler", None, states)], intervals, log, end
