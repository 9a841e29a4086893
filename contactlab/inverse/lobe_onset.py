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

The Cramér-Rao bound of ``t0`` (:attr:`LobeFit.bound`) is that of white noise of the
record's standard deviation with ``A``, ``tau`` and the line unknown:
``sqrt([(J^T J)^-1]_00) sigma`` with ``J`` the model's derivatives at the fit.
"""

import functools
import math
import sys
from dataclasses import dataclass

import numpy as np
from scipy import integrate, optimize, signal

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError

__all__ = [
    "DAMPINGS",
    "FAMILIES",
    "FirstTouch",
    "LobeFit",
    "fit_lobe",
    "force_shape",
    "lobe_family",
    "single_onset",
]

FAMILIES = {"linear": (1.0, 0.0), "hertz": (1.5, 0.25)}
"""Contact families ``name: (n, m)``: the force ``d**n + 2 zeta d**m d'`` [-] (a linear
spring-dashpot; Hertz with Tsuji's damping, undamped Hertz at ``zeta = 0``)."""

DAMPINGS = (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)
"""Damping ratios ``zeta`` tried [-] (restitution 1 to about 0.2 for the linear family)."""

DAMPING_TOLERANCE = 0.005
"""The shared damping ratio is refined to this [-] (a linear contact's bias in the onset:
about 0.2 us at the grid's step of 0.05, measured on the 40 kHz sensor)."""

UNDAMPED_CHI_SQUARED = 4.0
"""A family's damping is kept only where it lowers the summed chi-squared by more than
this against none [-] (a likelihood-ratio test of one parameter at about 2 sigma): a
damping fitted to the noise, 0.002-0.005 on undamped contacts, moved Hertz onsets by
1-2 samples at 5 MHz (the force ``2 zeta d**0.25 d'`` starts as ``s**0.25``)."""

PEAK_SIGMAS = 3.0
"""A fitted force whose peak is below this many noise sigmas is no contact [-] (the
detector finds impacts from five)."""

SHAPE_POINTS = 4096
"""Samples of the unit force shape on its unit duration [-] (interpolated linearly: a
relative error below 1e-6 of the peak where the shape is smooth)."""

FINE_PERIODS = 1.0 / 128.0
"""The force is pushed through the sensor on a step of at most this many sensor periods
and half a sample [-] (the first-order hold is exact for a piecewise-linear force; the
signal, interpolated linearly between the steps, is then within ``(2 pi / 128)**2 / 8 =
3e-4`` of its peak; a damped contact's force step is centred on its step)."""

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
    """Residual sum of squares over the noise variance [-]."""
    samples: int
    """Samples fitted [-]."""
    bound: float
    """Cramér-Rao bound of ``onset`` under white noise of the given sigma [s], with the
    damping known or (``damping_free``) unknown."""


@functools.lru_cache(maxsize=64)
def force_shape(family, damping):
    """The unit force shape of a contact family: ``h(u)`` on ``u`` in [0, 1], peak 1.

    Parameters
    ----------
    family : str
        A name of :data:`FAMILIES`.
    damping : float
        Damping ratio ``zeta`` [-], >= 0.

    Returns
    -------
    u, h : numpy.ndarray
        Time over the contact's duration [-] and force over its peak [-]
        (:func:`scipy.integrate.solve_ivp`, relative tolerance 1e-10).
    """
    if family not in FAMILIES:
        raise ParameterError(f"family must be one of {sorted(FAMILIES)}, not {family!r}")
    n, m = FAMILIES[family]

    def force(d, v):  # odd in d: the event below crosses zero cleanly
        return math.copysign(abs(d) ** n, d) + 2.0 * damping * abs(d) ** m * v

    def rhs(_, x):
        return [x[1], -force(x[0], x[1])]

    def released(u, x):  # the force returns to zero (after its start)
        return force(x[0], x[1]) if u > 1e-6 else 1.0

    released.terminal, released.direction = True, -1.0
    solved = integrate.solve_ivp(
        rhs, (0.0, 20.0), [0.0, 1.0], events=released, rtol=1e-10, atol=1e-12, dense_output=True
    )
    end = float(solved.t_events[0][0])
    u = np.linspace(0.0, end, SHAPE_POINTS)
    d, v = solved.sol(u)
    h = np.array([force(a, b) for a, b in zip(d, v, strict=True)])
    h[-1] = 0.0
    return u / end, h / h.max()


@functools.lru_cache(maxsize=16)
def _sensor_filter(w, zeta, step):
    """The signal response of a sensor (angular frequency ``w`` [rad/s], damping ratio
    ``zeta`` [-]) as a discrete filter on ``step`` [s] (first-order hold: exact for a
    piecewise-linear force)."""
    b, a, _ = signal.cont2discrete(
        ([2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w]), step, method="foh"
    )
    return np.ravel(b), np.ravel(a)


class _Model:
    """The signal of ``A h((t - t0) / tau)`` on a window, for the fit and its bound."""

    def __init__(self, t, y, sensor, family, damping):
        self.t, self.y = t, y
        self.dt = float(t[1] - t[0])
        self.u, self.h = force_shape(family, damping)
        self.family, self.damping = family, damping
        self.fine = math.ceil(max(2.0, self.dt / (FINE_PERIODS * sensor.period)))
        self.filter = _sensor_filter(
            sensor.angular_frequency, sensor.damping_ratio, self.dt / self.fine
        )
        self.period = sensor.period
        centre = float(t.mean())
        self.line = np.column_stack([np.ones_like(t), (t - centre) / self.period])
        self.basis = np.linalg.qr(self.line)[0]
        self.y_off = y - self.basis @ (self.basis.T @ y)
        self.y_rss = float(self.y_off @ self.y_off)

    def unit(self, tau, shape=None):
        """The unit-peak signal against the time since the force's start: time [s] and
        signal [-]. The force starts half a fine step after a fine sample, so that the
        hold's ramp over that step centres a damped contact's force step on it.
        ``shape``: another ``(u, h)`` than the model's."""
        step = self.dt / self.fine
        s = np.arange(-1, self.fine * (self.t.size + 2)) * step
        u, h = (self.u, self.h) if shape is None else shape
        force = np.interp((s - 0.5 * step) / tau, u, h, left=0.0, right=0.0)
        return s - 0.5 * step, signal.lfilter(*self.filter, force)

    def response(self, t0, tau, unit=None):
        """The unit-peak signal on the window's samples [-] (``unit``: :meth:`unit` of
        ``tau``, when already computed)."""
        s, r = self.unit(tau) if unit is None else unit
        return np.interp(self.t - t0, s, r, left=0.0)

    def design(self, t0, tau, unit=None):
        """Columns: offset, slope (over a sensor period), the unit-peak signal."""
        return np.column_stack([self.line, self.response(t0, tau, unit)])

    def solve(self, t0, tau, unit=None, coefficients=True):
        """Linear amplitudes (offset, slope, ``A``; only ``A`` without ``coefficients``)
        and the residual sum of squares (the signal's column projected off the line's
        orthonormal basis)."""
        if not tau > 0.0:
            return np.full(3, np.nan), math.inf
        r = self.response(t0, tau, unit)
        r_off = r - self.basis @ (self.basis.T @ r)
        norm = float(r_off @ r_off)
        if not norm > 0.0:  # no force inside the window
            return np.full(3, np.nan), math.inf
        amplitude = float(r_off @ self.y_off) / norm
        rss = max(self.y_rss - amplitude * amplitude * norm, 0.0)
        if not coefficients:
            return amplitude, rss
        line = np.linalg.lstsq(self.line, self.y - amplitude * r, rcond=None)[0]
        return np.array([*line, amplitude]), rss

    def scan(self, lo, hi, length):
        """The best onset and duration on a grid: onsets from ``lo`` to ``hi`` [s] every
        :data:`SCAN_PERIODS` sensor period (the residual has a minimum every sensor
        period, where the ringing realigns), durations :data:`SCAN_DURATIONS` times
        ``length`` [s]."""
        best = (math.inf, lo, length)
        onsets = np.arange(lo, hi, SCAN_PERIODS * self.period)
        for tau in length * np.asarray(SCAN_DURATIONS):
            unit = self.unit(tau)
            for t0 in onsets:
                rss = self.solve(t0, tau, unit, coefficients=False)[1]
                if rss < best[0]:
                    best = (rss, t0, tau)
        return best[1], best[2]

    def bound(self, t0, tau, noise, damping_free):
        """Cramér-Rao bound of ``t0`` [s] (central differences of a tenth of a sample;
        with ``damping_free`` the damping ratio is a nuisance parameter too, its
        derivative one-sided over 0.01)."""
        coefficients, _ = self.solve(t0, tau)
        ht, htau = 0.1 * self.dt, 1e-3 * tau
        d_t0 = (self.response(t0 + ht, tau) - self.response(t0 - ht, tau)) / (2.0 * ht)
        d_tau = (self.response(t0, tau + htau) - self.response(t0, tau - htau)) / (2.0 * htau)
        a = coefficients[2]
        columns = [a * d_t0 * self.dt, a * d_tau * tau, self.design(t0, tau)]
        if damping_free:
            other = self.unit(tau, force_shape(self.family, self.damping + 0.01))
            d_zeta = (self.response(t0, tau, other) - self.response(t0, tau)) / 0.01
            columns.insert(2, a * d_zeta)
        jacobian = np.column_stack(columns)
        try:
            covariance = np.linalg.inv(jacobian.T @ jacobian)
        except np.linalg.LinAlgError:  # no rise in the window: no information on t0
            return math.inf
        return float(math.sqrt(max(covariance[0, 0], 0.0)) * noise * self.dt)


def fit_lobe(t, y, sensor, guess, noise, family="linear", damping=0.0, *, damping_free=False):
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

    Returns
    -------
    LobeFit

    Raises
    ------
    ParameterError
        A rigid sensor, a guess outside the record, fewer than 16 samples in the lobe,
        a fit that found no contact (duration not positive, peak below
        :data:`PEAK_SIGMAS` noise sigmas), or an onset
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
    model = _Model(t[inside], y[inside], sensor, family, damping)

    def cost(x):
        return model.solve(x[0], x[1], coefficients=False)[1]

    t0, tau = model.scan(lo, rough, length)
    dt, step = model.dt, SCAN_PERIODS * period
    simplex = [
        [t0, tau],
        [t0 + step, tau],
        [t0, tau * (1.0 + SCAN_DURATIONS[1] - SCAN_DURATIONS[0])],
    ]
    best = optimize.minimize(
        cost,
        simplex[0],
        method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": 1e-3 * dt, "fatol": 1e-9},
    )
    t0, tau = (float(v) for v in best.x)
    coefficients, rss = model.solve(t0, tau)
    if not (tau > 0.0 and coefficients[2] > PEAK_SIGMAS * noise):
        raise ParameterError(
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
        chi_squared=rss / noise**2,
        samples=int(model.t.size),
        bound=model.bound(t0, tau, noise, damping_free),
    )


def lobe_family(lobes, sensor):
    """The contact family and damping shared by impacts: for each of :data:`FAMILIES`
    the damping of :data:`DAMPINGS` with the smallest summed chi-squared, refined between
    the grid's neighbours (bounded Brent, to :data:`DAMPING_TOLERANCE`); then the family
    with the smaller.

    Parameters
    ----------
    lobes : list of (t, y, guess, noise)
        The impacts, as :func:`fit_lobe` takes them; those that cannot be fitted are left
        out.
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

    def chi_squared(lobe, family, damping):
        t, y, guess, noise = lobe
        try:
            return fit_lobe(t, y, sensor, guess, noise, family, damping).chi_squared
        except ParameterError:  # no contact of this shape fits (or none at all)
            return math.inf

    totals, fitted = {}, []
    for lobe in lobes:
        fits = {(f, z): chi_squared(lobe, f, z) for f in FAMILIES for z in DAMPINGS}
        if not any(math.isfinite(chi) for chi in fits.values()):
            continue  # too short or no contact: this lobe tells nothing
        fitted.append(lobe)
        for shape, chi in fits.items():
            totals[shape] = totals.get(shape, 0.0) + chi
    if not fitted:
        raise ParameterError("no impact with a lobe that can be fitted")

    def total(family, z):  # finite where a lobe fails (Brent's parabola takes differences)
        chi = sum(chi_squared(lobe, family, float(z)) for lobe in fitted)
        return chi if math.isfinite(chi) else sys.float_info.max

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
        if totals[(family, 0.0)] - best[family][0] < UNDAMPED_CHI_SQUARED:
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
