"""A record's baseline, local noise and detection threshold, robust to what laboratories
record (steps 1-2 of :mod:`dem_check.campaign.detection`).

A laboratory record drifts, wanders, hums, steps and rings with the structure after a
hit; its quietest stretch is quieter than the rest (issue 22: on a real load-cell record
the quietest stretch gave 0.017 N while the wander after the hit spans +-0.1 N). So the
baseline is followed, not read once, and the noise is read locally:

- :func:`contactlab.signals.running_baseline` over blocks of :data:`BLOCK_PERIODS`
  sensor periods (at least :data:`BLOCK_MIN_SAMPLES` samples): block medians,
  interpolated, follow drift, wander and slow hum; each sample's distance to the nearest
  block level is its residual, which an offset step does not raise;
- the local noise is :data:`contactlab.signals.MAD_TO_SIGMA` times the median absolute
  distance from the baseline of each block, the largest of a block and its neighbours:
  hum, wander faster than a block and a structure's ringing raise their own block's
  threshold. The impacts found on a first pass, with their ringing, are left out of it
  on the second (a hard hit's ringing can fill most of a block);
- a record that starts at an impact (its first run within :data:`HEAD_QUIET_SAMPLES`
  of the start) has no block level under it: the run is excluded and the baseline
  re-fitted after it and extrapolated back (``running_baseline``'s ``head``; up to
  :data:`HEAD_PASSES` passes of detect, exclude, re-fit);
- the threshold is ``sigmas`` local noise sigmas of the smoothed residual, ``sigmas``
  set so that Gaussian noise crosses it in fewer than :data:`FALSE_ALARMS` records.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d
from scipy.stats import norm

from contactlab import signals
from contactlab._block_levels import block_levels
from contactlab.errors import ParameterError
from contactlab.traces import Trace, lowpass
from contactlab.traces.checks import uniform_interval

__all__ = [
    "BLOCK_MIN_SAMPLES",
    "BLOCK_PERIODS",
    "CUTOFF_FACTOR",
    "FALSE_ALARMS",
    "FLOOR_SIGMAS",
    "ONSET_SIGMAS",
    "QUIET_MIN_SAMPLES",
    "QUIET_PERIODS",
    "NoiseFloor",
    "candidate_runs",
    "noise_floor",
    "record_filters",
]

CUTOFF_FACTOR = 2.0
"""-3 dB frequency of both smoothings in units of the sensor resonance [-]. The
Butterworth filter (fourth order, applied twice) keeps the ringing at resonance to
within 0.4 % (``1 / (1 + 2**-8)``); the Gaussian kernel's width is
``sqrt(ln 2) / (2 pi fc)`` (1.66 us for a 40 kHz sensor)."""

NYQUIST_FRACTION = 0.8
"""The record is low-passed only if the cutoff lies below this fraction of the Nyquist
frequency (and smoothed only if the Gaussian kernel is wider than half a sample); a
record sampled more coarsely is used as it is."""

EDGE_CUTOFF_PERIODS = 4.0
"""The low-passed record is not read this many cutoff periods from either end: the
zero-phase filter's start-up (its slowest poles decay as ``exp(-0.38 * 2 pi fc t)``,
to 7e-5 after 4 periods) pulls it towards the first and last raw samples."""

BLOCK_PERIODS = 64.0
"""Block length of the running baseline and local noise [sensor periods]: 1.6 ms for a
40 kHz sensor, 16 times a 100 us contact with its main lobe, so an impact moves its
block's median and MAD little; short against drift, wander and the mains period."""

BLOCK_MIN_SAMPLES = 64
"""Shortest block [samples]: a MAD of 64 samples scatters by about 10 %."""

FALSE_ALARMS = 1e-3
"""Expected number of chance detections per record [-] (sets the detection sigmas)."""

MIN_SIGMAS = 7.0
"""Lowest detection threshold [local noise sigmas]: laboratory noise has heavier tails
than Gaussian noise relative to a block's local noise (on the real hammer records of
``data/traces/real``, 5.8 sigma excursions occur once in 25600 samples; 1/f noise as large
as the white noise made a 6.4 sigma excursion at 5 MHz, its slow part being under-read by
a block's MAD, in the hypothesis sweep), so the Bonferroni threshold is never lowered below this."""

ONSET_SIGMAS = 5.0
"""Onset level in noise sigmas of the smoothed segment's own baseline [-]; the
smoothing cuts the noise, so this is a small fraction of a typical impact's peak."""

FLOOR_SIGMAS = 3.0
"""Noise floor in local noise sigmas of the smoothed record [-]: an impact lasts while
its signal keeps coming back above it."""

QUIET_PERIODS = 4.0
"""An impact ends after this many sensor periods below the floor [-] (at least
:data:`QUIET_MIN_SAMPLES`)."""

QUIET_MIN_SAMPLES = 8
"""Fewest samples below the floor that end an impact (coarse records) [-]."""

HEAD_QUIET_SAMPLES = 16
"""A record whose first impact run (with its ringing) starts within this many samples
of its first one starts at the impact [-] (the quiet samples a local baseline needs,
``dem_check.campaign.detection.BASELINE_MIN_SAMPLES``): the running baseline is then
fitted after that run and extrapolated back under it
(:func:`contactlab._head_level.head_level`)."""

HEAD_PASSES = 3
"""Passes of detect, exclude the run at the record's start, re-fit [-]: the first
pass's baseline is off under that run, which lengthens it; the second's run is the
impact's, and a third confirms it."""


def candidate_runs(ratio, hold, sigmas):
    """``(first, last)`` sample indices of each run of ``ratio`` (smoothed signal over
    local noise) above :data:`FLOOR_SIGMAS` that reaches ``sigmas``; runs closer than
    ``hold`` samples are one."""
    above = np.flatnonzero(ratio > FLOOR_SIGMAS)
    if above.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(above) > hold)
    firsts = np.concatenate([[0], breaks + 1])
    lasts = np.concatenate([breaks, [above.size - 1]])
    peaks = np.maximum.reduceat(ratio[above], firsts)
    keep = peaks > sigmas
    return list(zip(above[firsts[keep]].tolist(), above[lasts[keep]].tolist(), strict=True))


def _impact_mask(levels, hold, sigmas):
    """Samples of the impacts found on a first pass (on a record's
    :func:`~contactlab._block_levels.block_levels`), with their ringing (to
    :data:`QUIET_PERIODS` past their last sample above the floor): left out of the
    local noise on the second pass."""
    first_pass = signals.levels_baseline(levels)
    if np.median(first_pass.noise) == 0.0:
        raise ParameterError(
            "the record is exactly constant over most of its blocks: no noise to set a "
            "detection threshold from"
        )
    ratio = np.abs(first_pass.residual) / np.maximum(first_pass.noise, np.finfo(float).tiny)
    mask = np.zeros(levels.y.size, dtype=bool)
    for first, last in candidate_runs(ratio, hold, sigmas):
        mask[first : last + hold + 1] = True
    return mask


def _head(mask, longest):
    """Samples of the impact run (with its ringing) that the record starts in, 0 when it
    starts quiet (at least :data:`HEAD_QUIET_SAMPLES` samples before the first run), at
    most ``longest``."""
    if not mask[:HEAD_QUIET_SAMPLES].any():
        return 0
    quiet = np.flatnonzero(~mask)
    after = quiet[quiet >= np.argmax(mask)]
    return int(min(after[0] if after.size else mask.size, longest))


@dataclass(frozen=True)
class NoiseFloor:
    """How a record's baseline and noise were read (unit of the record, N)."""

    window: tuple
    """Quietest block ``[start, end)`` [s] (where the record's noise is lowest)."""
    baseline: float
    """Median of the running baseline (removed) [N]."""
    noise: float
    """Median local noise of the record [N] (its typical noise sigma)."""
    smoothed_noise: float
    """Median local noise of the smoothed record [N]."""
    cutoff: float
    """-3 dB frequency of the smoothings [Hz]."""
    kernel: float
    """Standard deviation of the Gaussian kernel [s] (0 when not smoothed)."""
    sigmas: float
    """Detection threshold in local noise sigmas of the smoothed record [-]."""
    block: float = 0.0
    """Block length of the running baseline [s]."""
    wander: float = 0.0
    """Range of the running baseline over the record [N] (drift, wander, steps)."""
    largest_noise: float = 0.0
    """Largest local noise of the smoothed record [N] (hum, ringing, bursts)."""

    @property
    def threshold(self):
        """Typical detection threshold on the smoothed record [N] (where its local noise
        is the median one; it follows the local noise)."""
        return self.sigmas * self.smoothed_noise

    @property
    def floor(self):
        """Typical noise floor of the smoothed record [N]."""
        return FLOOR_SIGMAS * self.smoothed_noise


def _finite(trace):
    """The record with overrange samples (+-inf) set to the largest finite magnitude,
    for detection only (impacts that hold them are flagged, never analysed)."""
    if not len(trace.metadata["overrange"]):
        return trace
    values = np.asarray(trace.values)
    finite = np.isfinite(values)
    limit = float(np.max(np.abs(values[finite]))) if finite.any() else 1.0
    step = {"step": "overrange_for_detection", "limit": limit}
    return trace.derive(step, values=np.where(finite, values, np.sign(values) * limit))


def _gaussian(trace, kernel, dt):
    """The trace smoothed by a Gaussian kernel of standard deviation ``kernel`` [s]."""
    if kernel < 0.5 * dt:
        return trace
    step = {"step": "gaussian_smoothing", "kernel [s]": kernel, "mode": "reflect"}
    return trace.derive(step, values=gaussian_filter1d(trace.values, kernel / dt))


def _lowpassed(trace, cutoff, dt):
    """The trace low-passed at ``cutoff`` [Hz], its first and last samples of filter
    start-up (:data:`EDGE_CUTOFF_PERIODS`) set to nan, or the trace itself when too
    coarse to filter."""
    if cutoff >= NYQUIST_FRACTION * 0.5 / dt:
        return trace
    filtered = lowpass(trace, cutoff)
    edge = round(EDGE_CUTOFF_PERIODS / cutoff / dt)
    values = np.array(filtered.values)
    values[:edge], values[values.size - edge :] = np.nan, np.nan
    step = {"step": "edges_unread", "samples": edge}
    return filtered.derive(step, values=values)


def record_filters(trace, floor):
    """``trace`` [N] through the record's two filters: the Gaussian kernel and the
    low-pass of ``floor`` (:class:`NoiseFloor`), as :func:`noise_floor` filtered the
    record (the low-passed trace's edges unread). Both are linear, so a modelled part
    of the record taken off it is taken off its filtered traces with these.

    Returns
    -------
    smoothed, lowpassed : Trace
    """
    dt = uniform_interval(trace, "filtering needs uniform sampling")
    return _gaussian(trace, floor.kernel, dt), _lowpassed(trace, floor.cutoff, dt)


def block_samples(trace_length, period, dt):
    """Block length [samples] of the running baseline for a record of ``trace_length``
    samples: :data:`BLOCK_PERIODS` sensor periods, at least :data:`BLOCK_MIN_SAMPLES`,
    at most half the record (a record shorter than 16 samples a block is refused)."""
    width = max(BLOCK_MIN_SAMPLES, round(BLOCK_PERIODS * period / dt))
    width = min(width, trace_length // 2)
    if width < 16:
        raise ParameterError(
            f"the record ({trace_length} samples) is too short to find a noise floor: "
            "it needs two blocks of at least 16 samples"
        )
    return width


def noise_floor(trace, sensor):
    """Baseline, local noise and detection threshold of a record (module docstring).

    Parameters
    ----------
    trace : Trace
        The record [N], uniformly sampled.
    sensor : Sensor
        Its period sets the block length and its resonance the smoothing.

    Returns
    -------
    floor : NoiseFloor
    signal, smoothed, lowpassed : Trace
        The record without its running baseline, smoothed (Gaussian; the residual from
        the nearest block level, what impacts are found on) and low-passed.
    local_noise : numpy.ndarray
        Local noise of the smoothed record at every sample [N].

    Raises
    ------
    ParameterError
        Not uniformly sampled, too short, or without noise.
    """
    dt = uniform_interval(trace, "finding impacts needs uniform sampling")
    finite = _finite(trace)
    values = np.asarray(finite.values, dtype=float)
    width = block_samples(values.size, sensor.period, dt)
    cutoff = CUTOFF_FACTOR * sensor.resonance
    kernel = math.sqrt(math.log(2.0)) / (2.0 * math.pi * cutoff)
    sigmas = max(MIN_SIGMAS, float(norm.isf(FALSE_ALARMS / (2.0 * len(trace)))))
    hold = max(QUIET_MIN_SAMPLES, round(QUIET_PERIODS * sensor.period / dt))
    head = 0
    levels = block_levels(values, width)  # computed once for every pass (the same bits)
    for _ in range(HEAD_PASSES):  # detect, exclude the pulse at the start, re-fit
        levelled = signals.levels_baseline(levels, head=head).residual
        step = {"step": "levelled", "head [samples]": head}
        smoothed_raw = _gaussian(finite.derive(step, values=levelled), kernel, dt)
        smoothed_levels = block_levels(np.asarray(smoothed_raw.values, dtype=float), width)
        mask = _impact_mask(smoothed_levels, hold, sigmas)
        found = _head(mask, values.size - width)
        if found == head:
            break
        head = found
    smooth = signals.levels_baseline(smoothed_levels, exclude=mask)
    raw = signals.levels_baseline(levels, exclude=mask, head=head)
    step = {"step": "running_baseline", "block [samples]": width, "head [samples]": head}
    signal = finite.derive(step, values=values - raw.level)
    typical = float(np.median(smooth.noise))
    if typical == 0.0:
        raise ParameterError(
            "the record is exactly constant over most of its blocks: no noise to set a "
            "detection threshold from"
        )
    smoothed = Trace(finite.t, smooth.residual, finite.unit, dict(smoothed_raw.metadata))
    floor = NoiseFloor(
        window=signals.levels_quiet_window(finite.t, levels),
        baseline=float(np.median(raw.level)),
        noise=float(np.median(raw.noise)),
        smoothed_noise=typical,
        cutoff=cutoff,
        kernel=kernel if kernel >= 0.5 * dt else 0.0,
        sigmas=sigmas,
        block=width * dt,
        wander=float(np.ptp(raw.level)),
        largest_noise=float(smooth.noise.max()),
    )
    return floor, signal, smoothed, _lowpassed(signal, cutoff, dt), smooth.noise
