"""Realistic laboratory records: the forward model's impacts with what a laboratory adds.

:func:`dem_check.campaign.synthetic_record` places exact impacts on white noise after a
long quiet stretch. Laboratory records are not like that (issue 22). :func:`realistic_record`
starts from the same impacts and adds, each one switched on alone by its field of
:class:`Effects` (all off by default):

- ``pink``: coloured noise, power spectral density proportional to ``1/f`` from the
  record's length to the Nyquist frequency (standard deviation [N]);
- ``drift``: slow baseline drift and wander, a sum of five sines of 0.2-5 Hz with random
  phases and a linear trend, largest excursion from the start [N];
- ``hum``: mains hum at ``mains`` [Hz] (50 or 60) and its harmonics 2-5 with the
  amplitudes ``harmonics`` relative to the fundamental's (amplitude [N]);
- ``crosstalk``: structural crosstalk, the plate's modes (``plate_modes``: frequency
  [Hz] and damping ratio each) driven by each impact's force on the plate (the
  sensor's force: the response is its convolution with the mode's impulse response,
  which starts with the force), scaled so that the impact's impulse delivered at once
  would ring at the impact's peak signal times ``crosstalk`` [-];
- ``full_scale`` and ``bits``: an ADC of range ``[-full_scale, +full_scale]`` [N] with
  ``bits`` bits: samples are quantised to its steps and clipped at its rails (the rail
  value is written, as most instruments do, not +-inf);
- ``steps`` and ``step_size``: DC offset steps (a charge amplifier's range change or
  reset) at random times, heights ``+-step_size`` [N]; ``offsets``: steps at given
  times with given heights (near a record's edge or an impact, where they are hardest);
- ``bounce`` and ``bounce_delay``: each impact followed by a second one at ``bounce``
  times its velocity, ``bounce_delay`` [s] later (a double hit or a grain's bounce).

The record's start relative to the first impact (``onsets`` near 0: a short or zero
pre-trigger) and trigger-aligned files (``trigger``: the time axis starts before the
trigger, as oscilloscopes write it) are set by the arguments. The truth table holds
the bounces too, with a ``clipped`` column.
"""

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pandas as pd

from contactlab.errors import ParameterError
from contactlab.traces import Trace
from contactlab.validation import check_count, check_number, check_samples
from dem_check.campaign.synthetic import synthetic_record

__all__ = ["Effects", "RealisticRecord", "add_effects", "realistic_record", "ringing_at_onsets"]

DRIFT_BAND = (0.2, 5.0)
"""Frequencies of the drift's sines [Hz]: thermal and charge-amplifier wander."""


@dataclass(frozen=True)
class Effects:
    """What a laboratory adds to the impacts; every effect is off by default (units N
    unless stated)."""

    pink: float = 0.0
    """Standard deviation of the 1/f noise [N]."""
    drift: float = 0.0
    """Largest excursion of the slow drift and wander from the record's start [N]."""
    hum: float = 0.0
    """Amplitude of the mains fundamental [N]."""
    mains: float = 50.0
    """Mains frequency [Hz] (50 or 60)."""
    harmonics: tuple = (0.3, 0.5, 0.1, 0.2)
    """Amplitudes of harmonics 2, 3, 4, 5 relative to the fundamental [-] (odd
    harmonics dominate a transformer's field)."""
    crosstalk: float = 0.0
    """Scale of the plate-mode ringing each impact's force drives, as a fraction of the
    impact's peak signal [-]: the initial amplitude of each mode's response to the
    impact's impulse delivered at once (0.5-1 times this, drawn per mode)."""
    plate_modes: tuple = ((730.0, 0.01), (1890.0, 0.02), (4100.0, 0.015))
    """Plate modes: ``(frequency [Hz], damping ratio [-])`` each."""
    full_scale: float | None = None
    """ADC range ``[-full_scale, +full_scale]`` [N]; samples beyond it are clipped to
    the rail (None: no ADC)."""
    bits: int = 16
    """ADC resolution [bits] (with ``full_scale``)."""
    steps: int = 0
    """Number of DC offset steps, at random times [-]."""
    step_size: float = 0.0
    """Height of each offset step, sign random [N]."""
    offsets: tuple = ()
    """Offset steps at given places: ``(time [s] from the record's first sample, height
    [N], signed)`` pairs, added to the ``steps`` random ones."""
    bounce: float = 0.0
    """Velocity of the bounce or second hit after each impact, as a fraction of the
    impact's [-] (0: none)."""
    bounce_delay: float = 2e-3
    """Time from an impact to its bounce [s]."""

    def __post_init__(self):
        _check_fields(self)

    @classmethod
    def everything(cls, noise, peak, **changes):
        """Every effect on, at levels usual in a laboratory, for impacts of peak signal
        ``peak`` [N] on white noise of standard deviation ``noise`` [N]: 1/f noise as
        large as the white noise, a drift of 20 noise sigmas, hum of 1.5 sigma, crosstalk
        of 2 % of each peak, a 16-bit ADC clipping at 1.2 times ``peak``, two offset steps
        of 8 sigma and bounces at 40 % of the velocity 2 ms later."""
        noise = check_number("noise", noise, low=0.0, low_open=False, unit="N")
        peak = check_number("peak", peak, low=0.0, unit="N")
        levels = {
            "pink": noise,
            "drift": 20.0 * noise,
            "hum": 1.5 * noise,
            "crosstalk": 0.02,
            "full_scale": 1.2 * peak,
            "bits": 16,
            "steps": 2,
            "step_size": 8.0 * noise,
            "bounce": 0.4,
            "bounce_delay": 2e-3,
        }
        return cls(**{**levels, **changes})


class RealisticRecord(NamedTuple):
    """A realistic record and what is known of it."""

    trace: Trace
    """The record (unit N, or V with a sensitivity)."""
    truth: pd.DataFrame
    """One row per impact and bounce, the columns of
    :data:`dem_check.campaign.synthetic.TRUTH_COLUMNS` and ``clipped`` (the ADC's rail
    was reached inside it)."""
    noise: float
    """Standard deviation of the random noise (white, 1/f and quantisation) [N]: the
    scale of the significance of an impact."""
    step_times: np.ndarray
    """Times of the offset steps [s]."""


def _pink(rng, count, sigma):
    """``count`` samples of 1/f noise of standard deviation ``sigma``."""
    if sigma == 0.0:
        return np.zeros(count)
    spectrum = rng.normal(size=count // 2 + 1) + 1j * rng.normal(size=count // 2 + 1)
    f = np.arange(spectrum.size, dtype=float)
    spectrum[1:] /= np.sqrt(f[1:])
    spectrum[0] = 0.0
    noise = np.fft.irfft(spectrum, count)
    return sigma * noise / noise.std()


def _drift(rng, t, size):
    """Slow wander: five sines of :data:`DRIFT_BAND` and a trend, largest excursion
    ``size`` from the start."""
    if size == 0.0:
        return np.zeros(t.size)
    wander = t * rng.uniform(-1.0, 1.0) / max(float(t[-1]), 1e-12)
    for f in rng.uniform(*DRIFT_BAND, 5):
        phase = rng.uniform(0.0, 2.0 * math.pi)
        wander += rng.uniform(0.3, 1.0) * (np.sin(2 * math.pi * f * t + phase) - math.sin(phase))
    return size * wander / np.max(np.abs(wander))


def _hum(rng, t, effects):
    if effects.hum == 0.0:
        return np.zeros(t.size)
    hum = np.zeros(t.size)
    for order, relative in enumerate((1.0, *effects.harmonics), start=1):
        phase = rng.uniform(0.0, 2.0 * math.pi)
        hum += relative * np.sin(2.0 * math.pi * order * effects.mains * t + phase)
    return effects.hum * hum


def _mode_response(t, drive, frequency, zeta):
    """A plate mode's response to ``drive`` [N/s]: the convolution with its impulse
    response ``exp(-zeta w s) sin(w s)`` (``w = 2 pi frequency``), exact for a drive
    linear between the samples (first-order hold; scipy ``cont2discrete``)."""
    from scipy.signal import cont2discrete, lfilter  # scipy.signal is slow to import

    w = 2.0 * math.pi * frequency
    # Laplace transform of exp(-a s) sin(w s): w / ((s + a)**2 + w**2)
    a = zeta * w
    num, den, _ = cont2discrete(([w], [1.0, 2.0 * a, a * a + w * w]), t[1] - t[0], method="foh")
    return lfilter(np.ravel(num), den, drive)


def _crosstalk(rng, t, clean, truth, effects):
    """The plate's modes driven by each impact's force on it (zero before its onset).

    The sensor stands on the plate: what the plate feels is the sensor's force, the
    clean signal. A linear structure answers it by convolution, so its ringing starts
    with the force and builds up through the contact (not at full amplitude at the
    touch). Each impact's force (its clean signal up to the next onset) is scaled by
    its first lobe's integral (its impulse): the response to the impulse delivered at
    once would start at ``crosstalk`` times the impact's peak signal times U(0.5, 1),
    drawn per impact and mode; a pulse of finite length rings a little less (by its
    Fourier transform at the mode over its impulse: 0.85 for 100 us at 4100 Hz).
    """
    ringing = np.zeros(t.size)
    if effects.crosstalk == 0.0:
        return ringing
    starts = np.searchsorted(t, truth["onset [s]"].to_numpy())
    following = np.append(np.sort(starts), t.size)  # each force lasts to the next onset
    ends = following[np.searchsorted(following[:-1], starts, side="right")]
    drives = [np.zeros(t.size) for _ in effects.plate_modes]
    for start, end, peak in zip(starts, ends, truth["peak_sensor_force [N]"], strict=True):
        force = clean[start:end]
        area = _first_lobe_area(force, t[1] - t[0] if t.size > 1 else 1.0)
        for drive in drives:
            weight = effects.crosstalk * peak * rng.uniform(0.5, 1.0)
            if area > 0.0:  # no force, no response
                drive[start:end] += weight * force / area
    if t.size < 2:
        return ringing
    for drive, (frequency, zeta) in zip(drives, effects.plate_modes, strict=True):
        ringing += _mode_response(t, drive, frequency, zeta)
    return ringing


def _first_lobe_area(force, dt):
    """Integral [N*s] of ``force`` from its start to where it first falls to zero or
    below after its peak (the contact's pulse; the sensor's ringing after it integrates
    to about nothing)."""
    if not force.size or force.max() <= 0.0:
        return 0.0
    top = int(np.argmax(force))
    below = np.flatnonzero(force[top:] <= 0.0)
    end = top + int(below[0]) if below.size else force.size
    return float(np.sum(force[:end]) * dt)


def _steps(rng, t, effects):
    """The offset steps' levels at every sample [N] and their times [s], in time order:
    ``steps`` at random times, then ``offsets``."""
    times = np.sort(rng.uniform(t[0], t[-1], effects.steps))
    heights = effects.step_size * rng.choice((-1.0, 1.0), size=times.size)
    placed = np.array(effects.offsets, dtype=float).reshape(-1, 2)
    times = np.concatenate([times, t[0] + placed[:, 0]])
    heights = np.concatenate([heights, placed[:, 1]])
    levels = np.zeros(t.size)
    for at, height in zip(times, heights, strict=True):
        levels[t >= at] += height
    return levels, np.sort(times)


def _adc(values, effects):
    """Quantised to the ADC's steps and clipped at its rails; which samples hit a rail."""
    if effects.full_scale is None:
        return values, np.zeros(values.size, dtype=bool)
    top = effects.full_scale
    lsb = 2.0 * top / 2**effects.bits
    clipped = np.abs(values) >= top
    return np.clip(np.round(values / lsb) * lsb, -top, top), clipped


def add_effects(t, clean, effects, truth, noise, rng):
    """A clean signal with white noise and a laboratory's :class:`Effects` added.

    Parameters
    ----------
    t, clean : numpy.ndarray
        Time [s] and the clean signal [N].
    effects : Effects
    truth : pandas.DataFrame
        ``onset [s]`` and ``peak_sensor_force [N]`` of each impact (the crosstalk rings after
        each).
    noise : float
        White noise standard deviation [N].
    rng : numpy.random.Generator

    Returns
    -------
    values : numpy.ndarray
        [N], quantised and clipped by the ADC if ``effects.full_scale`` is set.
    rail : numpy.ndarray of bool
        Samples at an ADC rail.
    step_times : numpy.ndarray
        Times of the offset steps [s].
    """
    _check_effects(effects)
    white = rng.normal(0.0, check_number("noise", noise, low=0.0, low_open=False), t.size)
    random_part = white + _pink(rng, t.size, effects.pink)
    levels, step_times = _steps(rng, t, effects)
    values = (
        clean
        + random_part
        + _drift(rng, t, effects.drift)
        + _hum(rng, t, effects)
        + _crosstalk(rng, t, clean, truth, effects)
        + levels
    )
    values, rail = _adc(values, effects)
    return values, rail, step_times


def _check_effects(effects):
    if not isinstance(effects, Effects):
        raise ParameterError(f"effects must be a dem_check.campaign.Effects; got {effects!r}")


def _check_fields(effects):
    """Every field of an :class:`Effects`, each refused by its name; the sequences as
    tuples of floats."""
    for name in ("pink", "drift", "hum", "crosstalk", "step_size", "bounce"):
        check_number(name, getattr(effects, name), low=0.0, low_open=False)
    check_number("mains", effects.mains, low=0.0, unit="Hz")
    check_number("bounce_delay", effects.bounce_delay, low=0.0, unit="s")
    check_count("bits", effects.bits, low=2)
    check_count("steps", effects.steps, low=0)
    if effects.full_scale is not None:
        check_number("full_scale", effects.full_scale, low=0.0, unit="N")
    harmonics = tuple(
        check_number("harmonics", h, low=0.0, low_open=False)
        for h in _sequence("harmonics", effects.harmonics)
    )
    modes = []
    for mode in _sequence("plate_modes", effects.plate_modes):
        pair = _sequence("plate_modes", mode)
        if len(pair) != 2:
            raise ParameterError(
                f"plate_modes must hold (frequency [Hz], damping ratio) pairs; got {mode!r}"
            )
        modes.append(
            (
                check_number("plate_modes frequency", pair[0], low=0.0, unit="Hz"),
                check_number(
                    "plate_modes damping ratio", pair[1], low=0.0, high=1.0, high_open=True
                ),
            )
        )
    offsets = []
    for step in _sequence("offsets", effects.offsets):
        pair = _sequence("offsets", step)
        if len(pair) != 2:
            raise ParameterError(f"offsets must hold (time [s], height [N]) pairs; got {pair!r}")
        offsets.append(
            (
                check_number("offsets time", pair[0], low=0.0, low_open=False, unit="s"),
                check_number("offsets height", pair[1], unit="N"),
            )
        )
    object.__setattr__(effects, "harmonics", harmonics)
    object.__setattr__(effects, "plate_modes", tuple(modes))
    object.__setattr__(effects, "offsets", tuple(offsets))


def _sequence(name, value):
    """``value`` as a tuple, refused by ``name`` when it is not a sequence."""
    if isinstance(value, str | bytes) or not isinstance(value, tuple | list | np.ndarray):
        raise ParameterError(f"{name} must be a sequence; got {value!r}")
    return tuple(value)


def realistic_record(
    grain,
    sensor,
    law,
    velocities,
    onsets,
    *,
    length,
    sample_rate,
    noise=0.02,
    effects=Effects(),
    trigger=None,
    sensitivity=None,
    seed=0,
):
    """A record of impacts with a laboratory's noise, drift, hum, crosstalk and ADC.

    Parameters
    ----------
    grain, sensor, law, velocities, onsets, length, sample_rate, noise, seed
        As for :func:`dem_check.campaign.synthetic_record` (``noise``: white noise
        [N]); an onset of 0 puts the impact at the record's first sample (no
        pre-trigger).
    effects : Effects
        What is added (module docstring); the default adds nothing.
    trigger : float, optional
        Trigger time [s] from the record's start: the time axis is shifted so that the
        trigger is at t = 0 (trigger-aligned files, as oscilloscopes write them) and
        ``metadata["trigger_time"]`` is 0.
    sensitivity : float, optional
        [V/N]: the record is then in volts (everything above is scaled).

    Returns
    -------
    RealisticRecord
    """
    _check_effects(effects)
    velocities = np.atleast_1d(check_samples("velocities", velocities, ndim=None))
    onsets = np.atleast_1d(check_samples("onsets", onsets, ndim=None))
    if trigger is not None:
        trigger = check_number("trigger", trigger, unit="s")
    if sensitivity is not None:
        sensitivity = check_number("sensitivity", sensitivity, low=0.0, unit="V/N")
    if effects.bounce > 0.0 and velocities.size:
        later = onsets + effects.bounce_delay
        inside = later < length
        onsets = np.concatenate([onsets, later[inside]])
        velocities = np.concatenate([velocities, effects.bounce * velocities[inside]])
        order = np.argsort(onsets, kind="stable")
        onsets, velocities = onsets[order], velocities[order]
    sampling = {"length": length, "sample_rate": sample_rate}
    clean, truth = synthetic_record(grain, sensor, law, velocities, onsets, **sampling, noise=0.0)
    rng = np.random.default_rng(check_count("seed", seed, low=0))
    t = np.asarray(clean.t)
    values, rail, step_times = add_effects(t, np.asarray(clean.values), effects, truth, noise, rng)
    lsb = 0.0 if effects.full_scale is None else 2.0 * effects.full_scale / 2**effects.bits
    truth["clipped"] = [
        bool(rail[(t >= at) & (t < at + 10.0 * sensor.period)].any()) for at in truth["onset [s]"]
    ]
    unit, scale = ("N", 1.0) if sensitivity is None else ("V", sensitivity)
    shift = 0.0 if trigger is None else float(trigger)
    metadata = {
        **clean.metadata,
        "instrument": "realistic laboratory record (dem_check.campaign.realistic_record)",
        "trigger_time": None if trigger is None else 0.0,
    }
    trace = Trace(t - shift, values * scale, unit, metadata)
    truth["onset [s]"] = truth["onset [s]"] - shift
    random_noise = math.sqrt(noise**2 + effects.pink**2 + lsb**2 / 12.0)
    return RealisticRecord(trace, truth, random_noise, step_times - shift)


def ringing_at_onsets(truth, effects):
    """Largest amplitude of the structure's ringing (the crosstalk of the impacts before)
    at each true onset [N]: every plate mode at its largest initial weight, decayed
    since; the scale, with the random noise, of how clear an impact is.

    Parameters
    ----------
    truth : pandas.DataFrame
        ``onset [s]`` and ``peak_sensor_force [N]`` of each impact, in time order.
    effects : Effects

    Returns
    -------
    numpy.ndarray
    """
    onsets, peaks = truth["onset [s]"].to_numpy(), truth["peak_sensor_force [N]"].to_numpy()
    out = np.zeros(onsets.size)
    for k, at in enumerate(onsets):
        since = at - onsets[onsets < at]
        for frequency, zeta in effects.plate_modes:
            decay = np.exp(-zeta * 2.0 * np.pi * frequency * since)
            out[k] += effects.crosstalk * float(np.sum(peaks[onsets < at] * decay))
    return out
