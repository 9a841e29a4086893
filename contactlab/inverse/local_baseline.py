"""The local baseline of one impact, fitted on both sides of it, and its impulse.

A laboratory record's baseline moves under an impact: drift, wander, hum and the slow
part of 1/f noise. One constant read before the impact (or on the record's quietest
stretch) leaves the baseline's change under the pulse in the signal: on a realistic
record with a drift of 20 noise sigmas over 4 ms the reconstructed contact lasted twice
as long as the true one (``docs/campaign.md``, "Single-trace paths"). So an impact gets
its own baseline, fitted on the record where the signal holds no impact:

- before it, the last :data:`PRE_PERIODS` sensor periods of its baseline window (the
  quiet samples just before it);
- after its contact, :data:`POST_PERIODS` sensor periods of the sensor's free ringing,
  fitted together with the baseline as the damped sinusoid the sensor's resonance and
  damping ratio give (two amplitudes: the sensor's state when the contact has ended).

The baseline is a line (:data:`DEGREE`) through both sides. The impulse is the integral
of the record less this baseline up to the start of the post-contact window, plus the
fitted free ringing's integral from there on in closed form: for a ringing
``exp(-a s) (A cos(b s) + B sin(b s))`` with ``a = zeta w``, ``b = w sqrt(1 - zeta**2)``
that is ``(A a + B b) / w**2``. The integral is then taken over the contact and a few
periods, not over the whole decay of the ringing (about 1 ms for a 40 kHz sensor of
damping 0.02), so the noise, 1/f noise and hum add far less to it; and the baseline
under it is read on both sides instead of extrapolated from before it.

A record too coarse to resolve the sensor's ringing (fewer than four samples per period)
is integrated to the end of the decayed ringing, with the baseline fitted before the
impact and after the decay.

The fit also says how far the baseline can be trusted (:class:`LocalBaseline`): how much
it changes across the pulse (``drift``) against the noise before it, and how much of the
post-contact window the sensor's free ringing leaves unexplained (``post_noise`` against
``noise``: structural crosstalk, a bounce or a wrong sensor model leave more than noise).
Used by the campaign (:mod:`dem_check.campaign.analysis`) and the single-trace paths
(:mod:`contactlab.inverse.pulse`).

A single trace that starts at its pulse has nothing before it: :func:`head_baseline`
fits the campaign's head level (:func:`contactlab._head_level.head_fit`: a line, or a
quadratic where its curvature is significant, robust loss) together with the free
ringing on :data:`HEAD_PERIODS` sensor periods after the contact and extrapolates it
back under the pulse; a constant there was 9.6-9.8 noise sigmas off under a drift of
100 sigmas over 4 ms (``docs/campaign.md``, "Single-trace paths").
"""

import math
from dataclasses import dataclass

import numpy as np

from contactlab._head_level import HEAD_MIN_SAMPLES, head_fit
from contactlab.inverse.noise_prediction import BLOCK_PER_PERIOD, predict_gap
from contactlab.metrics import impulse

__all__ = [
    "DEGREE",
    "HEAD_PERIODS",
    "POST_PERIODS",
    "PRE_PERIODS",
    "LocalBaseline",
    "free_ringing",
    "head_baseline",
    "local_baseline",
]

DEGREE = 1
"""Degree of the local baseline polynomial [-]: a line through the quiet samples before
the impact and the ringing after its contact. Drift, wander and hum are smooth over the
~1 ms the fit spans; a higher degree extrapolates the 1/f noise of each side across the
impact instead of averaging it."""

POST_PERIODS = 16.0
"""Sensor periods after the contact fitted with the free ringing [-] (at least
:data:`POST_MIN_SAMPLES`): enough to average the noise out of the ringing's two
amplitudes, short against the drift."""

POST_MIN_SAMPLES = 32
"""Fewest samples of the post-contact window [-]."""

PRE_PERIODS = 8.0
"""Sensor periods of the baseline window just before the impact that are fitted [-]
(at least :data:`POST_MIN_SAMPLES`): 1/f noise is best interpolated under the impact
from samples near it (over 12 impacts at 5 MHz with 1/f noise as large as the white
noise, the impulse's rms error was 2.1 % with 8 periods, 3.1 % with 20)."""

RESOLVED_PERIOD_SAMPLES = 4
"""Fewest samples per sensor period for the free ringing to be fitted [-]."""

DECAY_TIMES = 5.0
"""Decay times ``1 / (zeta w)`` of the sensor's ringing after the contact from which
:func:`head_baseline` fits a record too coarse to resolve it [-] (``exp(-5)``: under 1 %
of its amplitude is left)."""

HEAD_PERIODS = 64.0
"""Fit window of :func:`head_baseline` after the contact [sensor periods] (at least
:data:`~contactlab._head_level.HEAD_MIN_SAMPLES` samples): the campaign's block
(``dem_check.campaign.noise.BLOCK_PERIODS``, one of which its head fit spans), 1.6 ms
for a 40 kHz sensor: 16 times a 100 us contact, so the level is extrapolated back over
a short stretch, and short against thermal and charge-amplifier drift."""


@dataclass(frozen=True, eq=False)
class LocalBaseline:
    """The local baseline of one impact and what it gives."""

    window: tuple
    """The baseline window's part that was fitted ``[start, end)`` [s] (its last
    :data:`PRE_PERIODS` periods before the impact)."""
    values: np.ndarray
    """The baseline at every sample of the segment [N] (with a noise model, plus the
    noise predicted under the pulse)."""
    post: tuple
    """Post-contact window ``[start, end]`` [s] the baseline (and ringing) were fitted on."""
    impulse: float
    """Impulse of the contact force [N*s]: the record less the baseline integrated from
    the impact's start to ``post[0]``, plus the fitted free ringing's integral after it."""
    noise: float
    """Standard deviation of the record less the baseline in the baseline window [N]
    (``nan`` when it holds fewer than 2 of the fitted samples)."""
    post_noise: float
    """Root-mean-square residual of the baseline and free ringing in the post-contact
    window [N]: the noise, if that window holds only the sensor's free ringing."""
    drift: float
    """Change of the baseline from the impact's start to ``post[0]`` [N] (signed); for a
    constant baseline (one side only), the change of a line through the fit's residual
    over the fitted samples: a drift the constant could not follow; for a head level
    (:func:`head_baseline`), a line through what the fit leaves on the post-contact
    window (its free ringing refitted there), extrapolated back to the record's first
    sample: a drift near the pulse that the fit did not follow."""
    head: tuple = ()
    """For a head level: the samples it was fitted on ``[start, end]`` [s] and its
    degree, ``(start, end, degree)``; empty otherwise."""
    ringing: tuple = ()
    """The fitted free ringing's amplitudes ``(A, B)`` [N] at ``post[0]``
    (``exp(-a s) (A cos(b s) + B sin(b s))``, ``s = t - post[0]``; :func:`free_ringing`
    gives its values); empty when the ringing is not resolved."""
    impulses: tuple = ()
    """Impulses of the further records given as ``also`` [N*s], read with this fit
    (:func:`local_baseline`); empty when none was given."""


def _ringing(s, sensor):
    """Columns of the sensor's free ringing ``exp(-a s) cos(b s)``, ``... sin(b s)``."""
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    a, b = zeta * w, w * math.sqrt(max(1.0 - zeta**2, 0.0))
    decay = np.exp(-a * s)
    return np.stack([decay * np.cos(b * s), decay * np.sin(b * s)], axis=1), a, b


def free_ringing(t, start, amplitudes, sensor):
    """The sensor's free ringing ``exp(-a s) (A cos(b s) + B sin(b s))``, ``s = t -
    start``, at the times ``t`` [s] (:attr:`LocalBaseline.ringing`'s amplitudes ``(A,
    B)`` [N] at ``start`` [s]); extrapolated before ``start`` too (it is free ringing only
    after the contact: the caller keeps the samples where it is)."""
    columns, _, _ = _ringing(np.asarray(t, dtype=float) - start, sensor)
    return columns @ np.asarray(amplitudes, dtype=float)


def _rms(values, ddof):
    """Root-mean-square of ``values`` with ``ddof`` degrees used (``nan`` if too few)."""
    if values.size <= ddof:
        return math.nan
    return math.sqrt(float(values @ values) / (values.size - ddof))


def _post_window(t, contact_end, end, sensor):
    """Whether the sensor's ringing is resolved, and the post-contact window ``[start,
    end]`` [s]: :data:`POST_PERIODS` from ``contact_end`` (from ``end``, the decayed
    ringing, on a coarse record), at least :data:`POST_MIN_SAMPLES` before the record's
    end."""
    dt = float(t[1] - t[0])
    resolved = sensor.period / dt >= RESOLVED_PERIOD_SAMPLES
    length = max(POST_MIN_SAMPLES * dt, POST_PERIODS * sensor.period)
    post_start = contact_end if resolved else end
    post_start = min(post_start, float(t[-1]) - POST_MIN_SAMPLES * dt)
    return resolved, (post_start, min(post_start + length, float(t[-1])))


def _tail(amplitudes, a, b, sensor):
    """Integral of the free ringing ``exp(-a s) (A cos(b s) + B sin(b s))`` from its
    start to infinity [N*s] (module docstring)."""
    amplitude_cos, amplitude_sin = amplitudes
    return (amplitude_cos * a + amplitude_sin * b) / sensor.angular_frequency**2


def local_baseline(
    t, y, base, start, contact_end, end, sensor, noise=None, exclude=None, also=None
):
    """Fit the local baseline of one impact and integrate its impulse (module docstring).

    Parameters
    ----------
    t, y : numpy.ndarray
        The impact's segment: time [s] and the record [N].
    base : (float, float)
        Baseline window ``[start, end)`` [s], before the impact or (short pre-trigger)
        after its ringing (an empty window after the impact: the post-contact window
        alone gives the baseline, a constant).
    start : float
        Where the impulse integral starts [s] (the end of the baseline window before
        the impact, or the segment's first sample).
    contact_end : float
        A time after the contact has ended [s] (the post-contact window starts there).
    end : float
        When the ringing had decayed [s] (the integral's end on a coarse record).
    sensor : Sensor
    noise : ColouredNoise, optional
        The record's noise (:func:`contactlab.inverse.noise_prediction.estimate_coloured_noise`):
        with it, and a baseline on both sides of a resolved impact, the line and ringing
        are fitted by generalised least squares and the noise from ``start`` to the
        post-contact window is predicted from both sides and taken off with the line
        (:func:`contactlab.inverse.noise_prediction.predict_gap`).
    exclude : numpy.ndarray of bool, optional
        Samples of the segment that hold another impact (its onset to its decayed
        ringing): left out of both sides' fit and of the samples the noise under the
        pulse is predicted from; what they hold is signal, not baseline or noise.
    also : numpy.ndarray, optional
        ``(len(t), k)``: further records whose impulses are read with this fit's
        windows and noise model (:attr:`LocalBaseline.impulses`); the impulse is linear
        in the record, so the columns of a fitted model give its share of the impulse
        (``contactlab.inverse.crosstalk.Crosstalk.share``) at the cost of one fit.

    Returns
    -------
    LocalBaseline
    """
    dt = float(t[1] - t[0])
    resolved, post = _post_window(t, contact_end, end, sensor)
    if base[1] <= start:  # a baseline before the impact: its last PRE_PERIODS
        near = max(PRE_PERIODS * sensor.period, POST_MIN_SAMPLES * dt)
        base = (max(base[0], base[1] - near), base[1])
    kept = np.ones(t.size, dtype=bool) if exclude is None else ~exclude
    in_base = (t >= base[0]) & (t < base[1]) & kept
    in_post = (t >= post[0]) & (t <= post[1]) & ~in_base & kept
    fitted = in_base | in_post
    centre = float(t[fitted].mean())
    scale = max(float(np.ptp(t[fitted])), dt)
    # a line needs both sides: read on one side (a short pre-trigger's baseline lies
    # after the ringing) it would be extrapolated back over the ringing's decay, so a
    # constant is taken instead (on the real hammer records a line put the baseline
    # under the hit 0.1-0.2 N off, a constant within 0.03 N)
    degree = DEGREE if base[1] <= start and in_base.any() else 0
    powers = np.vander((t - centre) / scale, degree + 1, increasing=True)
    columns = [powers]
    if resolved:
        ringing, a, b = _ringing(np.maximum(t - post[0], 0.0), sensor)
        ringing[~in_post] = 0.0
        columns.append(ringing)
    design = np.concatenate(columns, axis=1)
    records = (y if also is None else np.column_stack([y, also])).reshape(t.size, -1)
    predicted = np.zeros(records.shape)
    if noise is not None and resolved and degree > 0:
        # GLS on both sides and the noise under the pulse predicted from them
        q = max(1, round(sensor.period / dt / BLOCK_PER_PERIOD))
        under = np.flatnonzero((t >= start) & (t <= post[0]))
        coefficients, predicted[under] = predict_gap(
            noise.autocovariance(t.size),
            records,
            design,
            np.flatnonzero(in_base),
            np.flatnonzero(in_post),
            under,
            q,
        )
    else:
        coefficients, *_ = np.linalg.lstsq(design[fitted], records[fitted], rcond=None)
    lines = powers @ coefficients[: degree + 1]

    def integral(k):  # the impulse of record k (its line, prediction and ringing)
        if not resolved:
            return float(impulse(t, records[:, k] - lines[:, k], start, end))
        tail = _tail(coefficients[degree + 1 :, k], a, b, sensor)
        return float(
            impulse(t, records[:, k] - lines[:, k] - predicted[:, k], start, post[0]) + tail
        )

    total, impulses = integral(0), tuple(integral(k) for k in range(1, records.shape[1]))
    coefficients, predicted, line = coefficients[:, 0], predicted[:, 0], lines[:, 0]
    residual = y - design @ coefficients
    if degree > 0:
        drift = float(np.interp(post[0], t, line) - np.interp(start, t, line))
    else:  # a constant: how far a line through what it leaves moves over the fitted span
        slope = np.polynomial.polynomial.polyfit(t[fitted], residual[fitted], 1)[1]
        drift = float(slope * np.ptp(t[fitted]))
    return LocalBaseline(
        window=tuple(base),
        values=line + predicted,
        post=post,
        impulse=total,
        impulses=impulses,
        noise=_rms(residual[in_base] - residual[in_base].mean(), 1) if in_base.any() else math.nan,
        post_noise=_rms(residual[in_post], 2 if resolved else 0),
        drift=drift,
        ringing=tuple(float(v) for v in coefficients[degree + 1 :]) if resolved else (),
    )


def head_baseline(t, y, contact_end, end, sensor):
    """The local baseline of a pulse at the record's first sample (short pre-trigger):
    the head level fitted with the sensor's free ringing after the contact, extrapolated
    back under the pulse (module docstring), and the impulse.

    The fit is :func:`contactlab._head_level.head_fit`, the campaign's (a line, or a
    quadratic where its curvature is 3 standard errors; ``soft_l1`` loss), on
    :data:`HEAD_PERIODS` sensor periods from the post-contact window's start, with the
    ringing's two columns there; past the fit window the polynomial is extrapolated
    (only the pulse and the post-contact window are read on it). On a record too coarse
    to resolve the ringing it is fitted without it, from :data:`DECAY_TIMES` decay
    times after ``contact_end`` (an aliased ringing is not zero-mean: fitted from the
    contact at 3 samples a period, a quadratic took it for drift, 4.6 noise sigmas off),
    and the impulse integrated to ``end``.

    Parameters
    ----------
    t, y : numpy.ndarray
        The record from its first sample: time [s] and signal [N].
    contact_end : float
        A time after the contact has ended [s] (the post-contact window starts there).
    end : float
        When the ringing had decayed [s] (the integral's end on a coarse record).
    sensor : Sensor

    Returns
    -------
    LocalBaseline
        ``window`` empty at ``post[0]``, ``noise`` nan (nothing before the pulse),
        ``drift`` the residual's drift near the pulse extrapolated under it, ``head``
        the fit window and degree.

    Raises
    ------
    ParameterError
        Fewer than :data:`~contactlab._head_level.HEAD_MIN_SAMPLES` samples after the
        contact.
    """
    dt = float(t[1] - t[0])
    resolved, post = _post_window(t, contact_end, end, sensor)
    if not resolved:  # from where the unresolved ringing has decayed
        decayed = contact_end + DECAY_TIMES / (sensor.damping_ratio * sensor.angular_frequency)
        decayed = min(decayed, float(t[-1]) - HEAD_MIN_SAMPLES * dt)
        post = (decayed, min(decayed + post[1] - post[0], float(t[-1])))
    head = int(np.searchsorted(t, post[0]))
    columns = None
    if resolved:
        columns, a, b = _ringing(np.maximum(t - post[0], 0.0), sensor)
        columns[:head] = 0.0
    width = max(HEAD_MIN_SAMPLES, round(HEAD_PERIODS * sensor.period / dt))
    fit = head_fit(y, head, width, columns=columns)
    level = fit.level(np.arange(t.size))
    residual = y - level - (0.0 if columns is None else columns @ fit.extra)
    if resolved:
        total = impulse(t, y - level, float(t[0]), post[0]) + _tail(fit.extra, a, b, sensor)
    else:
        total = impulse(t, y - level, float(t[0]), end)
    in_post = (t >= post[0]) & (t <= post[1])
    first, last = fit.window
    return LocalBaseline(
        window=(post[0], post[0]),
        values=level,
        post=post,
        impulse=float(total),
        noise=math.nan,
        post_noise=_rms(residual[in_post], 2 if resolved else 0),
        drift=_residual_drift(t, residual, in_post, None if columns is None else columns[:, :2]),
        head=(float(t[first]), float(t[last]), fit.degree),
    )


def _residual_drift(t, residual, in_post, ringing):
    """A line through ``residual`` on the post-contact window (with the free ringing's
    ``ringing`` columns refitted there, when resolved), at the record's first sample
    [N]: how far a drift near the pulse that the head level did not follow moves the
    baseline under it (white noise: about 0.1 noise sigmas)."""
    centre = float(t[in_post].mean())
    columns = [np.ones(int(in_post.sum())), t[in_post] - centre]
    if ringing is not None:
        columns += [ringing[in_post, 0], ringing[in_post, 1]]
    coefficients, *_ = np.linalg.lstsq(np.column_stack(columns), residual[in_post], rcond=None)
    return float(coefficients[0] + coefficients[1] * (float(t[0]) - centre))
