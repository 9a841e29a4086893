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

**The fit is checked** (:func:`checked_joint_ringing`): the model assumes the record's
contact family, read on other impacts (or on this pair's first lobe). Where the second
impact's contact differs (a misread family, or a law of its own), the lobe's shape is
wrong and so are its numbers. At the fitted onset and duration the linear coefficients
are fitted again by generalised least squares under the record's white and 1/f noise
(:class:`contactlab.inverse.noise_prediction.ColouredNoise`), and the whitened
residual's chi-squared is compared with its expectation: ``n - 7`` degrees of freedom
(``n`` samples; five coefficients, the onset and the duration), standard deviation
``sqrt(2 (n - 7))``. A fit more than :data:`REJECT_SIGMAS` of them above is rejected,
and every family and damping of :data:`contactlab.inverse.lobe_onset.DAMPINGS` is
fitted instead, the best one's damping refined between its grid neighbours (bounded
Brent, as :func:`contactlab.inverse.lobe_onset.lobe_family`); the fit of least
chi-squared is kept if it passes, and the result says that none did otherwise.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg, optimize

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_model import FAMILIES, LobeModel
from contactlab.inverse.lobe_onset import (
    DAMPING_TOLERANCE,
    DAMPINGS,
    SCAN_DURATIONS,
    SCAN_PERIODS,
)
from contactlab.inverse.local_baseline import RESOLVED_PERIOD_SAMPLES, free_ringing

__all__ = [
    "AFTER_PERIODS",
    "EARLY_PERIODS",
    "REJECT_SIGMAS",
    "CheckedJoint",
    "JointRinging",
    "checked_joint_ringing",
    "joint_ringing",
]

AFTER_PERIODS = 16.0
"""Sensor periods after the second contact's guessed end that are fitted [-]: as many
as an impact's own free ringing is fitted on
(:data:`contactlab.inverse.local_baseline.POST_PERIODS`)."""

EARLY_PERIODS = 2.0
"""The second touch is sought from this many sensor periods before its detected onset
[-] (:data:`dem_check.campaign.overlaps.HOLD_PERIODS`: that onset is where the ringing
envelope grew, up to two of its windows after the touch) to half a period after it."""


REJECT_SIGMAS = 6.0
"""A joint fit whose chi-squared exceeds its expectation under the record's noise by more
than this many of its standard deviations is rejected [-]. Measured: with the right
family -1.4 to +0.4 on ``bench_overlaps.py --pairs`` (18 pairs 0.2-0.5 ms apart, the
noise's white and 1/f levels estimated on the record) and -1.2 to +0.4 on 16 records of
closed-form pulses (``tests/dem_check/campaign/test_overlap_fit.py``, noise known); with
the other family (Hertz for a half-sine, linear for a Hertz pulse) +24 to +265 on the
latter. Six is four times the largest with the right family: a rejection costs 18 fits
and a damping search and may fall back to an unreliable reading, so a few sigmas of
noise-level error must not trigger it."""


UNFITTED = 1e300
"""The chi-squared given a family whose force could not be fitted [-] (finite: the
bounded Brent search of the damping takes differences)."""


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
    family: tuple = None
    """The contact family and damping ratio ``(name, zeta [-])`` of the second's force."""
    chi_squared: float = math.nan
    """The whitened residual's chi-squared under the record's noise [-] (module
    docstring; NaN without a noise model)."""
    degrees: int = 0
    """Its degrees of freedom, the samples less seven [-]."""

    @property
    def excess(self):
        """The chi-squared's excess over its expectation, in its standard deviations
        ``sqrt(2 degrees)`` [-] (NaN without a noise model)."""
        return (self.chi_squared - self.degrees) / math.sqrt(2.0 * max(self.degrees, 1))

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


def _chi_squared(design, y, noise):
    """The chi-squared of ``y`` [N] on the columns of ``design`` fitted by generalised
    least squares under ``noise`` (:class:`ColouredNoise`; the covariance is Toeplitz:
    Levinson's recursion, :func:`scipy.linalg.solve_toeplitz`) [-]."""
    solved = linalg.solve_toeplitz(noise.autocovariance(y.size), np.column_stack([design, y]))
    weighted, target = solved[:, :-1], solved[:, -1]
    beta = np.linalg.solve(design.T @ weighted, weighted.T @ y)
    residual = y - design @ beta
    return float(residual @ (target - weighted @ beta))


def joint_ringing(t, y, guess, sensor, family, noise=None):
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
    noise : ColouredNoise, optional
        The record's white and 1/f noise (:func:`dem_check.campaign.local.record_noise`):
        the fit's chi-squared under it (module docstring); None: not computed.

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
    chi = math.nan if noise is None else _chi_squared(design, y, noise)
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
        family=(name, float(damping)),
        chi_squared=chi,
        degrees=t.size - 7,
    )


@dataclass(frozen=True)
class CheckedJoint:
    """The joint fit kept by :func:`checked_joint_ringing` and how it was chosen."""

    joint: JointRinging
    """The fit kept: the record's family's, or the family of least chi-squared."""
    accepted: bool
    """Whether its chi-squared is within :data:`REJECT_SIGMAS` of the noise's
    expectation (True without a noise model: not checked)."""
    rejected: JointRinging = None
    """The record's family's fit, where it was rejected."""

    def note(self):
        """What the check found, for a row's reason."""
        joint = self.joint
        if math.isnan(joint.chi_squared):
            return "the joint fit's chi-squared not checked (no noise estimate of the record)"
        kept = f"{joint.family[0]} contact, damping ratio {joint.family[1]:.3g}"
        if self.rejected is None:
            return (
                f"the joint fit ({kept}) agrees with the record's noise (chi-squared "
                f"{joint.excess:+.1f} standard deviations from its expectation)"
            )
        first = self.rejected
        text = (
            f"the joint fit with the record's family ({first.family[0]}, damping ratio "
            f"{first.family[1]:.3g}) was rejected: its chi-squared is {first.excess:.1f} "
            f"standard deviations over the record's noise's expectation (limit "
            f"{REJECT_SIGMAS:g})"
        )
        if self.accepted:
            return f"{text}; refitted with every family: the {kept} agrees ({joint.excess:+.1f})"
        return f"{text}; no family agrees (the best, {kept}: {joint.excess:.1f})"


def checked_joint_ringing(t, y, guess, sensor, family, noise):
    """:func:`joint_ringing` with the record's ``family``, checked against the record's
    ``noise`` and refitted with every family and damping where rejected (module
    docstring).

    Parameters
    ----------
    t, y, guess, sensor, family
        As for :func:`joint_ringing`.
    noise : ColouredNoise or None
        The record's white and 1/f noise; None: the fit is kept unchecked.

    Returns
    -------
    CheckedJoint

    Raises
    ------
    ParameterError
        As :func:`joint_ringing` with the record's family.
    """
    first = joint_ringing(t, y, guess, sensor, family, noise)
    if noise is None or first.excess <= REJECT_SIGMAS:
        return CheckedJoint(joint=first, accepted=True)
    fits = {first.family: first}

    def chi(name, damping):
        key = (name, round(float(damping), 12))
        if key not in fits:
            try:
                fits[key] = joint_ringing(t, y, guess, sensor, key, noise)
            except ParameterError:  # no force of this shape fitted: not a candidate
                fits[key] = None
        return UNFITTED if fits[key] is None else fits[key].chi_squared

    name, damping = min(((f, z) for f in FAMILIES for z in DAMPINGS), key=lambda p: chi(*p))
    k = DAMPINGS.index(damping)  # refined between the grid's neighbours, as lobe_family
    low, high = DAMPINGS[max(k - 1, 0)], DAMPINGS[min(k + 1, len(DAMPINGS) - 1)]
    optimize.minimize_scalar(
        lambda z: chi(name, z),
        bounds=(low, high),
        method="bounded",
        options={"xatol": DAMPING_TOLERANCE},
    )
    best = min((fit for fit in fits.values() if fit is not None), key=lambda f: f.chi_squared)
    return CheckedJoint(joint=best, accepted=best.excess <= REJECT_SIGMAS, rejected=first)
