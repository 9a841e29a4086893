"""The structure's free ringing after an impact, fitted around a later candidate: does it
explain the candidate?

A force sensor stands on a plate; a strong hit rings the plate's modes (a few hundred
hertz to a few kilohertz) for milliseconds, and their sum swings the record's level by a
tenth of a newton within a tenth of a millisecond (issue 22: the 1890 and 4100 Hz modes
of a 3.6 N impact, 2 % crosstalk). The running baseline's blocks (1.6 ms for a 40 kHz
sensor) do not follow such a swing, so its trough, with a noise excursion on it, can
reach the detection threshold: a ``negative`` impact 0.95 ms after a 3.59 N one
(``benchmarks/bench_steps.py``, seed 28), and the period means a level change across
an impact (a -0.125 N step 0.41 ms after a 3.8 N impact, seed 53). A compressive force
sensor gives no negative main lobe and a plate's ringing is no step; both are judged
against the plate's model:

1. **Window.** From a sensor period after the earlier impact's main lobe (its contact
   is over) to :data:`SPAN` after the candidate (or before the next impact, or the
   record's end).
2. **Modes.** Damped sinusoids in the structure's band, their poles started on grids of
   one an octave and refined by variable projection on the window's period means
   (:func:`_refined`, :func:`contactlab.inverse.ringdown.refine_unheld`): no mode need
   be known (``dem_check.campaign.structure.record_modes`` finds none on records whose
   hits are 1-3 ms apart).
3. **Fit.** A quadratic (drift, slow wander), the sensor's free ringing from the
   window's start and each mode's free ringing, by least squares.
4. **A negative candidate** (:func:`negative_swing`): the fit leaves out its run with
   :data:`MARGIN_PERIODS` sensor periods either side; when the record less the model,
   smoothed as for detection, stays under the detection threshold over the run, the
   plate's ringing predicted from both sides of it explains it, and it is listed with
   status :data:`STATUS` and the numbers in its reason, not as an impact. Otherwise it
   stays ``negative``.
5. **A step in an impact's ringing** (:func:`judged_steps`): the ringing alone against
   the ringing and the step, by Akaike's criterion (:func:`step_or_swing`).

Seed 28: modes of 734, 1885 and 4113 Hz found (the record's model: 730, 1890 and 4100
Hz); the candidate's -0.140 N (7.06 local sigmas) is left at 2.3 local sigmas. Seed 53:
the period means fitted to 0.013 N rms by the ringing alone, 0.045 N with the step.
Akaike's criterion as in :mod:`dem_check.campaign.edge_models` (Akaike 1974, cited
there).
"""

import dataclasses
import math

import numpy as np
from scipy.ndimage import gaussian_filter1d, uniform_filter1d

from contactlab.inverse.crosstalk import BAND_FRACTION, MAX_DAMPING
from contactlab.inverse.local_baseline import free_ringing
from contactlab.inverse.ringdown import MIN_DAMPING, refine_unheld
from dem_check.campaign.steps import remove_steps

__all__ = [
    "MARGIN_PERIODS",
    "SPAN",
    "STATUS",
    "PlateFit",
    "explained",
    "judged_steps",
    "negative_swing",
    "plate_fit",
    "step_or_swing",
]

SPAN = 2e-3
"""Longest stretch of the window on each side of the candidate [s]: two periods of a
1 kHz plate mode, so that the pencil resolves the modes (it needs 1.6 ms for a 40 kHz
sensor); a quadratic follows drift and 1/f noise over it."""

MARGIN_PERIODS = 2.0
"""Sensor periods left out on each side of the candidate's run [-]: the smoothing's
reach and the onset before the run's first sample above the floor."""

SIDE_PERIODS = 8.0
"""Fewest sensor periods of the window on each side of a step for it to be judged
(:func:`judged_steps`) [-]: half the period means' window
(:data:`~dem_check.campaign.steps.WINDOW_PERIODS`), which found it."""

LOBE_PERIODS = 16.0
"""Longest main lobe looked for after a run's start [sensor periods] (0.4 ms for a 40
kHz sensor, longer than the contacts of the toolkit's grains)."""

GRIDS = 3
"""Starting grids of the poles' refinement [-], a third of an octave apart
(:func:`_refined`)."""

STATUS = "structure ringing"
"""Status of a candidate the plate's ringing explains (listed, not analysed)."""


@dataclasses.dataclass(frozen=True, eq=False)
class PlateFit:
    """The plate's ringing fitted on a window, the candidate's samples left out."""

    t: np.ndarray
    """Times of the window [s]."""
    residual: np.ndarray
    """The record less the model, on every sample of the window [N]."""
    poles: list
    """The modes' poles fitted [1/s]."""

    def describe(self):
        """``"729 Hz, 1876 Hz"`` or ``"no mode"``."""
        return _describe(self.poles)


def _refined(tau, y, keep, sensor):
    """The plate's poles [1/s] on a window: grids of one pole an octave (damping ratio
    0.01) from one period over the window to
    :data:`~contactlab.inverse.crosstalk.BAND_FRACTION` of the sensor resonance, each
    refined on the period means of the samples kept (the sensor's ringing averages out),
    those that want more damping than a structure has dropped
    (:func:`~contactlab.inverse.ringdown.refine_unheld`); of the :data:`GRIDS` grids
    (shifted by a fraction of an octave: a refinement can stop in a local minimum that
    leaves a mode out), the one whose poles leave the least residual."""
    means_t, means = _period_means(tau, y, keep, sensor)
    low, high = 1.0 / float(tau[-1]), BAND_FRACTION * sensor.resonance
    count = max(1, math.ceil(math.log2(high / low)))
    best, least = [], math.inf
    for shift in (np.arange(GRIDS) + 0.5) / GRIDS:
        grid = low * (high / low) ** ((np.arange(count) + shift) / count)
        poles = [2.0 * math.pi * f * complex(-0.01 / math.sqrt(1.0 - 0.01**2), 1.0) for f in grid]
        poles = refine_unheld([(means_t, means)], poles, (MIN_DAMPING, MAX_DAMPING))
        design = np.concatenate(_columns(means_t, poles), axis=1)
        coefficients, *_ = np.linalg.lstsq(design, means, rcond=None)
        rss = float(np.sum((means - design @ coefficients) ** 2))
        if rss < least:
            best, least = poles, rss
    return best


def _columns(tau, poles):
    """A quadratic over the window and each pole's free ringing (two columns each)."""
    columns = [np.vander(tau / max(float(tau[-1]), 1e-300) - 0.5, 3, increasing=True)]
    for pole in poles:
        decay, phase = np.exp(pole.real * tau), pole.imag * tau
        columns.append(np.stack([decay * np.cos(phase), decay * np.sin(phase)], axis=1))
    return columns


def _describe(poles):
    return ", ".join(f"{p.imag / (2.0 * math.pi):.0f} Hz" for p in poles) or "no mode"


def _period_means(tau, y, keep, sensor):
    """``(tau [s], y)`` of the means of consecutive blocks of one sensor period whose
    samples are all kept: the sensor's ringing averages out, and a damped sinusoid of the
    band stays one, with the same pole (the pencil's blocks in
    :mod:`contactlab.inverse.crosstalk`)."""
    size = max(1, round(sensor.period / float(tau[1] - tau[0])))
    count = tau.size // size
    whole = keep[: count * size].reshape(count, size).all(axis=1)
    means = y[: count * size].reshape(count, size).mean(axis=1)
    centres = tau[: count * size].reshape(count, size).mean(axis=1)
    return centres[whole], means[whole]


def plate_fit(t, y, start, left_out, sensor):
    """The plate's ringing after an impact, fitted on a window of the record (module
    steps 1-3).

    Parameters
    ----------
    t, y : numpy.ndarray
        The window: uniformly spaced times [s] and the record [N]; it starts after the
        earlier impact's contact.
    start : float
        Where the sensor's free ringing starts [s] (a sensor period after the earlier
        impact's first lobe).
    left_out : numpy.ndarray of bool
        Samples not fitted (the candidate's).
    sensor : Sensor

    Returns
    -------
    PlateFit
    """
    keep = ~left_out
    tau = t - t[0]
    poles = _refined(tau, y, keep, sensor)
    columns = _columns(tau, poles)
    columns += [free_ringing(t, start, unit, sensor)[:, None] for unit in ((1, 0), (0, 1))]
    design = np.concatenate(columns, axis=1)
    coefficients, *_ = np.linalg.lstsq(design[keep], y[keep], rcond=None)
    return PlateFit(t, y - design @ coefficients, poles)


def explained(record, detection_arrays, sigmas, run, earlier, following, sensor):
    """Whether the plate's ringing after the ``earlier`` impact explains a candidate run
    (module step 4), and the reason to list it with.

    Parameters
    ----------
    record : Trace
        The record [N] (its offset steps taken off).
    detection_arrays : (float, numpy.ndarray, numpy.ndarray)
        Standard deviation of the detection's Gaussian kernel [s] (0: not smoothed), the
        smoothed residual [N] and its local noise [N] at every sample.
    sigmas : float
        Detection threshold [local sigmas].
    run : (int, int)
        First and last sample of the candidate's run.
    earlier : (float, int)
        The earlier impact's onset [s] and the index where its first lobe ends.
    following : float
        Onset of the next impact [s] (``inf`` when none).
    sensor : Sensor

    Returns
    -------
    str or None
        The reason when explained, else None.
    """
    t = np.asarray(record.t)
    dt = float(t[1] - t[0])
    kernel, smoothed, local = detection_arrays
    first, last = run
    z = smoothed[first : last + 1] / local[first : last + 1]
    peak = float(smoothed[first + int(np.argmax(np.abs(z)))])
    margin = max(1, round(MARGIN_PERIODS * sensor.period / dt))
    start = float(t[earlier[1]]) + sensor.period
    end = min(float(t[last]) + SPAN, following - sensor.period, float(t[-1]))
    lo = max(int(np.searchsorted(t, start)), int(np.searchsorted(t, float(t[first]) - SPAN)))
    hi = int(np.searchsorted(t, end, side="right"))
    if first - margin <= lo or hi - lo < 64:
        return None  # no samples of the ringing before the candidate
    left_out = np.zeros(hi - lo, dtype=bool)
    left_out[first - margin - lo : last + margin + 1 - lo] = True
    values = np.asarray(record.values[lo:hi], dtype=float)
    fit = plate_fit(t[lo:hi], values, start, left_out, sensor)
    width = kernel / dt
    rest = gaussian_filter1d(fit.residual, width) if width >= 0.5 else fit.residual
    inside = slice(first - lo, last + 1 - lo)
    ratio = np.abs(rest[inside]) / local[first : last + 1]
    if not ratio.max() < sigmas:
        return None
    return (
        f"a negative lobe ({peak:.4g} N, {np.max(np.abs(z)):.3g} local sigmas) "
        f"{float(t[first]) - earlier[0]:.4g} s after the impact at {earlier[0]:.6g} s: the "
        f"structure's free ringing ({fit.describe()}, a quadratic and the sensor's ringing, "
        f"fitted from {float(t[lo]):.6g} to {float(t[hi - 1]):.6g} s without its samples) "
        f"predicts it to {ratio.max():.3g} local sigmas, under the detection threshold "
        f"({sigmas:.3g}): the plate's ringing, not an impact"
    )


def negative_swing(record, stage, run, earlier_windows, following, sensor):
    """The reason to list a ``negative`` candidate run as :data:`STATUS`, or None: the
    plate's ringing after the last impact before it with a positive main lobe explains
    it (:func:`explained`; None when there is no such impact).

    Parameters
    ----------
    record : Trace
        The record [N] (its offset steps taken off).
    stage : dict
        The detection's ``floor`` (NoiseFloor), ``smoothed`` (Trace) and ``local``
        (local noise [N] at every sample).
    run : (int, int)
        First and last sample of the candidate's run.
    earlier_windows : list of ImpactWindow
        The candidates before it.
    following : int
        First sample of the next run (the record's length when none).
    sensor : Sensor
    """
    t = np.asarray(record.t)
    z = np.asarray(stage["smoothed"].values, dtype=float)
    before = [w for w in earlier_windows if w.peak > 0.0 and w.onset < float(t[run[0]])]
    if not before:
        return None
    onset = before[-1].onset
    lo, hi = np.searchsorted(t, [onset, t[run[0]]])
    if hi - lo < 2:
        return None
    top = lo + int(np.argmax(z[lo:hi]))
    lobe_end = top + int(np.argmax(z[top:hi] <= 0.0))
    arrays = (stage["floor"].kernel, z, stage["local"])
    after = float(t[following]) if following < t.size else math.inf
    sigmas = stage["floor"].sigmas
    return explained(record, arrays, sigmas, run, (onset, lobe_end), after, sensor)


def step_or_swing(values, index, height, window, sensor, dt):
    """Whether an offset step after an impact is a step, or the plate's ringing.

    On the window (after the impact's first lobe, past the step), the period means of
    the record as it is and of the record with the step taken off are each fitted with
    a quadratic and the plate's free ringing (modes refined on each, :func:`_refined`);
    the second with the step's unit column too. The model with the lower
    Akaike criterion (Gaussian: ``n log(RSS / n) + 2 k``; ``k``: the quadratic's 3, 4 per
    mode, the step's place and height 2) is taken.

    Parameters
    ----------
    values : numpy.ndarray
        The record [N], its other steps taken off.
    index : int
        The step's first sample at the new level.
    height : float
        Its height [N].
    window : (int, int)
        ``[lo, hi)`` sample indices of the window.
    sensor : Sensor
    dt : float
        Sampling interval [s].

    Returns
    -------
    (bool, str)
        Whether it is a step, and the comparison in words.
    """
    lo, hi = window
    t = np.arange(hi - lo) * dt
    unit = (np.arange(lo, hi) >= index).astype(float)
    keep = np.ones(hi - lo, dtype=bool)
    scores, described = [], []
    for h, with_step in ((0.0, False), (height, True)):
        y = np.asarray(values[lo:hi], dtype=float) - h * unit
        means_t, means = _period_means(t, y, keep, sensor)
        _, column = _period_means(t, unit, keep, sensor)
        poles = _refined(t, y, keep, sensor)
        columns = _columns(means_t, poles)
        if with_step:
            columns.append(column[:, None])
        design = np.concatenate(columns, axis=1)
        coefficients, *_ = np.linalg.lstsq(design, means, rcond=None)
        rss = float(np.sum((means - design @ coefficients) ** 2))
        k = 3 + 4 * len(poles) + (2 if with_step else 0)
        scores.append(means.size * math.log(max(rss, 1e-300) / means.size) + 2 * k)
        fitted = h + (coefficients[-1] if with_step else 0.0)
        described.append((_describe(poles), math.sqrt(rss / means.size), fitted))
    step = scores[1] < scores[0]
    (modes0, rms0, _), (modes1, rms1, fitted) = described
    reason = (
        f"on {float(t[-1]):.3g} s after the impact's lobe, the plate's free ringing "
        f"({modes0}) fits the period means to {rms0:.3g} N rms without a step (Akaike "
        f"{scores[0]:.1f}), with a step of {fitted:.4g} N ({modes1}) to {rms1:.3g} N "
        f"({scores[1]:.1f})"
    )
    return step, reason


def _lobe_end(values, first, period):
    """The end of a run's main lobe [index]: twice its rise after the run's first sample
    (a contact's force falls about as fast as it rose), the top read on the record
    averaged over a sensor period (no ringing) against its level a period before the
    run, at most :data:`LOBE_PERIODS` sensor periods after the run's start."""
    reach, lead = round(LOBE_PERIODS * period), min(first, period)
    averaged = uniform_filter1d(values[first - lead : first + reach], period)
    x = averaged[lead:] - averaged[0]  # from the level a period before the run
    top = int(np.argmax(x)) if x.max() >= -x.min() else int(np.argmin(x))
    return first + 2 * top


def judged_steps(values, steps, runs, period, ring):
    """The offset steps found on the period means less those that lie in an impact's
    ringing and that the plate's free ringing explains better (:func:`step_or_swing`).

    A step is judged when it lies within :data:`SPAN` after a first-pass run's start
    and the window (from a sensor period after that run's main lobe to :data:`SPAN` past
    the step, or two periods before the next run) holds at least
    :data:`SIDE_PERIODS` sensor periods on each side of it; others are kept as found.

    Parameters
    ----------
    values : numpy.ndarray
        The record [N] (the steps of other kinds taken off).
    steps : list of OffsetStep
    runs : list of (int, int)
        The first pass's candidate runs.
    period : int
        The sensor's period [samples].
    ring : (Sensor, float)
        The sensor and the sampling interval [s].

    Returns
    -------
    list of OffsetStep
        Those kept, each judged one with the comparison in its ``note``.
    """
    sensor, dt = ring
    span, side = round(SPAN / dt), round(SIDE_PERIODS * period)
    kept = []
    for step in steps:
        before = [r for r in runs if r[0] < step.index <= r[0] + span]
        later = [r[0] for r in runs if r[0] > step.index]
        if not before:
            kept.append(step)
            continue
        lo = _lobe_end(values, before[-1][0], period) + period
        hi = min(step.index + span, later[0] - 2 * period if later else values.size)
        if step.index - lo < side or hi - step.index < side:
            kept.append(step)
            continue
        rest = remove_steps(values, [other for other in steps if other is not step])
        is_step, reason = step_or_swing(rest, step.index, step.height, (lo, hi), sensor, dt)
        if is_step:
            kept.append(dataclasses.replace(step, note=f"{step.note}; {reason}"))
    return kept
