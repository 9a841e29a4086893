"""The first touch from the whole first lobe: a contact family's force through the sensor.

A fit of the rise alone (this module's predecessor, issue 22) extrapolates the first
microseconds, which for a Hertz contact (signal ``~ s**3.5``) lie under the noise. The
whole contact carries the onset when the force's shape is known up to its size and its
duration: a single-degree-of-freedom contact on a rigid wall, nondimensional,

    ``d'' = -(d**n + 2 zeta d**m d')``,  ``d(0) = 0``, ``d'(0) = 1``,

has the force ``h(u) = d**n + 2 zeta d**m d'`` until it returns to zero (linear
spring-dashpot: ``n = 1, m = 0``; Hertz with Tsuji's damping: ``n = 1.5, m = 0.25``). The
record's force is ``A h((t - t0) / tau)`` (``h`` rescaled to a unit peak and a unit
duration) and its signal that force through the sensor (``k1 x1 + c1 v1``, the transfer
function ``(c1 p + k1) / (m1 p**2 + c1 p + k1)``), plus a line for the drift. ``A`` and
the line are linear least squares; ``t0`` and ``tau`` minimise the residual. The sensor
is taken to be rigid against the contact (its stiffness ``k1`` is 10**3 times a grain's
contact stiffness for the 40 kHz disc): the force's shape then does not depend on it.

With the record's noise model (an autoregressive process fitted on its quiet samples,
:mod:`contactlab.inverse.noise_colour`) the fit whitens the residual first
(:mod:`contactlab.inverse.lobe_model`). The Cramér-Rao bound of ``t0``
(:attr:`LobeFit.bound`) is that of the noise (white of the record's standard deviation,
or the noise model's) with ``A``, ``tau`` and the line unknown:
``sqrt([(J^T J)^-1]_00) sigma`` with ``J`` the model's (whitened) derivatives at the fit
and ``sigma`` the (innovation's) standard deviation.
"""

import functools
import math
import sys
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from contactlab.inverse.lobe_model import FAMILIES, LobeModel, force_shape

__all__ = [
    "DAMPINGS",
    "FAMILIES",
    "FirstTouch",
    "LobeFit",
    "NoContact",
    "damping_resolved",
    "fit_lobe",
    "force_shape",
    "lobe_family",
    "single_onset",
]

DAMPINGS = (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)
"""Damping ratios ``zeta`` tried [-] (restitution 1 to about 0.2 for the linear family)."""

DAMPING_TOLERANCE = 0.005
"""The shared damping ratio is refined to this [-] (a linear contact's bias in the onset:
about 0.2 us at the grid's step of 0.05, measured on the 40 kHz sensor)."""


def damping_resolved(gain, samples):
    """Whether a damping's fit is kept against none: Schwarz's criterion (BIC) for one
    parameter more, its chi-squared gain [-] over ``ln(samples)`` (the samples fitted,
    summed over the impacts) [-].

    A likelihood-ratio test at a fixed level (a gain of 4, about 2 sigma, until session
    16) reads a damping for a few undamped records in a hundred even where the residual
    is white (half a chi-squared of one degree at the bound ``zeta = 0``: 2.3 %; more,
    since the damping's profile has several minima), and a damping misread moves every
    onset of the record: Tsuji's term starts as ``s**0.25``, so 0.02 put undamped Hertz
    onsets 6-14 samples late at 2-5 MHz. Schwarz's criterion chooses the undamped model
    with a probability that goes to 1 with the samples; on the benchmark's records
    (about 2 000 samples over four impacts at 2 MHz: a gain of 7.6) it kept every
    damped contact (gains of about 2e4 on the two traced) and dropped the gains of 2.3-5.1 read on
    undamped Hertz (docs/campaign.md, "Accuracy on realistic records with a Hertz
    contact"). Before the fixed level, a damping of 0.002-0.005 fitted to the noise of
    undamped Hertz impacts had moved their onsets by 1-2 samples at 5 MHz.
    """
    return gain > math.log(samples)


PEAK_SIGMAS = 3.0
"""A fitted force whose peak is below this many noise sigmas is no contact [-] (the
detector finds impacts from five)."""


class NoContact(ParameterError):
    """The lobe fit found no contact: a duration not positive or a force whose peak is
    below :data:`PEAK_SIGMAS` noise sigmas (the samples hold no lobe the sensor makes)."""


BEFORE_PERIODS = 1.0
"""Sensor periods of record fitted before the earliest onset sought [-] (the line)."""

SEARCH_PERIODS = 1.0
"""The onset is sought from this many sensor periods before the first guess [-], or
:data:`SEARCH_DURATION` of the contact's guessed duration if that is longer."""

SEARCH_DURATION = 0.5
"""... [-]: a weak Hertz impact (10 sigma) crosses five sigmas at half its peak, a third
of its duration after the touch."""

SCAN_PERIODS = 1.0 / 32.0
"""Step of the first scan of onsets, in sensor periods [-] (the sensor's step response
rises over a quarter period: the residual's valley is several steps wide)."""

SCAN_DURATIONS = (0.6, 0.75, 0.9, 1.05, 1.2, 1.4, 1.7)
"""Contact durations of the first scan, over the guess [-] (the lobe's length above a
fraction of its peak is 0.6-0.9 of the contact's duration)."""

START_DURATION = 0.02
"""The simplex of a fit started near its optimum (``start``) spans this fraction of the
duration [-] and a sample of the onset (neighbouring dampings of the family read move
the fit by a few tenths of a sample; Nelder-Mead widens its simplex where needed)."""

AFTER_PERIODS = 0.5
"""Sensor periods fitted after the contact's end [-] (the sensor's free ringing starts)."""


@dataclass(frozen=True)
class LobeFit:
    """One impact's onset fitted with one contact family over its first lobe."""

    onset: float
    """The first touch [s]."""
    duration: float
    """The contact's duration ``tau`` [s]."""
    amplitude: float
    """The force's peak ``A`` [N] (signal units)."""
    family: str
    """Name in :data:`FAMILIES`."""
    damping: float
    """The family's damping ratio ``zeta`` [-]."""
    chi_squared: float
    """Residual sum of squares over the noise variance [-] (whitened: over the
    innovation's)."""
    samples: int
    """Samples fitted [-]."""
    bound: float
    """Cramér-Rao bound of ``onset`` [s] under the noise given (white of its sigma, or
    the noise model), with the damping known or (``damping_free``) unknown."""
    uncertainty: float = math.nan
    """Standard deviation of ``onset`` [s] under the noise covariance given
    (``autocovariance``; :meth:`contactlab.inverse.lobe_model.LobeModel.onset_spread`),
    the family and damping known; ``nan`` without one."""
    damping_terms: tuple | None = None
    """What an error of the damping read adds to that variance
    (:meth:`contactlab.inverse.lobe_model.LobeModel.damping_terms`, under the same
    covariance); None without one."""


def _scan(model, lo, hi, durations, also=()):
    """The best onset and duration on a grid: onsets from ``lo`` to ``hi`` [s] every
    :data:`SCAN_PERIODS` sensor period (the residual has a minimum every sensor period,
    where the ringing realigns) and the onsets ``also`` [s], each of ``durations`` [s]."""
    best = (math.inf, lo, durations[0])
    onsets = np.append(np.arange(lo, hi, SCAN_PERIODS * model.period), also)
    for tau in durations:
        rss = model.scan(onsets, tau)
        k = int(np.argmin(rss))  # the first of equal residuals, as a loop keeps it
        if rss[k] < best[0]:
            best = (float(rss[k]), float(onsets[k]), tau)
    return best[1], best[2]


def fit_lobe(
    t,
    y,
    sensor,
    guess,
    noise,
    family="linear",
    damping=0.0,
    *,
    damping_free=False,
    noise_model=None,
    start=None,
    autocovariance=None,
):
    """The onset of one impact: a contact family's force through the sensor, fitted on
    the impact's first lobe.

    Parameters
    ----------
    t, y : numpy.ndarray
        Time [s] (uniform) and the record's signal [N] around the impact: best from
        :data:`BEFORE_PERIODS` + :data:`SEARCH_PERIODS` sensor periods before ``guess``
        (the onset is sought from :data:`SEARCH_PERIODS` before it, or the first sample)
        to :data:`AFTER_PERIODS` past the contact's end.
    sensor : Sensor
        The moving sensor that recorded it.
    guess : (float, float)
        The latest the touch can be [s] (a threshold crossing of the raw signal, which
        lags the touch; a smoothed signal's crossing leads a sharp rise, so that one plus
        the smoothing kernel's reach) and a first contact duration [s] (the lobe's
        length).
    noise : float
        The record's noise standard deviation [N] (scales the chi-squared and the bound).
    family : str, default "linear"
        A name of :data:`FAMILIES`.
    damping : float, default 0
        The family's damping ratio [-].
    damping_free : bool, default False
        The bound counts the damping as unknown (it was read on this lobe alone).
    noise_model : ARNoise, optional
        The record's noise per sample (:func:`contactlab.inverse.noise_colour.fit_ar_noise`
        of its quiet samples): the fit whitens with it, and the chi-squared and the bound
        are the innovation's. None: white noise of ``noise``.
    start : (float, float), optional
        An onset [s] and a duration [s] near the fit's (another damping's fit on the
        same lobe): the first scan is of that duration alone, its onsets and that one,
        and the simplex starts at the one of smallest residual, :data:`START_DURATION`
        wide in the duration and a sample (the scan's step where a scanned onset won)
        in the onset. The onset is still scanned since another damping's optimum can
        lie in a neighbouring valley of the residual, which has a minimum every sensor
        period (undamped Hertz fitted to a record of Tsuji's damped Hertz lies a period
        early).
    autocovariance : numpy.ndarray, optional
        The record's noise autocovariance at lags ``0, 1, ...`` samples [N**2] (e.g.
        :meth:`contactlab.inverse.noise_prediction.ColouredNoise.autocovariance`, at
        least as many lags as the window fitted): gives :attr:`LobeFit.uncertainty` and
        :attr:`LobeFit.damping_terms`.

    Returns
    -------
    LobeFit

    Raises
    ------
    ParameterError
        A rigid sensor, a guess outside the record, fewer than 16 samples in the lobe,
        a fit that found no contact (:class:`NoContact`: duration not positive, peak
        below :data:`PEAK_SIGMAS` noise sigmas), or an onset
        more than a search span before it or after the crossing.
    """
    if not isinstance(sensor, Sensor) or sensor.is_rigid:
        raise ParameterError("sensor must be a moving contactlab.Sensor")
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    rough, length = float(guess[0]), float(guess[1])
    period = sensor.period
    if not length > 0.0:
        raise ParameterError(f"guess: the contact duration must be > 0, not {length!r} s")
    span = max(SEARCH_PERIODS * period, SEARCH_DURATION * length)
    lo = max(rough - span, float(t[0]))
    inside = (t >= lo - BEFORE_PERIODS * period) & (t <= rough + length + AFTER_PERIODS * period)
    if inside.sum() < 16 or not rough > lo or t[-1] < rough + length:
        raise ParameterError(
            f"the lobe at {rough:.6g} s has too few samples around it to fit its onset"
        )
    model = LobeModel(t[inside], y[inside], sensor, family, damping, noise_model)

    dt = model.dt
    if start is None:
        t0, tau = _scan(model, lo, rough, length * np.asarray(SCAN_DURATIONS))
        step, widen = SCAN_PERIODS * period, SCAN_DURATIONS[1] - SCAN_DURATIONS[0]
    else:  # the start's onset or a better one of the scan's at its duration: the
        # start may lie a sensor period off this damping's optimum
        durations = [float(start[1]), length]
        t0, tau = _scan(model, lo, rough, durations, also=[float(start[0])])
        step, widen = (dt if t0 == start[0] else SCAN_PERIODS * period), START_DURATION
    simplex = [[t0, tau], [t0 + step, tau], [t0, tau * (1.0 + widen)]]
    t0, tau = model.fit(simplex, xatol=1e-3 * dt, fatol=1e-9)  # scipy's Nelder-Mead
    coefficients, rss = model.solve(t0, tau)
    sigma = noise if noise_model is None or noise_model.order == 0 else noise_model.innovation
    if not (tau > 0.0 and coefficients[2] > PEAK_SIGMAS * noise):
        raise NoContact(
            f"no contact fitted at {rough:.6g} s (duration {tau:.3g} s, peak "
            f"{coefficients[2]:.3g} N, noise {noise:.3g} N)"
        )
    if not lo - span <= t0 <= rough:
        raise ParameterError(
            f"the onset fitted at {t0:.6g} s lies outside the span searched, {lo:.6g} to "
            f"{rough:.6g} s (the latest touch)"
        )
    return LobeFit(
        onset=t0,
        duration=tau,
        amplitude=float(coefficients[2]),
        family=family,
        damping=float(damping),
        chi_squared=rss / sigma**2,
        samples=int(model.t.size),
        bound=model.bound(t0, tau, sigma, damping_free),
        uncertainty=math.nan
        if autocovariance is None
        else model.onset_spread(t0, tau, autocovariance),
        damping_terms=None
        if autocovariance is None
        else model.damping_terms(t0, tau, autocovariance),
    )


def lobe_family(lobes, sensor):
    """The contact family and damping shared by impacts: for each of :data:`FAMILIES`
    the damping of :data:`DAMPINGS` with the smallest summed chi-squared, refined between
    the grid's neighbours (bounded Brent, to :data:`DAMPING_TOLERANCE`) and kept where
    :func:`damping_resolved` against none; then the family with the smaller.

    Parameters
    ----------
    lobes : list of (t, y, guess, noise) or (t, y, guess, noise, noise_model)
        The impacts, as :func:`fit_lobe` takes them (without ``noise_model`` or with
        None: white noise); those that cannot be fitted are left out.
    sensor : Sensor

    Returns
    -------
    family : str
    damping : float

    Raises
    ------
    ParameterError
        When no lobe can be fitted.
    """

    def fit(lobe, family, damping, start):
        t, y, guess, noise, *model = lobe
        noise_model = model[0] if model else None
        try:
            return fit_lobe(
                t, y, sensor, guess, noise, family, damping, noise_model=noise_model, start=start
            )
        except ParameterError:  # no contact of this shape fits (or none at all)
            return None

    def grid_fits(lobe, family):  # each damping's fit started from the one before (the
        # first scanned): the optimum moves little between neighbours
        fits, start = {}, None
        for z in DAMPINGS:
            fits[z] = fit(lobe, family, z, start)
            if fits[z] is not None:
                start = (fits[z].onset, fits[z].duration)
        return fits

    def chi(found):
        return math.inf if found is None else found.chi_squared

    totals, fitted = {}, []
    for lobe in lobes:
        fits = {f: grid_fits(lobe, f) for f in FAMILIES}
        if all(found is None for f in FAMILIES for found in fits[f].values()):
            continue  # too short or no contact: this lobe tells nothing
        fitted.append((lobe, fits))
        for f in FAMILIES:
            for z, found in fits[f].items():
                totals[(f, z)] = totals.get((f, z), 0.0) + chi(found)
    if not fitted:
        raise ParameterError("no impact with a lobe that can be fitted")
    samples = sum(  # every fit of a lobe has the same window
        next(found.samples for f in FAMILIES for found in fits[f].values() if found)
        for _, fits in fitted
    )

    def total(family, z):  # finite where a lobe fails (Brent's parabola takes differences)
        sum_ = 0.0
        for lobe, fits in fitted:  # started from the nearest grid damping's fit
            near = fits[family][min(DAMPINGS, key=lambda d: abs(d - z))]
            sum_ += chi(
                fit(lobe, family, float(z), None if near is None else (near.onset, near.duration))
            )
        return sum_ if math.isfinite(sum_) else sys.float_info.max

    best = {}
    for family in FAMILIES:  # each family's damping refined: the grid's step alone can
        # leave a misfit larger than the other family's at a few hundred sigma
        k = min(range(len(DAMPINGS)), key=lambda i, f=family: totals[(f, DAMPINGS[i])])
        low, high = DAMPINGS[max(k - 1, 0)], DAMPINGS[min(k + 1, len(DAMPINGS) - 1)]
        refined = optimize.minimize_scalar(
            functools.partial(total, family),
            bounds=(low, high),
            method="bounded",
            options={"xatol": DAMPING_TOLERANCE},
        )
        grid = (totals[(family, DAMPINGS[k])], DAMPINGS[k])
        best[family] = (refined.fun, round(float(refined.x), 4)) if refined.fun < grid[0] else grid
        if not damping_resolved(totals[(family, 0.0)] - best[family][0], samples):
            best[family] = (totals[(family, 0.0)], 0.0)  # damping not resolved: none
    family = min(best, key=lambda f: best[f][0])
    return family, best[family][1]


@dataclass(frozen=True)
class FirstTouch:
    """A single impact's first touch: the lobe fit with the family read on it, or the
    threshold crossing where that fit failed."""

    onset: float
    """The first touch [s] (the crossing where ``fit`` is None)."""
    fit: LobeFit | None
    """The lobe fit (its family, damping, duration and Cramér-Rao bound), or None."""
    note: str
    """Empty when fitted; why the crossing was kept otherwise."""

    def parameters(self):
        """As a result's parameters (``reconstruct_force``): onset [s], bound [s] (None
        where not fitted), and the family read or why the crossing was kept."""
        fit = self.fit
        return {
            "first_touch [s]": self.onset,
            "first_touch_bound [s]": None if fit is None else fit.bound,
            "first_touch_shape": self.note or f"{fit.family}, damping ratio {fit.damping:g}",
        }


def single_onset(t, y, sensor, crossing, duration, noise):
    """The first touch of one impact with nothing to share its shape with: the family
    and damping read on its own lobe (:func:`lobe_family` of one), then
    :func:`fit_lobe`; the crossing where either fails.

    Parameters
    ----------
    t, y : numpy.ndarray
        Time [s] and signal [N] of the record.
    sensor : Sensor
    crossing : float
        The threshold crossing [s] (late).
    duration : float
        A first guess of the contact's duration [s] (the signal's lobe).
    noise : float
        The record's noise standard deviation [N].

    Returns
    -------
    FirstTouch
    """
    lobe = (t, y, (crossing, duration), noise)
    try:
        family, damping = lobe_family([lobe], sensor)
        fit = fit_lobe(
            t, y, sensor, (crossing, duration), noise, family, damping, damping_free=True
        )
    except ParameterError as error:
        return FirstTouch(
            crossing, None, f"onset: the threshold crossing (lobe fit failed: {error})"
        )
    return FirstTouch(fit.onset, fit, "")
