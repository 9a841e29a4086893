"""A contact family's force through the sensor on a record's window, fitted by least
squares (:mod:`contactlab.inverse.lobe_onset` fits its onset and duration with it).

The record's force is ``A h((t - t0) / tau)`` (the unit shape ``h`` of
:func:`force_shape`) and its signal that force through the sensor (``k1 x1 + c1 v1``,
the transfer function ``(c1 p + k1) / (m1 p**2 + c1 p + k1)``), plus a line for the
drift. ``A`` and the line are linear least squares (variable projection); with a noise
model (an autoregressive process, :class:`contactlab.inverse.noise_colour.ARNoise`) the
record and every column are whitened by its filter ``A(z)`` first (generalised least
squares): the slow part of 1/f noise, which a fit that takes it as white reads as the
pulse's shape, then weighs as little as it carries.
"""

import functools
import math

import numpy as np
from scipy import integrate, linalg, signal

from contactlab.errors import ParameterError
from contactlab.kernels.held_force import held_signal, sampled_signal
from contactlab.kernels.lobe_cost import fitted_rss, scanned_rss, simplex_fit, white_signal

__all__ = ["FAMILIES", "FINE_PERIODS", "SHAPE_POINTS", "LobeModel", "force_shape"]

FAMILIES = {"linear": (1.0, 0.0), "hertz": (1.5, 0.25)}
"""Contact families ``name: (n, m)``: the force ``d**n + 2 zeta d**m d'`` [-] (a linear
spring-dashpot; Hertz with Tsuji's damping, undamped Hertz at ``zeta = 0``)."""

SHAPE_POINTS = 4096
"""Samples of the unit force shape on its unit duration [-] (interpolated linearly: a
relative error below 1e-6 of the peak where the shape is smooth)."""

FINE_PERIODS = 1.0 / 128.0
"""The force is pushed through the sensor on a step of at most this many sensor periods
and half a sample [-] (the first-order hold is exact for a piecewise-linear force; the
signal, interpolated linearly between the steps, is then within ``(2 pi / 128)**2 / 8 =
3e-4`` of its peak; a damped contact's force step is centred on its step)."""


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


def _identity(values):
    return np.asarray(values, dtype=float)


class LobeModel:
    """The signal of ``A h((t - t0) / tau)`` plus a line on a window, for the fit and
    its bound.

    Parameters
    ----------
    t, y : numpy.ndarray
        The window's time [s] (uniform) and signal [N].
    sensor : contactlab.Sensor
        The moving sensor.
    family : str
        A name of :data:`FAMILIES`.
    damping : float
        Its damping ratio [-].
    noise_model : ARNoise, optional
        The record's noise per sample; its filter whitens the record and the columns
        (the first ``p`` samples only start it). None: white noise.
    """

    def __init__(self, t, y, sensor, family, damping, noise_model=None):
        self.t, self.y = t, y
        self.dt = float(t[1] - t[0])
        self.u, self.h = force_shape(family, damping)
        self.family, self.damping = family, damping
        self.fine = math.ceil(max(2.0, self.dt / (FINE_PERIODS * sensor.period)))
        self.filter = _sensor_filter(
            sensor.angular_frequency, sensor.damping_ratio, self.dt / self.fine
        )
        self.period = sensor.period
        coloured = noise_model is not None and noise_model.order > 0
        self.whiten = noise_model.whiten if coloured else _identity
        self.ar = noise_model.coefficients if coloured else np.zeros(0)
        centre = float(t.mean())
        self.line = np.column_stack([np.ones_like(t), (t - centre) / self.period])
        self.line_w, self.y_w = self.whiten(self.line), self.whiten(y)
        self.basis = np.linalg.qr(self.line_w)[0]
        self.y_off = self.y_w - self.basis @ (self.basis.T @ self.y_w)
        self.y_rss = float(self.y_off @ self.y_off)
        self._fitted = (np.ascontiguousarray(self.basis), self.y_off, self.y_rss)
        grid = (self.dt / self.fine, self.fine * (t.size + 2))  # as unit() builds it
        compiled = [np.ascontiguousarray(a, dtype=float) for a in (t, self.ar)]  # one type
        self._problem = (compiled[0], *grid, self.u, self.h, *self.filter, compiled[1], self.fine)
        self._problem += self._fitted

    def unit(self, tau, shape=None):
        """The unit-peak signal against the time since the force's start: time [s] and
        signal [-]. The force starts half a fine step after a fine sample, so that the
        hold's ramp over that step centres a damped contact's force step on it.
        ``shape``: another ``(u, h)`` than the model's."""
        u, h = (self.u, self.h) if shape is None else shape
        count = self.fine * (self.t.size + 2)
        return held_signal(self.dt / self.fine, count, float(tau), u, h, *self.filter)

    def white_unit(self, tau):
        """:meth:`unit` whitened on its fine grid: ``r(s) - sum_k a_k r(s - k dt)``, the
        sample step ``dt`` being ``fine`` grid steps. Whitening commutes with the shift
        by ``t0``, so that the whitened column at any onset is this one sampled (its
        first ``p`` samples, which the filter needs before the window, dropped)."""
        s, r = self.unit(tau)
        return s, white_signal(r, self.ar, self.fine)

    def response(self, t0, tau, unit=None):
        """The unit-peak signal on the window's samples [-] (``unit``: :meth:`unit` of
        ``tau``, when already computed)."""
        s, r = self.unit(tau) if unit is None else unit
        return sampled_signal(self.t, float(t0), s, r)  # numpy.interp(t - t0, s, r, left=0)

    def solve(self, t0, tau, unit=None, coefficients=True):
        """Linear amplitudes (offset, slope over a sensor period, ``A``; only ``A``
        without ``coefficients``) and the residual sum of squares of the whitened record
        (the signal's column projected off the line's orthonormal basis). ``unit``:
        :meth:`white_unit` of ``tau``, when already computed."""
        if not tau > 0.0:
            return np.full(3, np.nan), math.inf
        unit = self.white_unit(tau) if unit is None else unit
        r = self.response(t0, tau, unit)[self.ar.size :]
        r_off = r - self.basis @ (self.basis.T @ r)
        norm = float(r_off @ r_off)
        if not norm > 0.0:  # no force inside the window
            return np.full(3, np.nan), math.inf
        amplitude = float(r_off @ self.y_off) / norm
        rss = max(self.y_rss - amplitude * amplitude * norm, 0.0)
        if not coefficients:
            return amplitude, rss
        line = np.linalg.lstsq(self.line_w, self.y_w - amplitude * r, rcond=None)[0]
        return np.array([*line, amplitude]), rss

    def rss(self, t0, tau):
        """The residual sum of squares of :meth:`solve` [N**2] in one compiled call
        (:func:`contactlab.kernels.lobe_cost.fitted_rss`): the fits' objective.
        ``inf`` where ``tau`` is not positive or no force lies inside the window."""
        if not tau > 0.0:
            return math.inf
        return fitted_rss(float(t0), float(tau), *self._problem)[1]

    def fit(self, simplex, xatol, fatol):
        """The onset and duration of least residual, Nelder-Mead from ``simplex``
        (``(3, 2)``: ``(t0 [s], tau [s])`` vertices) to the vertices' spread ``xatol``
        [s] and the residuals' ``fatol`` [N**2]: scipy's ``minimize(method="Nelder-Mead")``
        of :meth:`rss` compiled (:func:`contactlab.kernels.lobe_cost.simplex_fit`, equal to
        it to the last bit). Returns ``(t0, tau)`` [s]."""
        simplex = np.ascontiguousarray(simplex, dtype=float)
        most = 200 * simplex.shape[1]  # scipy's evaluations and iterations by default
        best, _ = simplex_fit(simplex, float(xatol), float(fatol), most, self._problem)
        return float(best[0]), float(best[1])

    def scan(self, onsets, tau):
        """The residual sum of squares at each of ``onsets`` [s] for one duration
        ``tau`` [s] > 0 [N**2] (:func:`contactlab.kernels.lobe_cost.scanned_rss`)."""
        s, r = self.white_unit(tau)
        times = self._problem[0]  # the window's times as the compiled calls take them
        return scanned_rss(times, np.asarray(onsets, float), s, r, self.ar.size, *self._fitted)

    def _jacobian(self, t0, tau, damping_free):
        """Derivatives of the model at the fit (unwhitened): ``t0`` per sample, ``tau``
        relative, [the damping ratio,] the line and the amplitude; central differences
        of a tenth of a sample, the damping's one-sided over 0.01."""
        coefficients, _ = self.solve(t0, tau)
        ht, htau = 0.1 * self.dt, 1e-3 * tau
        d_t0 = (self.response(t0 + ht, tau) - self.response(t0 - ht, tau)) / (2.0 * ht)
        d_tau = (self.response(t0, tau + htau) - self.response(t0, tau - htau)) / (2.0 * htau)
        a = coefficients[2]
        columns = [a * d_t0 * self.dt, a * d_tau * tau, self.line, self.response(t0, tau)]
        if damping_free:
            other = self.unit(tau, force_shape(self.family, self.damping + 0.01))
            d_zeta = (self.response(t0, tau, other) - self.response(t0, tau)) / 0.01
            columns.insert(2, a * d_zeta)
        return np.column_stack(columns)

    def bound(self, t0, tau, noise, damping_free):
        """Cramér-Rao bound of ``t0`` [s] for noise of standard deviation ``noise`` [N]
        (the whitened noise's: the innovation's with a noise model), with the damping
        ratio a nuisance parameter too where ``damping_free``."""
        jacobian = self.whiten(self._jacobian(t0, tau, damping_free))
        try:
            covariance = np.linalg.inv(jacobian.T @ jacobian)
        except np.linalg.LinAlgError:  # no rise in the window: no information on t0
            return math.inf
        return float(math.sqrt(max(covariance[0, 0], 0.0)) * noise * self.dt)

    def onset_spread(self, t0, tau, autocovariance):
        """Standard deviation of the fitted ``t0`` [s] under Gaussian noise of the given
        autocovariance (lags ``0, 1, ...`` samples, at least the window's length)
        [N**2], the damping known: the fit as it is made (least squares, whitened with
        the model's noise model if it has one), linearised at ``(t0, tau)``.

        ``t0 - t0_true ~ g' e`` for the noise ``e`` on the window, with ``g = W' A
        (A' A)**-1 u`` (``W`` the whitening, ``A = W J`` the whitened derivatives,
        ``u`` the unit vector of ``t0``), so its variance is ``g' S g`` with ``S`` the
        noise's Toeplitz covariance (the sandwich of least squares under a covariance
        it does not weigh by; the Cramér-Rao bound under ``S`` when ``W' W = S**-1``).
        """
        whitened = self.whiten(self._jacobian(t0, tau, False))
        try:
            row = np.linalg.solve(whitened.T @ whitened, np.eye(whitened.shape[1])[0])
        except np.linalg.LinAlgError:  # no rise in the window: no information on t0
            return math.inf
        influence = self._whiten_adjoint(whitened @ row)
        n = influence.size
        covariance_times = linalg.matmul_toeplitz(np.asarray(autocovariance)[:n], influence)
        return float(math.sqrt(max(float(influence @ covariance_times), 0.0)) * self.dt)

    def damping_terms(self, t0, tau, autocovariance):
        """What an error of the damping ratio, read on several impacts of a record, adds
        to the onset's variance (:func:`dem_check.campaign.onsets.record_onsets` sums
        them): ``(shift, information, noise, cross)``.

        With the damping fixed ``d`` too high, the fit's onset moves by ``-shift * d``
        (``shift`` [s] per unit damping ratio, the other parameters refitted). A damping
        read by least squares on impacts ``F`` errs by ``d = sum_F u_W' e / sum_F
        information``, ``u`` the whitened damping column made orthogonal to the fit's
        others, ``u_W = W' u``, ``information = u' u`` [N**2]; ``noise = u_W' S u_W``
        [N**4] is the variance of its numerator's term, ``cross = g' S u_W`` [s N**2] its
        covariance with this impact's onset error ``g' e`` (:meth:`onset_spread`).
        Linearised at the fit; the damping's derivative one-sided over 0.01.
        """
        whitened = self.whiten(self._jacobian(t0, tau, True))
        zeta = whitened[:, 2]
        known = np.delete(whitened, 2, axis=1)
        normal = known.T @ known
        back = np.linalg.solve(normal, known.T @ zeta)
        row = np.linalg.solve(normal, np.eye(known.shape[1])[0])
        u = zeta - known @ back
        influence, u_w = self._whiten_adjoint(known @ row), self._whiten_adjoint(u)
        s_u = linalg.matmul_toeplitz(np.asarray(autocovariance)[: u_w.size], u_w)
        return (
            float(back[0]) * self.dt,
            float(u @ u),
            float(u_w @ s_u),
            float(influence @ s_u) * self.dt,
        )

    def _whiten_adjoint(self, values):
        """``W' v``: the adjoint of :attr:`whiten` (``W`` drops the first ``p`` rows and
        subtracts ``a_k`` times the samples ``k`` before)."""
        p = self.ar.size
        out = np.zeros(values.size + p)
        out[p:] += values
        for k, a in enumerate(self.ar, start=1):
            out[p - k : out.size - k] -= a * values
        return out
