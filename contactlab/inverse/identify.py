"""Identify a force sensor's resonance and damping from its free ringing.

After the grain has left (or after a tap of a calibration hammer) the sensor rings freely:
its signal ``S1 = k1 x1 + c1 v1`` is a damped sinusoid with the sensor's own poles
``-zeta w +- i w sqrt(1 - zeta**2)``, ``w = 2 pi f1``, whatever the pulse was. During
contact the grain's stiffness shifts the frequency, so only the ringing after the last
contact is used.

The estimate is made in two steps: a matrix pencil (Hua & Sarkar 1990) on the window
gives the poles without a starting guess; a least-squares fit of a damped sine plus an
offset (``scipy.optimize.least_squares``) refines them on every sample, and its Jacobian
and residual variance give the standard errors.
"""

import itertools
import math
from dataclasses import asdict, dataclass

import numpy as np
from scipy.optimize import least_squares

from contactlab.blas import with_one_blas_thread
from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from contactlab.inverse._signal import (
    RINGING_EXCESS,
    check_window,
    difference_noise,
    lobe_around_peak,
    uniform_signal,
)
from contactlab.validation import check_count, check_interval, check_samples

__all__ = ["SensorIdentification", "identify_sensor", "matrix_pencil"]

MIN_WINDOW_SAMPLES = 20
"""Fewest samples in a ringing window: a pencil of order 3 needs a few times that."""

MIN_WINDOW_PERIODS = 2.0
"""Fewest ringing periods a window must span for frequency and decay to separate."""

DECAY_TIMES = 4.0
"""Length of the default ringing window in decay times ``1 / (zeta w)`` [-]: the ringing
falls to 2 % of its start, so later samples add little to the fit but let drift,
crosstalk or a bounce in (a 4 ms record with a drift of 20 noise sigmas was refused with
the window running to its end; ``docs/campaign.md``, "Single-trace paths")."""

ENVELOPE_SIGMAS = 6.0
"""The first pass's window ends where the ringing's half range over a block falls below
this many noise standard deviations [-] (the half range of pure noise over a few hundred
samples is about 3 sigma)."""

MIN_EXPLAINED = 0.5
"""Smallest fraction of the window's variance the damped sine must explain; below it
the window holds noise or a forced response, not free ringing."""


@dataclass(frozen=True)
class SensorIdentification:
    """Resonance and damping of a sensor identified from free ringing (SI units).

    ``resonance`` is the undamped natural frequency ``f1 = sqrt(k1/m1) / (2 pi)``, the
    quantity :meth:`contactlab.Sensor.from_resonance` takes; the ringing itself is at
    ``f1 sqrt(1 - zeta**2)``.
    """

    resonance: float
    """Undamped resonance frequency ``f1`` [Hz]."""
    damping_ratio: float
    """Damping ratio ``zeta1`` [-]."""
    resonance_stderr: float
    """Standard error of ``resonance`` [Hz] (Jacobian and residual variance)."""
    damping_ratio_stderr: float
    """Standard error of ``damping_ratio`` [-]."""
    window: tuple
    """Window ``(t0, t1)`` [s] of the ringing that was fitted."""
    amplitude: float
    """Ringing amplitude at ``t0`` (signal unit)."""
    phase: float
    """Phase ``phi`` [rad] of the ringing ``A exp(-zeta w tau) cos(w_d tau - phi)``."""
    offset: float
    """Offset of the signal at ``t0`` (signal unit)."""
    slope: float
    """Slope of the signal's baseline in the window (signal unit per second): drift."""
    residual_rms: float
    """Root-mean-square residual of the fit (signal unit): the noise if the model holds."""
    samples: int
    """Samples in the window."""
    status: str = "ok"
    """``"ok"``, or ``"not free ringing"`` when the fit leaves more than
    :data:`~contactlab.inverse.pulse.RINGING_EXCESS` times the record's noise (read on
    its sample-to-sample differences): crosstalk from the structure, a bounce or a
    second mode in the window."""
    notes: tuple = ()
    """Why the status is not ``"ok"``, with the numbers."""

    def ringing(self, t):
        """The fitted free ringing (baseline included) at times ``t`` [s] (signal unit).

        Parameters
        ----------
        t : array_like
            Times [s], 1-D, finite, not before the window's start (the free ringing is
            fitted from there on; before it the contact still drives the sensor).
        """
        t = check_samples("t", t, min_size=1, unit="s")
        if t.min() < self.window[0]:
            raise ParameterError(
                f"t must not be before the identification window's start "
                f"{self.window[0]:.6g} s (the free ringing starts there); got {t.min():.6g} s"
            )
        tau = t - self.window[0]
        w = 2.0 * math.pi * self.resonance
        wd = w * math.sqrt(1.0 - self.damping_ratio**2)
        decay = np.exp(-self.damping_ratio * w * tau)
        ringing = self.amplitude * decay * np.cos(wd * tau - self.phase)
        return ringing + self.offset + self.slope * tau

    def to_sensor(self, mass):
        """The identified sensor with a moving mass ``mass`` [kg] (:class:`contactlab.Sensor`)."""
        return Sensor.from_resonance(self.resonance, mass=mass, damping_ratio=self.damping_ratio)

    def to_dict(self, unit="N"):
        """Results with unit-bearing keys (JSON-ready).

        Parameters
        ----------
        unit : str, default "N"
            Unit of the signal the ringing was fitted to (``"V"`` for a trace read without
            a sensitivity): the unit of the amplitude, offset and residual.
        """
        units = {
            "resonance": "Hz",
            "damping_ratio": "-",
            "resonance_stderr": "Hz",
            "damping_ratio_stderr": "-",
            "window": "s",
            "amplitude": unit,
            "phase": "rad",
            "offset": unit,
            "slope": f"{unit}/s",
            "residual_rms": unit,
            "samples": "-",
            "status": "-",
            "notes": "-",
        }
        out = {f"{k} [{units[k]}]": v for k, v in asdict(self).items()}
        out["window [s]"] = list(self.window)
        out["status"], out["notes"] = out.pop("status [-]"), list(self.notes)
        out.pop("notes [-]")
        return out

    def __repr__(self):
        return (
            f"SensorIdentification(resonance={self.resonance:.6g} +- "
            f"{self.resonance_stderr:.2g} Hz, damping_ratio={self.damping_ratio:.4g} +- "
            f"{self.damping_ratio_stderr:.2g}, window=({self.window[0] * 1e6:.4g}, "
            f"{self.window[1] * 1e6:.4g}) us, samples={self.samples}, status={self.status!r})"
        ) + "".join(f"\n  note: {note}" for note in self.notes)


def matrix_pencil(y, dt, order):
    """Poles of a sum of damped exponentials by the matrix pencil method.

    Parameters
    ----------
    y : array_like
        Uniformly sampled signal ``y[n] = sum_k A_k z_k**n`` (+ noise), 1-D, finite, at
        least ``3 order`` samples.
    dt : float
        Sample interval [s], > 0.
    order : int
        Number of exponentials ``M`` (2 for a real damped sine, 3 with an offset), >= 1.

    Returns
    -------
    numpy.ndarray
        Continuous-time poles ``s_k = ln(z_k) / dt`` [1/s], complex.

    Notes
    -----
    Total-least-squares pencil: the Hankel matrix of the data (pencil parameter
    ``L = N/3``) is reduced to its ``M`` dominant right singular vectors ``V``; the poles
    are the eigenvalues of ``pinv(V[:-1]) V[1:]``. Noise in the discarded singular
    directions drops out, which makes the estimate close to the Cramer-Rao bound at
    moderate noise.

    References
    ----------
    Hua Y., Sarkar T.K. (1990) Matrix pencil method for estimating parameters of
    exponentially damped/undamped sinusoids in noise. IEEE Trans. Acoust. Speech Signal
    Process. 38, 814-824. DOI 10.1109/29.56027
    """
    order = check_count("order", order)
    y = check_samples("y", y, min_size=3 * order)
    dt = check_interval("dt", dt)
    n = y.size
    pencil = n // 3
    hankel = np.lib.stride_tricks.sliding_window_view(y, pencil + 1)
    _, _, vh = np.linalg.svd(hankel, full_matrices=False)
    v = vh[:order].T
    z = np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:])
    return np.log(z.astype(complex)) / dt


def _damped_sine(params, tau):
    """Model ``exp(-s tau) (a cos(wd tau) + b sin(wd tau)) + c + d tau`` and its
    Jacobian."""
    f, zeta, a, b, c, d = params
    w = 2.0 * math.pi * f
    root = math.sqrt(max(1.0 - zeta**2, 1e-300))
    s, wd = zeta * w, w * root
    e = np.exp(-s * tau)
    cos, sin = np.cos(wd * tau), np.sin(wd * tau)
    osc = a * cos + b * sin
    ds = -tau * e * osc  # d model / d s
    dwd = tau * e * (b * cos - a * sin)  # d model / d wd
    jac = np.column_stack(
        [
            ds * 2.0 * math.pi * zeta + dwd * 2.0 * math.pi * root,
            ds * w - dwd * w * zeta / root,
            e * cos,
            e * sin,
            np.ones_like(tau),
            tau,
        ]
    )
    return e * osc + c + d * tau, jac


def _linear_amplitudes(f, zeta, tau, y):
    """Best ``a, b, c, d`` for given frequency and damping (linear least squares)."""
    w = 2.0 * math.pi * f
    e = np.exp(-zeta * w * tau)
    wd = w * math.sqrt(1.0 - zeta**2)
    basis = np.column_stack([e * np.cos(wd * tau), e * np.sin(wd * tau), np.ones_like(tau), tau])
    return np.linalg.lstsq(basis, y, rcond=None)[0]


def _auto_window(t, y):
    """First free-ringing window: from two lengths of the largest lobe after its start to
    where the ringing has decayed into the noise (or the record's end).

    The largest lobe is the impact's (or the hammer's) main response. A pulse shorter
    than half a sensor period ends inside that lobe; a long pulse is followed by the
    signal within about a period, and the lobe is then as long as the pulse. Either way
    the contact is over one lobe-length after the lobe ends. The lobe is at least half a
    ringing period long, so blocks of two lobe-lengths hold a period or more: the window
    ends at the first block whose half range is under :data:`ENVELOPE_SIGMAS` noise
    standard deviations (read on the record's sample-to-sample differences, which drift
    and hum do not reach).
    """
    start, end = lobe_around_peak(t, y - _level(t, y))
    t0 = end + (end - start)
    noise = difference_noise(y)
    block = max(round(2.0 * (end - start) / (t[1] - t[0])), 2)
    after = y[t >= t0]
    for k in range(1, after.size // block):
        piece = after[k * block : (k + 1) * block]
        if 0.5 * float(np.ptp(piece)) < ENVELOPE_SIGMAS * noise:
            return t0, float(t0 + (k + 1) * block * (t[1] - t[0]))
    return t0, float(t[-1])


LEVEL_BLOCKS = 16
"""Blocks whose medians give the record's level (:func:`_level`) [-]."""


def _level(t, y):
    """The record's baseline as a line: the Theil-Sen line through the medians of
    :data:`LEVEL_BLOCKS` blocks, which a pulse and its ringing move little (a median is
    robust, and the line through the medians as well). Under a drift of 20 noise sigmas
    over 4 ms the record's median put the largest lobe's end 0.6 ms late, and the window
    after the ringing (``docs/campaign.md``)."""
    from scipy.stats import theilslopes  # scipy.stats is slow to import: only here

    edges = np.linspace(0, y.size, min(LEVEL_BLOCKS, y.size) + 1).astype(int)
    medians = [np.median(y[a:b]) for a, b in itertools.pairwise(edges)]
    centres = [0.5 * (t[a] + t[b - 1]) for a, b in itertools.pairwise(edges)]
    slope, intercept, *_ = theilslopes(medians, centres)
    return intercept + slope * t


def _status(residual_rms, noise):
    """Status and notes of a fit leaving ``residual_rms`` on a record of ``noise``."""
    if noise == 0.0 or residual_rms <= RINGING_EXCESS * noise:  # no noise: nothing to judge
        return "ok", ()
    return "not free ringing", (
        f"the damped sine leaves {residual_rms:.3g} rms, {residual_rms / noise:.1f} times the "
        "record's noise (from its sample-to-sample differences): crosstalk from the "
        "structure, a bounce or another mode in the window; give window= over free ringing",
    )


def _decay_window(window, f, zeta, last):
    """The window from ``window[0]`` over :data:`DECAY_TIMES` decay times [s] (at most
    to ``last``)."""
    return window[0], min(window[0] + DECAY_TIMES / (zeta * 2.0 * math.pi * f), last)


def _pencil_guess(y, dt, max_samples):
    """Frequency [Hz] and damping ratio of the dominant decaying mode, from the pencil."""
    q = max(1, math.ceil(y.size / max_samples))
    blocks = y[: y.size // q * q].reshape(-1, q).mean(axis=1)
    # block means of a sum of exponentials are again one, with poles z**q: exact decimation
    poles = matrix_pencil(blocks, q * dt, 3)
    oscillating = poles[poles.imag > 0]
    if oscillating.size == 0:
        raise ParameterError(
            "no ringing in the window: the matrix pencil finds no oscillating mode "
            "(choose the window after the pulse, where the sensor rings freely)"
        )
    pole = oscillating[0]
    w = abs(pole)
    return w / (2.0 * math.pi), -pole.real / w


@with_one_blas_thread
def identify_sensor(t, signal, window=None, *, max_pencil_samples=1000):
    """Resonance frequency and damping ratio of a sensor from its free ringing.

    Parameters
    ----------
    t : array_like
        Time [s], uniformly sampled.
    signal : array_like
        Sensor signal (N or V: only its shape matters), e.g. a grain impact recorded
        long enough to show the ringing after the grain has left, or a hammer tap.
    window : (float, float), optional
        Window ``(t0, t1)`` [s] of free ringing. Default: from the end of the largest
        lobe plus that lobe's length over :data:`DECAY_TIMES` decay times (see Notes).
    max_pencil_samples : int, default 1000
        The pencil works on block means of the window, at most this many (>= 20; the SVD of
        the Hankel matrix grows as the cube); the least-squares fit uses every sample.

    Returns
    -------
    SensorIdentification

    Raises
    ------
    ParameterError
        A window with fewer than 20 samples or shorter than two ringing periods, or
        without free ringing (no oscillating pole, a growing one, or a damped sine that
        explains less than half of the window's variance).

    Notes
    -----
    The model is ``y = exp(-zeta w tau) (a cos(w_d tau) + b sin(w_d tau)) + c + d tau``
    with ``tau = t - t0``, ``w = 2 pi f1``, ``w_d = w sqrt(1 - zeta**2)``: the free
    response of the sensor's two poles on a baseline line (an offset and a drift). The
    damped sine must explain half of what a line leaves. Standard errors are
    ``sqrt(diag((J^T J)^-1) * RSS / (n - 6))``, honest for white noise; coloured noise
    (a filtered trace) makes them optimistic by about the square root of the samples
    per correlation length.

    The automatic window starts one lobe-length after the end of the largest lobe of
    the signal (the lobe is the run of samples on one side of the record's level around
    the largest deviation; the level is a line through block medians, which follows a
    drift). A contact cannot outlast that point: a pulse shorter than half
    a sensor period ends inside the lobe, a longer one is tracked by the signal. A
    first fit runs to where the ringing has decayed into the noise (its half range over
    blocks of two lobe-lengths under :data:`ENVELOPE_SIGMAS` noise sigmas, or the
    record's end); the second, reported, runs :data:`DECAY_TIMES` decay times
    ``1 / (zeta w)`` of the first (at most to the record's end). A window to the record's
    end let a slow drift, the structure's ringing or a bounce outweigh the sensor's
    decayed ringing on a realistic record (``docs/campaign.md``). A grain that bounces
    back onto the sensor within the window still breaks the rule: give ``window`` then.

    References
    ----------
    Hua Y., Sarkar T.K. (1990) IEEE Trans. ASSP 38, 814-824. DOI 10.1109/29.56027
    (matrix pencil). Bates D.M., Watts D.G. (1988) Nonlinear Regression Analysis and
    Its Applications, Wiley, ch. 2 (standard errors from the Jacobian).
    DOI 10.1002/9780470316757

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(4000) * 5e-7
    >>> y = np.exp(-0.02 * 2 * np.pi * 40e3 * t) * np.cos(2 * np.pi * 40e3 * 0.9998 * t)
    >>> ident = identify_sensor(t, y, window=(0.0, t[-1]))
    >>> round(ident.resonance), round(ident.damping_ratio, 4)
    (40000, 0.02)
    """
    t, y, dt = uniform_signal(t, signal)
    max_pencil_samples = check_count("max_pencil_samples", max_pencil_samples, MIN_WINDOW_SAMPLES)
    noise = difference_noise(y)
    if window is not None:
        return _identify(t, y, dt, check_window("window", window), max_pencil_samples, noise)
    first = _identify(t, y, dt, _auto_window(t, y), max_pencil_samples, noise)
    window = _decay_window(first.window, first.resonance, first.damping_ratio, float(t[-1]))
    return _identify(t, y, dt, window, max_pencil_samples, noise)


def _identify(t, y, dt, window, max_pencil_samples, noise):
    """The damped sine's fit on one window (:func:`identify_sensor`)."""
    t0, t1 = window
    mask = (t >= t0) & (t <= t1)
    n = int(mask.sum())
    if n < MIN_WINDOW_SAMPLES:
        raise ParameterError(
            f"window ({t0:.6g}, {t1:.6g}) s holds {n} samples; need at least "
            f"{MIN_WINDOW_SAMPLES} of free ringing (record longer after the pulse)"
        )
    tau, yw = t[mask] - t0, y[mask]
    f, zeta = _pencil_guess(yw, dt, max_pencil_samples)
    if not 0.0 < zeta < 1.0:
        raise ParameterError(
            f"no decaying ringing in the window ({t0:.6g}, {t1:.6g}) s: the pencil's mode "
            f"has damping ratio {zeta:.3g} (need 0 < zeta < 1); give window= after the pulse"
        )
    x0 = np.concatenate([[f, zeta], _linear_amplitudes(f, zeta, tau, yw)])

    def residuals(p):
        return _damped_sine(p, tau)[0] - yw

    def jacobian(p):
        return _damped_sine(p, tau)[1]

    fit = least_squares(residuals, x0, jac=jacobian, method="lm", x_scale="jac")
    f, zeta, a, b, c, d = fit.x
    rss = float(fit.fun @ fit.fun)
    # the share of what a line leaves (drift is not ringing) that the damped sine explains
    line = np.polynomial.polynomial.polyfit(tau, yw, 1)
    detrended = yw - np.polynomial.polynomial.polyval(tau, line)
    explained = 1.0 - rss / float(detrended @ detrended)
    if not 0.0 < zeta < 1.0 or explained < MIN_EXPLAINED:
        raise ParameterError(
            f"no free ringing in the window ({t0:.6g}, {t1:.6g}) s: a damped sine "
            f"explains {max(explained, 0.0):.0%} of its variance about a line (need "
            f"{MIN_EXPLAINED:.0%}); give window= after the pulse"
        )
    periods = (t1 - t0) * f * math.sqrt(1.0 - zeta**2)
    if periods < MIN_WINDOW_PERIODS:
        raise ParameterError(
            f"window ({t0:.6g}, {t1:.6g}) s spans {periods:.2g} ringing periods; need at "
            f"least {MIN_WINDOW_PERIODS:g} to separate frequency and decay"
        )
    jac = jacobian(fit.x)
    covariance = np.linalg.inv(jac.T @ jac) * rss / (n - x0.size)
    stderr = np.sqrt(np.diag(covariance))
    return SensorIdentification(
        resonance=float(f),
        damping_ratio=float(zeta),
        resonance_stderr=float(stderr[0]),
        damping_ratio_stderr=float(stderr[1]),
        window=(float(t0), float(t1)),
        amplitude=float(math.hypot(a, b)),
        phase=float(math.atan2(b, a)),
        offset=float(c),
        slope=float(d),
        residual_rms=math.sqrt(rss / n),
        samples=n,
        **dict(zip(("status", "notes"), _status(math.sqrt(rss / n), noise), strict=True)),
    )
