"""Finding every impact in a long record: noise floor, detection, segmentation, overlaps.

A record holds impacts separated by quiet stretches. The steps, all on the record in
newtons:

1. **Noise floor.** The record is cut into blocks of :data:`BLOCK_PERIODS` sensor
   periods; blocks whose standard deviation is at most :data:`QUIET_FACTOR` times the
   median block's are quiet, and the longest run of quiet blocks is the baseline window.
   Its mean is removed (:func:`dem_check.traces.remove_baseline`) and its noise read
   (:func:`dem_check.traces.noise_level`), so no pre-trigger needs to be known. This
   assumes impacts and their ringing fill less than half of the record.
2. **Smoothing.** Two copies of the record: one smoothed by a Gaussian kernel
   (``scipy.ndimage.gaussian_filter1d``) whose -3 dB frequency is :data:`CUTOFF_FACTOR`
   times the sensor's resonance, for detection and timing (a positive kernel: no
   overshoot, so no false lobe before a sharp rise, and a lead of at most about three
   kernel widths, 5 us for a 40 kHz sensor); and one low-passed by a zero-phase
   Butterworth filter at the same frequency (:func:`dem_check.traces.lowpass`), flat in
   its pass band, for the peak (the Gaussian would lower a 40 kHz sensor's peaks by
   1-3 %). Both cut white noise five-fold at 5 MHz.
3. **Detection.** An impact is a run of the smoothed signal above the noise floor
   (:data:`FLOOR_SIGMAS` sigma) that reaches the detection threshold: ``k`` sigma, with
   ``k`` set so that Gaussian noise crosses it by chance in fewer than
   :data:`FALSE_ALARMS` records (Bonferroni over the record's samples; 6.2 sigma for
   1.5 million samples, never below 5). The run ends once the signal has stayed under
   the floor for :data:`QUIET_PERIODS` sensor periods: the ringing has decayed.
4. **Onset.** :func:`dem_check.traces.detect_onset` on the smoothed segment: the first
   crossing of :data:`ONSET_SIGMAS` times the noise of the segment's own baseline (the
   quiet samples just before the impact, at most :data:`BASELINE_PERIODS` periods).
5. **Overlaps.** Free ringing only decays. After the first lobe, the envelope (largest
   value per sensor period) is followed; where it grows by more than
   :data:`GROWTH_FACTOR` (plus the noise floor) a second impact started before the
   first one's ringing decayed. Both are flagged ``"overlap"``, never merged. Two
   impacts closer than the first one's main lobe cannot be told from one longer impact.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d
from scipy.stats import norm

from contactlab.errors import ParameterError
from dem_check.traces import Trace, detect_onset, lowpass, noise_level, remove_baseline
from dem_check.traces.checks import uniform_interval

__all__ = [
    "BASELINE_MIN_SAMPLES",
    "Detection",
    "ImpactWindow",
    "NoiseFloor",
    "find_impacts",
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

BLOCK_PERIODS = 2.0
"""Block length of the quiet-stretch search [sensor periods], at least 16 samples."""

QUIET_FACTOR = 1.5
"""A block is quiet when its standard deviation (and its mean's distance from the
median block mean) is at most this many times the median block's standard deviation.
The standard deviation of 16 or more noise samples scatters by less than 18 %, so noise
blocks pass; a block with ringing of amplitude above the noise does not."""

FALSE_ALARMS = 1e-3
"""Expected number of chance detections per record [-] (sets the detection sigmas)."""

ONSET_SIGMAS = 5.0
"""Onset level in noise sigmas of the smoothed segment's own baseline [-]; the
smoothing cuts the noise, so this is a small fraction of a typical impact's peak."""

FLOOR_SIGMAS = 3.0
"""Noise floor in sigmas of the smoothed record [-]: an impact lasts while its signal
keeps coming back above it."""

QUIET_PERIODS = 4.0
"""An impact ends after this many sensor periods below the floor [-]."""

TAIL_PERIODS = 16.0
"""Quiet sensor periods kept after an impact's ringing has decayed (up to the next
impact's run) [-]: the reconstruction reads the signal to three periods past a window
that may end a lobe-length after the main lobe, which a noisy record's short ringing
would not reach."""

BASELINE_PERIODS = 20.0
"""Longest baseline taken before an impact [sensor periods]: enough samples for the
noise (to a few per cent) without reaching back into an older impact."""

BASELINE_MIN_SAMPLES = 16
"""Fewest baseline samples before an impact (as :func:`contactlab.inverse.reconstruct_force`
requires)."""

GROWTH_FACTOR = 1.5
"""Largest growth of the ringing envelope from one sensor period to the next that is
not a new impact: free ringing shrinks by ``exp(-2 pi zeta)`` per period."""


@dataclass(frozen=True)
class NoiseFloor:
    """How a record's baseline and noise were read (unit of the record, N)."""

    window: tuple
    """Baseline window ``[start, end)`` [s]: the longest quiet stretch."""
    baseline: float
    """Mean of the record over the window (removed) [N]."""
    noise: float
    """Standard deviation of the record over the window [N]."""
    smoothed_noise: float
    """Standard deviation of the smoothed record over the window [N]."""
    cutoff: float
    """-3 dB frequency of the smoothings [Hz]."""
    kernel: float
    """Standard deviation of the Gaussian kernel [s] (0 when not smoothed)."""
    sigmas: float
    """Detection threshold in ``smoothed_noise`` units [-]."""

    @property
    def threshold(self):
        """Detection threshold on the smoothed record [N]."""
        return self.sigmas * self.smoothed_noise

    @property
    def floor(self):
        """Noise floor of the smoothed record [N]."""
        return FLOOR_SIGMAS * self.smoothed_noise


@dataclass(frozen=True)
class ImpactWindow:
    """One impact found in a record: where it is, and whether it can be analysed."""

    onset: float
    """Start of the impact [s] (first crossing of the onset level; for the later impact
    of an overlap, the sensor period where the ringing grew)."""
    baseline_window: tuple
    """Local baseline before the impact ``[start, end)`` [s]."""
    first: int
    """Index of the first sample of the impact's segment (the baseline's first)."""
    stop: int
    """Index one past the segment's last sample (:data:`TAIL_PERIODS` after the ringing
    decayed, the next impact's run, or the record's end)."""
    end: float
    """Time the ringing had decayed [s]: :data:`QUIET_PERIODS` after the last sample above
    the noise floor (or the record's end)."""
    status: str
    """``"ok"``, ``"overlap"``, ``"truncated"``, ``"no baseline"``, ``"negative"`` or
    ``"overrange"``: only ``"ok"`` impacts are analysed further."""
    reason: str = ""
    """Why the status is not ``"ok"`` (empty when it is)."""


@dataclass(frozen=True, eq=False)
class Detection:
    """The impacts of one record, with the record as they were found on."""

    floor: NoiseFloor
    impacts: list
    """:class:`ImpactWindow` list, in time order."""
    signal: Trace
    """The record with its baseline removed [N]."""
    smoothed: Trace
    """The record smoothed by the Gaussian kernel [N], for detection and timing."""
    lowpassed: Trace
    """The record low-passed [N], for peaks (equal to ``signal`` when not filtered)."""


def _quiet_window(t, y, block):
    """The longest run of quiet blocks as ``(start, end)`` [s] (see the module)."""
    count = y.size // block
    if count < 2:
        raise ParameterError(
            f"the record ({y.size} samples) is shorter than two blocks of {block} samples "
            "(two sensor periods each): too short to find a noise floor"
        )
    blocks = y[: count * block].reshape(count, block)
    spread = blocks.std(axis=1, ddof=1)
    typical = float(np.median(spread))
    if typical == 0.0:
        raise ParameterError(
            "the record is exactly constant over most of its blocks: no noise to set a "
            "detection threshold from"
        )
    centre = np.median(blocks.mean(axis=1))
    quiet = (spread <= QUIET_FACTOR * typical) & (
        np.abs(blocks.mean(axis=1) - centre) <= QUIET_FACTOR * typical
    )
    edges = np.flatnonzero(np.diff(np.concatenate([[0], quiet.astype(np.int8), [0]])))
    starts, ends = edges[::2], edges[1::2]
    best = int(np.argmax(ends - starts))
    stop = min(ends[best] * block, t.size - 1)
    return float(t[starts[best] * block]), float(t[stop])


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


def noise_floor(trace, sensor):
    """Baseline, noise and detection threshold of a record (module steps 1-3).

    Returns
    -------
    floor : NoiseFloor
    signal, smoothed, lowpassed : Trace
        The record without its baseline, smoothed (Gaussian) and low-passed.
    """
    dt = uniform_interval(trace, "finding impacts needs uniform sampling")
    block = max(BASELINE_MIN_SAMPLES, round(BLOCK_PERIODS * sensor.period / dt))
    finite = _finite(trace)
    window = _quiet_window(finite.t, finite.values, block)
    signal = remove_baseline(finite, window)
    cutoff = CUTOFF_FACTOR * sensor.resonance
    kernel = math.sqrt(math.log(2.0)) / (2.0 * math.pi * cutoff)
    smoothed = _gaussian(signal, kernel, dt)
    sigmas = max(ONSET_SIGMAS, float(norm.isf(FALSE_ALARMS / (2.0 * len(trace)))))
    floor = NoiseFloor(
        window=window,
        baseline=float(signal.metadata["history"][-1]["baseline"]),
        noise=noise_level(finite, window),
        smoothed_noise=noise_level(smoothed, window),
        cutoff=cutoff,
        kernel=kernel if smoothed is not signal else 0.0,
        sigmas=sigmas,
    )
    return floor, signal, smoothed, _lowpassed(signal, cutoff, dt)


def _runs(z, floor, threshold, hold):
    """``(first, last)`` sample indices of each run above the floor that reaches the
    threshold; runs closer than ``hold`` samples are one."""
    above = np.flatnonzero(np.abs(z) > floor)
    if above.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(above) > hold)
    firsts = np.concatenate([[0], breaks + 1])
    lasts = np.concatenate([breaks, [above.size - 1]])
    peaks = np.maximum.reduceat(np.abs(z[above]), firsts)
    keep = peaks > threshold
    return list(zip(above[firsts[keep]].tolist(), above[lasts[keep]].tolist(), strict=True))


def _growths(z, first_lobe_end, last, period, noise_floor_level):
    """Sample indices where the ringing envelope grows: later impacts (module step 5)."""
    start = first_lobe_end + period  # the free ringing is under way one period later
    windows = (last + 1 - start) // period
    if windows < 2:
        return []
    envelope = np.abs(z[start : start + windows * period]).reshape(windows, period).max(axis=1)
    grows = envelope[1:] > GROWTH_FACTOR * envelope[:-1] + noise_floor_level
    runs = np.flatnonzero(grows & ~np.concatenate([[False], grows[:-1]])) + 1
    found = []
    for k in runs:
        level = GROWTH_FACTOR * envelope[k - 1] + noise_floor_level
        segment = np.abs(z[start + k * period : start + (k + 1) * period])
        found.append(start + k * period + int(np.argmax(segment > level)))
    return found


def find_impacts(trace, sensor):
    """Every impact in a record, with its onset, local baseline and status.

    Parameters
    ----------
    trace : Trace
        The record in newtons, uniformly sampled.
    sensor : Sensor
        A moving sensor: its period sets the time scales (blocks, quiet time, envelope)
        and its resonance the smoothing.

    Returns
    -------
    Detection

    Raises
    ------
    ParameterError
        Not uniformly sampled, too short, or without noise (no threshold can be set).
    """
    floor, signal, smoothed, lowpassed = noise_floor(trace, sensor)
    t, z = smoothed.t, np.asarray(smoothed.values)
    dt = float(t[1] - t[0])
    period = max(2, round(sensor.period / dt))
    hold = round(QUIET_PERIODS * sensor.period / dt)
    spread = round(3.0 * floor.kernel / dt)  # the kernel's reach before a rise
    overrange = np.asarray(trace.metadata["overrange"], dtype=int)
    tail = round(TAIL_PERIODS * sensor.period / dt)
    runs = _runs(z, floor.floor, floor.threshold, hold)
    windows, previous_end = [], 0
    for k, (first, last) in enumerate(runs):
        run = z[first : last + 1]
        polarity = 1.0 if run.max() >= -run.min() else -1.0  # the main lobe's side
        detected = first + int(np.argmax(polarity * run > floor.threshold))
        quiet = np.flatnonzero(np.abs(z[previous_end:detected]) <= floor.floor)
        base_end = previous_end + (int(quiet[-1]) if quiet.size else 0) - spread
        base_start = max(previous_end, base_end - round(BASELINE_PERIODS * sensor.period / dt))
        following = runs[k + 1][0] if k + 1 < len(runs) else t.size
        stop = min(last + hold + tail, following, t.size)
        previous_end = last + 1
        windows += _classify(
            smoothed,
            (base_start, base_end, detected, last, stop, hold),
            period,
            floor,
            overrange,
        )
    return Detection(floor, windows, signal, smoothed, lowpassed)


def _classify(smoothed, indices, period, floor, overrange):
    """The :class:`ImpactWindow` (one, or several for an overlap) of one run."""
    base_start, base_end, detected, last, stop, hold = indices
    t, z = smoothed.t, np.asarray(smoothed.values)
    truncated = last + hold > t.size
    rough = float(t[detected])
    end = float(t[min(last + hold, t.size - 1)])
    if base_end - base_start < BASELINE_MIN_SAMPLES:
        reason = (
            f"only {max(base_end - base_start, 0)} quiet samples before the impact at "
            f"{rough:.6g} s (need {BASELINE_MIN_SAMPLES}): it starts too close to the "
            "record's start or to the previous impact's ringing"
        )
        return [ImpactWindow(rough, (np.nan, np.nan), detected, stop, end, "no baseline", reason)]
    base = (float(t[base_start]), float(t[base_end]))
    segment = Trace(t[base_start:stop], z[base_start:stop], smoothed.unit)
    try:
        onset = detect_onset(segment, ONSET_SIGMAS, base)
    except ParameterError as exc:  # the local noise is far above the record's
        reason = f"the local baseline before {rough:.6g} s is too noisy to time it: {exc}"
        return [ImpactWindow(rough, base, base_start, stop, end, "no baseline", reason)]

    def window(at, status="ok", reason=""):
        return ImpactWindow(at, base, base_start, stop, end, status, reason)

    if z[detected] < 0.0:
        reason = (
            f"the main lobe is negative ({z[detected : last + 1].min():.4g} N after "
            f"{rough:.6g} s); a compressive contact gives a positive signal: check the "
            "sensor's polarity"
        )
        return [window(onset, "negative", reason)]
    if truncated:
        reason = (
            f"the record ends {t[-1] - onset:.4g} s after the onset, before the ringing "
            "decayed below the noise floor"
        )
        return [window(onset, "truncated", reason)]
    inside = overrange[(overrange >= base_start) & (overrange < stop)]
    if inside.size:
        reason = (
            f"{inside.size} overrange samples (first at {t[inside[0]]:.6g} s): the "
            "instrument's range was exceeded, the true signal is unknown"
        )
        return [window(onset, "overrange", reason)]
    lobe_end = detected + int(np.argmax(z[detected : last + 1] <= 0.0))
    later = _growths(z, lobe_end, last, period, floor.floor) if lobe_end > detected else []
    if not later:
        return [window(onset)]
    times = [onset, *(float(t[i]) for i in later)]
    out = []
    for k, at in enumerate(times):
        others = ", ".join(f"{other:.6g} s" for j, other in enumerate(times) if j != k)
        out.append(
            window(
                at,
                "overlap",
                f"impacts at {at:.6g} s and {others} overlap: one started before the "
                "other's ringing decayed, so neither is analysed alone",
            )
        )
    return out
