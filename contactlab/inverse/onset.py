"""The first touch of an impact: a least-squares fit of the sensor's response to the rise.

A threshold crossing of a smoothed signal lags the first touch by the time the signal
takes to reach it, a time set by the noise and the contact law (1.5-6 us for a 40 kHz
sensor at 10-100 noise sigmas), not by the sampling rate. With the sensor known, the
signal near the touch is the sensor's response to the contact force's start, and the
force's start is a power of the time since the touch for every contact law: a damped
linear contact steps (``q = 0``), an undamped one ramps (``q = 1``), a Hertz contact
grows as ``s**1.5``. The fit (variable projection) models the record on a window around
the rise as

    ``c0 + c1 (t - t_c) + a r_q(t - t0) + b r_{q+1}(t - t0)``

where ``r_p`` is the sensor's response to the force ``(s / T)**p`` switched on at
``s = 0`` (``T`` the sensor period; :func:`scipy.signal.lsim` of the sensor's transfer
function ``(c1 s + k1) / (m1 s**2 + c1 s + k1)``, since the signal is ``k1 x1 + c1 v1``)
and ``t0`` is the onset. The line takes the drift and the slow part of 1/f noise, the
second power the force's bend over the window. For each ``t0`` the four amplitudes are
linear least squares; ``t0`` minimises the residual (a scan on a quarter-sample grid,
then Brent's method). The exponent ``q`` trades off against ``t0`` on one noisy impact
(a later touch with a smaller power looks alike), so a campaign chooses it once per
record, where every impact has the same contact law (:func:`rise_exponent`).
"""

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy import optimize, signal

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError

__all__ = ["BENDS", "EXPONENTS", "RISE_FRACTION", "OnsetFit", "Rise", "fit_onset", "rise_shape"]

EXPONENTS = (0.0, 0.5, 1.0, 1.5, 2.0)
"""Powers ``q`` of the contact force's start tried [-]: a damped linear contact's step
(0), a damped Hertz contact's ``sqrt`` start (0.5), an undamped linear ramp (1), Hertz
(1.5), and one beyond."""

BENDS = (-0.5, 0.0, 0.5, 1.0, 2.0, 4.0, 8.0)
"""Ratios of the force's ``(s / T)**(q + 1)`` term to its ``(s / T)**q`` term tried [-]
(``T`` the sensor period): a damped linear contact ``v (c2 + k2 s)`` has ``k2 T / c2``
(2 for the hard test grain on a 40 kHz sensor), a Hertz contact a small negative one (the
grain slows)."""

RISE_FRACTION = 0.3
"""The fit window ends where the signal first reaches this fraction of its peak [-]:
far enough into the rise for the shape to be read above the noise, early enough for two
powers of the time since the touch to describe the force."""

BEFORE_PERIODS = 1.0
"""Sensor periods of quiet record fitted before the rough onset [-] (the line)."""

SEARCH_PERIODS = 1.0
"""The onset is sought within this many sensor periods before the rough onset, and up
to the window's end [-]: a Hertz contact's signal grows as ``s**3.5`` and reaches five
sigmas 10 us after the touch at 30-100 sigmas."""


GRID_SAMPLES = 2.0
"""Step of the onset's first scan [samples]; Brent's method refines the best step's
neighbourhood. The residual is smooth in the onset on this scale (the rise spans tens of
samples)."""


class Rise(NamedTuple):
    """One impact's rise, as :func:`fit_onset` reads it."""

    t: np.ndarray
    """Time [s], uniform."""
    y: np.ndarray
    """The record around the impact [N], as measured (the fit has its own line)."""
    rough: float
    """A first onset [s] (the smoothed signal's threshold crossing)."""
    end: float
    """The fit window's end [s]: where the rise reaches :data:`RISE_FRACTION` of its
    peak."""
    noise: float
    """The record's noise standard deviation [N] (scales the chi-squared)."""


@dataclass(frozen=True)
class OnsetFit:
    """One impact's onset fitted with one exponent."""

    onset: float
    """The first touch [s]."""
    exponent: float
    """The force's start ``(t - onset)**exponent`` [-]."""
    bend: float
    """The ``(s / T)**(exponent + 1)`` term's amplitude over the first's [-]."""
    chi_squared: float
    """Residual sum of squares over the noise variance [-]."""
    samples: int
    """Samples fitted [-]."""


@functools.lru_cache(maxsize=64)
def _response(w, zeta, period, exponent, periods, step):
    """The signal of a sensor (angular frequency ``w`` [rad/s], damping ratio ``zeta``
    [-], period [s]) for the force ``(s / period)**exponent`` from ``s = 0``, on a grid of
    ``step`` [s] over ``periods`` sensor periods."""
    s = np.arange(0.0, periods * period + 2.0 * step, step)
    system = ([2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w])
    _, y, _ = signal.lsim(system, (s / period) ** exponent, s)
    return s, y


def _solve(t0, t, y, centre, period, responses, bend):
    """Least-squares amplitudes and residual sum of squares with the onset at ``t0`` [s]:
    the second power's amplitude free (``bend`` None) or ``bend`` times the first's.
    Normal equations: four columns or fewer, each of order one."""
    shifted = [np.interp(t - t0, s, r, left=0.0) for s, r in responses]
    rise = shifted if bend is None else [shifted[0] + bend * shifted[1]]
    design = np.column_stack([np.ones_like(t), (t - centre) / period, *rise])
    gram, moment = design.T @ design, design.T @ y
    try:
        coefficients = np.linalg.solve(gram, moment)
    except np.linalg.LinAlgError:  # no rise inside the window: this onset is no fit
        return np.full(design.shape[1], np.nan), math.inf
    residual = y - design @ coefficients
    return coefficients, float(residual @ residual)


def fit_onset(rise, sensor, exponent, bend=None):
    """The onset of one impact: the sensor's response to ``(t - t0)**q`` fitted.

    Parameters
    ----------
    rise : Rise
        The impact's samples and where to look.
    sensor : Sensor
        The moving sensor that recorded it.
    exponent : float
        The force's start power ``q`` [-].
    bend : float, optional
        The force's ``(s / T)**(q + 1)`` amplitude over its ``(s / T)**q`` amplitude [-]
        (a record's shared shape); fitted per impact when not given.

    Returns
    -------
    OnsetFit

    Raises
    ------
    ParameterError
        A rigid sensor, or a rise with fewer than 8 samples in the window.
    """
    if not isinstance(sensor, Sensor) or sensor.is_rigid:
        raise ParameterError("sensor must be a moving contactlab.Sensor")
    t, y = np.asarray(rise.t, dtype=float), np.asarray(rise.y, dtype=float)
    rough, end = rise.rough, rise.end
    dt = float(t[1] - t[0])
    period = sensor.period
    lo = rough - SEARCH_PERIODS * period
    inside = (t >= lo - BEFORE_PERIODS * period) & (t <= end)
    if inside.sum() < 8 or not end > rough:
        raise ParameterError(f"the rise at {rough:.6g} s has too few samples to fit its onset")
    tw, yw = t[inside], y[inside]
    periods = math.ceil((float(tw[-1] - lo) + dt) / period)  # cached by whole periods
    step = dt / 16.0
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    responses = [_response(w, zeta, period, q, periods, step) for q in (exponent, exponent + 1.0)]
    centre = float(tw.mean())

    def cost(t0):
        return _solve(t0, tw, yw, centre, period, responses, bend)[1]

    grid = np.arange(lo, end, GRID_SAMPLES * dt)
    if grid.size < 2:
        raise ParameterError(f"the rise at {rough:.6g} s ends before its search starts")
    costs = np.array([cost(t0) for t0 in grid])
    k = int(np.argmin(costs))
    bracket = (grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)])
    best = optimize.minimize_scalar(
        cost, bounds=bracket, method="bounded", options={"xatol": 1e-3 * dt}
    )
    onset = float(best.x) if best.fun <= costs[k] else float(grid[k])
    coefficients, rss = _solve(onset, tw, yw, centre, period, responses, bend)
    ratio = bend if bend is not None else coefficients[3] / coefficients[2]
    return OnsetFit(onset, float(exponent), float(ratio), rss / rise.noise**2, int(tw.size))


def rise_shape(rises, sensor):
    """The force's start shared by a record's impacts: the exponent and bend of
    :data:`EXPONENTS` x :data:`BENDS` with the smallest summed chi-squared.

    Parameters
    ----------
    rises : list of Rise
        The record's strongest impacts (they carry the shape); those too short to fit
        are left out.
    sensor : Sensor

    Returns
    -------
    exponent, bend : float

    Raises
    ------
    ParameterError
        When no rise can be fitted.
    """
    totals = {}
    for r in rises:
        try:
            fits = {(q, b): fit_onset(r, sensor, q, b) for q in EXPONENTS for b in BENDS}
        except ParameterError:  # too few samples: this rise tells nothing
            continue
        for shape, fit in fits.items():
            totals[shape] = totals.get(shape, 0.0) + fit.chi_squared
    if not totals:
        raise ParameterError("no impact with a rise long enough to read its shape on")
    return min(totals, key=totals.get)
