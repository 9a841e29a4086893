"""An impact's free ringing fitted together with the next impact's lobe (issue 22).

Two impacts 0.2-0.5 ms apart (:mod:`dem_check.campaign.overlaps`) leave only a few
sensor periods of the first one's free ringing before the second begins. Fitted there
alone and extrapolated under the second, that ringing's error (its two amplitudes read
on about two periods) lands in the second impact's numbers: +6 to +8 % of its peak
signal and impulse at half the velocity, 0.2 ms apart. Here the first impact's free
ringing is fitted on the whole span from its first lobe's end to
:data:`AFTER_PERIODS` sensor periods past the second contact, together with what the
second impact adds there: its contact family's force ``A h((t - t0) / tau)`` through the
sensor (:class:`contactlab.inverse.lobe_model.LobeModel`, whose signal holds the
second's forced response and its own free ringing after its contact), plus a line.

The model on that span is

    ``y = c0 + c1 (t - tm) / T + exp(-a s) (A1 cos(b s) + B1 sin(b s)) + A r(t - t0; tau)``

(``s`` the time since the span's start, ``a, b`` the sensor's decay rate and damped
angular frequency, ``T`` its period, ``r`` the unit-peak signal of the family's force):
linear in ``c0, c1, A1, B1, A`` (least squares), with ``t0, tau`` sought (variable
projection: a scan of onsets every :data:`contactlab.inverse.lobe_onset.SCAN_PERIODS`
period and durations :data:`contactlab.inverse.lobe_onset.SCAN_DURATIONS` times the
guess, then a simplex). After the second contact both ringings are free ringing of the
same mode and cannot be told apart; the first one's amplitudes are read on the samples
before the second touch and through the second's lobe, whose shape the family and the
sensor fix. The fit is ordinary least squares (white noise), as the onset fits of the
campaign (:data:`dem_check.campaign.onsets.NOISE_MODEL`).
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_model import LobeModel
from contactlab.inverse.lobe_onset import SCAN_DURATIONS, SCAN_PERIODS
from contactlab.inverse.local_baseline import RESOLVED_PERIOD_SAMPLES, free_ringing

__all__ = ["AFTER_PERIODS", "EARLY_PERIODS", "JointRinging", "joint_ringing"]

AFTER_PERIODS = 16.0
"""Sensor periods after the second contact's guessed end that are fitted [-]: as many
as an impact's own free ringing is fitted on
(:data:`contactlab.inverse.local_baseline.POST_PERIODS`)."""

EARLY_PERIODS = 2.0
"""The second touch is sought from this many sensor periods before its detected onset
[-] (:data:`dem_check.campaign.overlaps.HOLD_PERIODS`: that onset is where the ringing
envelope grew, up to two of its windows after the touch) to half a period after it."""


@dataclass(frozen=True)
class JointRinging:
    """The first impact's free ringing read with the second impact's lobe."""

    start: float
    """The fitted span's start [s] (a period after the first lobe): the ringing's origin."""
    ringing: tuple
    """Its amplitudes ``(A1, B1)`` [N] at :attr:`start` (:func:`free_ringing`)."""
    line: tuple
    """The line ``(c0 [N], c1 [N per sensor period], tm [s])``."""
    onset: float
    """The second touch [s]."""
    duration: float
    """The second contact's duration ``tau`` [s]."""
    amplitude: float
    """The second force's peak ``A`` [N] (signal units)."""
    impulse: float
    """The second force's impulse ``A tau`` times the unit shape's integral [N*s]."""
    peak_signal: float
    """The second force's signal's largest value [N] (``A`` times the unit-peak
    signal's, on the model's fine grid)."""
    rms: float
    """Root-mean-square residual on the span [N] (the noise, where the model holds)."""

    def values(self, t, sensor):
        """The first impact's line and free ringing at the times ``t`` [s] (the ringing
        extrapolated before :attr:`start` too: the caller keeps the samples where it is
        free ringing)."""
        t = np.asarray(t, dtype=float)
        offset, slope, centre = self.line
        line = offset + slope * (t - centre) / sensor.period
        return line + free_ringing(t, self.start, self.ringing, sensor)


def _design(model, t0, tau, unit, ringing):
    """Columns: the line, the first's ringing and the second's unit-peak signal."""
    return np.column_stack([model.line, ringing, model.response(t0, tau, unit)])


def joint_ringing(t, y, guess, sensor, family):
    """Fit the first impact's line and free ringing together with the second impact's
    lobe on ``t`` (module docstring).

    Parameters
    ----------
    t, y : numpy.ndarray
        The record [s], [N] from a period after the first impact's lobe (the ringing's
        origin, ``t[0]``) to :data:`AFTER_PERIODS` sensor periods past the second
        contact, holding no third impact.
    guess : (float, float)
        The second impact's detected onset [s] (it lags the touch) and a contact
        duration [s].
    sensor : Sensor
    family : (str, float)
        The record's contact family and damping ratio
        (:data:`contactlab.inverse.lobe_model.FAMILIES`).

    Returns
    -------
    JointRinging

    Raises
    ------
    ParameterError
        A record that does not resolve the sensor's ringing, too few samples before
        the second touch for a line and a ringing, or no force fitted (its peak not
        positive).
    """
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    dt = float(t[1] - t[0])
    if sensor.period / dt < RESOLVED_PERIOD_SAMPLES:
        raise ParameterError(
            f"{sensor.period / dt:.3g} samples per sensor period: the ringing is not "
            f"resolved (need {RESOLVED_PERIOD_SAMPLES})"
        )
    onset, length = guess
    lo = max(float(t[0]), onset - EARLY_PERIODS * sensor.period)
    if np.count_nonzero(t < lo) < 4:  # four amplitudes before the touch (line and ringing)
        raise ParameterError(
            f"only {np.count_nonzero(t < lo)} samples between {t[0]:.6g} s and the next "
            f"impact's earliest touch {lo:.6g} s: no ringing to fit (need 4)"
        )
    name, damping = family
    model = LobeModel(t, y, sensor, name, float(damping))
    ringing = np.column_stack([free_ringing(t, float(t[0]), unit, sensor) for unit in np.eye(2)])
    units = {}

    def rss(params):
        t0, tau = params
        if not tau > 0.0:
            return math.inf
        key = round(tau, 15)
        if key not in units:
            units[key] = model.unit(tau)
        design = _design(model, t0, tau, units[key], ringing)
        residual = y - design @ np.linalg.lstsq(design, y, rcond=None)[0]
        return float(residual @ residual)

    grid = [
        (rss((t0, tau)), t0, tau)
        for tau in length * np.asarray(SCAN_DURATIONS)
        for t0 in np.arange(lo, onset + 0.5 * sensor.period, SCAN_PERIODS * sensor.period)
    ]
    _, t0, tau = min(grid)
    simplex = [(t0, tau), (t0 + dt, tau), (t0, 1.02 * tau)]
    found = optimize.minimize(
        rss,
        (t0, tau),
        method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": 1e-3 * dt, "fatol": 1e-12},
    )
    t0, tau = (float(v) for v in found.x)
    unit = model.unit(tau)
    design = _design(model, t0, tau, unit, ringing)
    coefficients = np.linalg.lstsq(design, y, rcond=None)[0]
    if not coefficients[4] > 0.0:
        raise ParameterError(f"the next impact's force fitted as {coefficients[4]:.3g} N")
    residual = y - design @ coefficients
    return JointRinging(
        start=float(t[0]),
        ringing=(float(coefficients[2]), float(coefficients[3])),
        line=(float(coefficients[0]), float(coefficients[1]), float(t.mean())),
        onset=t0,
        duration=tau,
        amplitude=float(coefficients[4]),
        impulse=float(coefficients[4] * tau * np.trapezoid(model.h, model.u)),
        peak_signal=float(coefficients[4] * np.max(unit[1])),
        rms=math.sqrt(float(residual @ residual) / max(t.size - 7, 1)),
    )
