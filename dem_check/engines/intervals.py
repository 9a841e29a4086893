"""Contacts of an engine's recorded steps, located inside the steps (every engine's reader).

Contact starts where the overlap turns positive and ends where the law's force formula
(``law.branch("load").force``, unclipped) turns negative, as in
:func:`contactlab.simulate_impact`. Both are located inside the step where they happen:
the overlap is interpolated by the cubic Hermite polynomial of its values and rates at
the step's ends (error O(dt**4)) and the root found by Brent's method, so the contact
time carries no error of the step grid (linear interpolation of ``d**1.5`` would err by
up to a tenth of a step).
"""

import math

import numpy as np
from scipy.optimize import brentq

from contactlab.errors import ParameterError

__all__ = ["contact_intervals"]


def _hermite(d0, d1, r0, r1, h):
    """Overlap and its rate at fraction ``s`` of a step of length ``h`` (cubic Hermite)."""

    def at(s):
        s2, s3 = s * s, s * s * s
        d = (
            (2 * s3 - 3 * s2 + 1) * d0
            + (s3 - 2 * s2 + s) * h * r0
            + (-2 * s3 + 3 * s2) * d1
            + (s3 - s2) * h * r1
        )
        r = (6 * s2 - 6 * s) * d0 / h + (3 * s2 - 4 * s + 1) * r0
        r += (-6 * s2 + 6 * s) * d1 / h + (3 * s2 - 2 * s) * r1
        return d, r

    return at


def _root_in_step(at, formula):
    """Fraction of the step where ``formula(d, d')`` (or, for ``None``, ``d``) is zero."""

    def test(s):
        overlap, rate = at(s)
        return overlap if formula is None else float(formula(overlap, rate))

    return brentq(test, 0.0, 1.0, xtol=1e-14)


def contact_intervals(law, t, overlap, rate):
    """Contacts as ``[(start, end), ...]`` [s] located inside the steps.

    Parameters
    ----------
    law : ContactLaw
        Its unclipped force formula marks the end of contact.
    t, overlap, rate : numpy.ndarray
        Time [s], overlap [m] and overlap rate [m/s] per step.

    Returns
    -------
    list of tuple
        One ``(start, end)`` per contact; ``end`` is ``nan`` for a contact still open.
    """
    formula = law.branch("load").force
    raw = formula(overlap, rate)
    touching = (overlap > 0.0) & (raw > 0.0)
    if touching[0]:
        raise ParameterError("the grain touches the sensor at release; give a positive gap")
    edges = np.flatnonzero(touching[1:] != touching[:-1]) + 1
    times = []
    for i in edges:
        h = t[i] - t[i - 1]
        at = _hermite(overlap[i - 1], overlap[i], rate[i - 1], rate[i], h)
        # what changes sign across the step: the force formula at the end of a contact,
        # the overlap at its start
        ends = touching[i - 1] and raw[i] <= 0.0
        times.append(t[i - 1] + h * _root_in_step(at, formula if ends else None))
    if touching[-1]:
        times.append(math.nan)
    return [(float(a), float(b)) for a, b in zip(times[::2], times[1::2], strict=True)]
