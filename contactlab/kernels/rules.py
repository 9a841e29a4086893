"""The event loop's rules, written once for every solver: window, scan step, contact
matrix, crossed side.

:func:`contactlab.simulate_impact` (Python pieces and compiled ones alike), the compiled
impact loops of :mod:`contactlab.kernels.linear_impact` and
:mod:`contactlab.kernels.hertz_impact` (which the batch solvers run row by row) and the
oblique solver take these rules from here: no rule is written twice. The functions are
compiled (numba) and callable from Python.
"""

import math

import numpy as np

from contactlab.compiled import njit
from contactlab.errors import ParameterError

__all__ = [
    "FIRST_CONTACT_HORIZON",
    "MAX_CONTACTS",
    "MAX_SCAN_POINTS",
    "RINGING_PERIODS",
    "SCAN_STEPS_PER_RADIAN",
    "WINDOW_PER_CONTACT",
    "contact_horizon",
    "contact_matrix",
    "happened",
    "ringing_time",
    "scan_step",
    "too_fast_error",
    "window_end",
]

MAX_CONTACTS = 200
"""Contact intervals after which the solver stops (a grain resting on a ringing plate)."""

FIRST_CONTACT_HORIZON = 1.0
"""How far the first contact is followed when no window is given [s]: a contact longer
than a second is not an impact."""

RINGING_PERIODS = 5.0
"""Default window: sensor periods of ringing after the first contact."""

WINDOW_PER_CONTACT = 1.5
"""Default window: at least this many first-contact durations."""

SCAN_STEPS_PER_RADIAN = 5.0
"""Event scan: about 31 points per period of the fastest mode, so no two crossings of an
event function fall between scan points."""


MAX_SCAN_POINTS = 20_000_000
"""Most scan points of one event search (about 25 s on one core): a piece whose fastest
mode needs more before its event is refused. A linear contact damping of 1e6 N*s/m on a
50 mg grain takes 1.3 million (1.4 s; a 5e-11 s relaxation time against a 13 us contact),
1e7 N*s/m 13 million (16 s); the scan grows with the damping, and 1e9 N*s/m ran for half
an hour. A 300 kHz sensor ringing through a second of free flight needs 1e7."""


def too_fast_error(detail):
    """The :class:`~contactlab.errors.ParameterError` of an event scan that reached
    :data:`MAX_SCAN_POINTS` (``detail``: where it stood)."""
    return ParameterError(
        f"a mode of this impact is too fast to follow: {detail} ({MAX_SCAN_POINTS:.0e} "
        "points); a contact damping or stiffness this large against the masses "
        "(relaxation time ~ m/c) is beyond the solver: lower it to a physical value"
    )


@njit(cache=True, error_model="numpy")
def ringing_time(m1, k1, rigid):
    """:data:`RINGING_PERIODS` periods of the free sensor ``sqrt(k1 / m1)`` [s] (0 on a wall)."""
    return 0.0 if rigid else RINGING_PERIODS * 2.0 * math.pi / math.sqrt(k1 / m1)


@njit(cache=True, error_model="numpy")
def window_end(contact_end, ringing):
    """Default window after a contact that ended at ``contact_end`` [s]: the contact and
    the ringing (``ringing`` [s], :func:`ringing_time`), at least
    :data:`WINDOW_PER_CONTACT` contact times."""
    return max(WINDOW_PER_CONTACT * contact_end, contact_end + ringing)


@njit(cache=True, error_model="numpy")
def contact_horizon(limit):
    """How far to follow the first contact when looking for its end [s], for a window
    ``limit`` [s] (inf: none given): a contact longer than a second (or 100 windows) is
    not an impact."""
    if math.isinf(limit):
        return FIRST_CONTACT_HORIZON
    return max(100.0 * limit, FIRST_CONTACT_HORIZON)


@njit(cache=True, error_model="numpy")
def scan_step(rate, tau_max):
    """Scan step [s] for events of a piece whose fastest mode has ``|lambda| = rate``
    [1/s], on ``(0, tau_max]``."""
    if rate == 0.0:
        return tau_max / 64.0
    return min(tau_max / 64.0, 1.0 / (SCAN_STEPS_PER_RADIAN * rate))


@njit(cache=True, error_model="numpy")
def contact_matrix(m1, k1, c1, m2, k, c, rigid):
    """System matrix of ``[x1, v1, x2, v2]`` under a contact force ``k d + c d' + f0``.

    On an immovable wall the grain's ``[x2, v2]`` alone (2 x 2); units 1/s and 1/s**2.
    """
    if rigid:
        return np.array([[0.0, 1.0], [-k / m2, -c / m2]])
    return np.array(
        [
            [0.0, 1.0, 0.0, 0.0],
            [-(k1 + k) / m1, -(c1 + c) / m1, k / m1, c / m1],
            [0.0, 0.0, 0.0, 1.0],
            [k / m2, c / m2, -k / m2, -c / m2],
        ]
    )


@njit(cache=True, error_model="numpy", inline="always")
def happened(value, direction):
    """Whether an event function is on its crossed side: ``value <= 0`` falling
    (``direction < 0``), ``value >= 0`` rising (:func:`contactlab.roots.has_happened`
    for one float, compiled)."""
    return value <= 0.0 if direction < 0 else value >= 0.0
