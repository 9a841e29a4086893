"""Structural crosstalk: the structure's own modes ringing after a hit, found and removed.

A force sensor sits on a plate, a frame or a table; the hit that loads the sensor also
excites the structure's modes (a few hundred hertz to a few kilohertz), whose ringing
reaches the sensor's channel and lasts long after the contact (issue 22: at 2 % of the
peak it added up to 14 % to the impulse and doubled the reconstructed contact time,
since the reconstructed force did not fall to 2 % of its peak while it rang). The
sensor's own mode is known; the others are read where the sensor's signal holds no
contact:

1. **Identification** (:func:`structure_modes`) on the ringing after the contact: the
   window less a quadratic and the sensor's free ringing (fitted by least squares with
   the sensor's resonance and damping ratio) is low-passed at :data:`BAND_FRACTION` of
   the sensor resonance, decimated to :data:`DECIMATED_PER_CUTOFF` samples per cutoff
   period and given to the matrix pencil
   (:func:`contactlab.inverse.identify.matrix_pencil`); its oscillating poles in the band
   with a damping ratio under :data:`MAX_DAMPING` are the candidate modes.
2. **Fit** (:func:`fit_crosstalk`) on the samples before the impact and after its contact:
   a quadratic, the sensor's free ringing after the contact and, for each mode, its
   response to the pulse (the pulse's samples convolved with the mode's damped cosine
   and sine: a linear structure answers the contact force so, and the response starts
   with the force) and, where the window before the impact holds half a period of it,
   the mode's free ringing from earlier hits. A mode whose response amplitude is not
   :data:`SIGNIFICANCE` standard errors above zero is dropped and the rest refitted.
3. The crosstalk (responses and free ringing of the kept modes) is evaluated through the
   pulse, where it cannot be read, and returned, to be subtracted before the impulse,
   the peak and a force reconstruction.

Modes between :data:`BAND_FRACTION` of the sensor resonance and the resonance itself are
not separated from the sensor's response (the low-pass that removes the sensor's ringing
removes them too).

References
----------
Hua Y., Sarkar T.K. (1990) Matrix pencil method for estimating parameters of
exponentially damped/undamped sinusoids in noise. IEEE Trans. Acoust. Speech Signal
Process. 38, 814-824. DOI 10.1109/29.56027
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal

from contactlab.errors import ParameterError
from contactlab.inverse.identify import matrix_pencil
from contactlab.signals import lowpass
from contactlab.validation import check_count, check_samples

__all__ = [
    "BAND_FRACTION",
    "MAX_DAMPING",
    "SIGNIFICANCE",
    "Crosstalk",
    "StructureMode",
    "fit_crosstalk",
    "structure_modes",
]

BAND_FRACTION = 0.25
"""Highest structure mode sought, as a fraction of the sensor resonance [-]; the
identification low-passes there (a fourth-order Butterworth applied twice keeps the
sensor's ringing to ``4**-8``, 1.5e-5, of its amplitude)."""

DECIMATED_PER_CUTOFF = 3.0
"""Samples per cutoff period after decimation [-] (above the Nyquist rate's 2)."""

MAX_MODES = 4
"""Most structure modes sought per impact [-]."""

SLOW_POLES = 8
"""Extra pencil order for what the quadratic left: wander, hum and 1/f noise [-]."""

MAX_DAMPING = 0.06
"""Largest damping ratio of a structure mode [-]: plates, frames and tables ring with
damping ratios of 0.001-0.05; a more damped pole is the pencil's model of 1/f noise,
drift or hum (on 2 MHz records with 1/f noise as large as the white noise, poles of
damping 0.07-0.2 at 700-6600 Hz appeared without a mode there)."""

SIGNIFICANCE = 5.0
"""A mode is removed only when its response amplitude is this many standard errors
above zero [-] (the standard error assumes white noise: 1/f noise makes it optimistic,
hence five rather than three)."""


@dataclass(frozen=True)
class StructureMode:
    """One structure mode removed from an impact."""

    frequency: float
    """Damped frequency [Hz]."""
    damping_ratio: float
    """[-]."""
    amplitude: float
    """Initial amplitude of the mode's response to this impact (unit of the record, N)."""


@dataclass(frozen=True, eq=False)
class Crosstalk:
    """The structure's crosstalk in a stretch of a record (see :func:`fit_crosstalk`)."""

    modes: tuple
    """:class:`StructureMode` of each mode removed (empty when none was significant)."""
    values: np.ndarray
    """The crosstalk at every sample of the stretch (responses to this impact and free
    ringing from earlier ones), to be subtracted (unit of the record)."""

    def describe(self):
        """``"730 Hz (zeta 0.010): 0.041 N; ..."``, or ``""`` when no mode was removed."""
        return "; ".join(
            f"{m.frequency:.0f} Hz (zeta {m.damping_ratio:.3f}): {m.amplitude:.3g} N"
            for m in self.modes
        )


def _quadratic(t):
    centre, scale = float(t.mean()), max(float(np.ptp(t)), 1e-300)
    return np.vander((t - centre) / scale, 3, increasing=True)


def _sensor_ringing(t, start, sensor):
    """The sensor's free ringing from ``start`` [s] (zero before it), two columns."""
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    s = np.maximum(t - start, 0.0)
    decay = np.exp(-zeta * w * s) * (t >= start)
    wd = w * math.sqrt(max(1.0 - zeta**2, 0.0))
    return np.stack([decay * np.cos(wd * s), decay * np.sin(wd * s)], axis=1)


def structure_modes(t, y, sensor, *, max_modes=MAX_MODES):
    """Candidate structure modes in a window of ringing after a contact.

    Parameters
    ----------
    t, y : array_like
        The window: uniformly spaced times [s] and the record (any unit); it must hold no
        contact (it starts after the contact's end).
    sensor : Sensor
        The moving sensor (its mode is not a structure mode).
    max_modes : int, default 4
        Most modes sought.

    Returns
    -------
    list of (float, float)
        ``(frequency [Hz], damping ratio [-])`` of each oscillating pole of the window
        between one period per window and :data:`BAND_FRACTION` of the sensor resonance,
        damping ratio in ``(0, MAX_DAMPING)``.

    Raises
    ------
    ParameterError
        Bad arguments, or a window too short for the pencil (fewer than three samples
        per pencil order after decimation).
    """
    t, y = check_samples("t", t), check_samples("y", y)
    max_modes = check_count("max_modes", max_modes)
    if t.shape != y.shape or t.size < 16:
        raise ParameterError(f"t and y must be equal 1-D windows of >= 16 samples; got {t.size}")
    dt = float(t[1] - t[0])
    columns = np.concatenate([_quadratic(t), _sensor_ringing(t, t[0], sensor)], axis=1)
    coefficients, *_ = np.linalg.lstsq(columns, y, rcond=None)
    rest = y - columns @ coefficients
    cutoff = BAND_FRACTION * sensor.resonance
    step = max(1, int(1.0 / (DECIMATED_PER_CUTOFF * cutoff * dt)))
    order = 2 * max_modes + SLOW_POLES
    if rest.size // step < 3 * order:
        raise ParameterError(
            f"the window of {np.ptp(t):.3g} s is too short to identify {max_modes} structure "
            f"modes: it needs {3 * order * step * dt:.3g} s (three decimated samples per "
            "pencil order)"
        )
    if cutoff < 0.4 / dt and rest.size > 30:
        rest = lowpass(rest, dt, cutoff)
    decimated, tau = rest[::step], t[::step] - t[0]
    poles = matrix_pencil(decimated, dt * step, order)
    low = 1.0 / float(np.ptp(t))
    candidates = []
    for pole in poles[poles.imag > 0.0]:
        w = abs(pole)
        zeta = -pole.real / w if w > 0.0 else 1.0
        frequency = pole.imag / (2.0 * math.pi)
        if low <= frequency <= cutoff and 0.0 < zeta < MAX_DAMPING:
            candidates.append((float(frequency), float(zeta), complex(pole)))
    return sorted(_significant(tau, decimated, candidates))


def _significant(tau, y, candidates):
    """The candidates whose amplitude, fitted with the others and a constant on the
    decimated window, is :data:`SIGNIFICANCE` standard errors above zero (the decimated
    samples' residual holds the noise of the band, 1/f noise included)."""
    if not candidates:
        return []
    columns = [np.ones((tau.size, 1))] + [_free(tau, 0.0, pole) for *_, pole in candidates]
    coefficients, covariance = _least_squares(np.concatenate(columns, axis=1), y)
    return [
        (frequency, zeta)
        for k, (frequency, zeta, _) in enumerate(candidates)
        if _pair(coefficients, covariance, 1 + 2 * k)[1]
    ]


def _least_squares(design, y):
    """Coefficients and their covariance (white residual) of ``design @ c = y``."""
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coefficients
    dof = max(design.shape[0] - design.shape[1], 1)
    return coefficients, np.linalg.pinv(design.T @ design) * float(residual @ residual) / dof


def _pair(coefficients, covariance, index):
    """Amplitude of the cosine-sine pair at ``index`` and whether it is
    :data:`SIGNIFICANCE` standard errors (along itself) above zero."""
    pair = coefficients[index : index + 2]
    norm = float(np.hypot(*pair))
    variance = float(pair @ covariance[index : index + 2, index : index + 2] @ pair)
    return norm, norm > SIGNIFICANCE * math.sqrt(max(variance, 0.0)) / max(norm, 1e-300)


def _responses(t, force, onset, frequency, zeta):
    """The mode's response to ``force`` (zero outside the pulse): the pulse convolved
    with ``exp(-a s) cos(b s)`` and ``... sin(b s)``, two columns (one-pole complex
    recursion, exact for samples), and ``|G|``: the response's initial amplitude per
    unit coefficient, referred to ``onset``."""
    dt = float(t[1] - t[0])
    b = 2.0 * math.pi * frequency
    pole = complex(-zeta * b / math.sqrt(max(1.0 - zeta**2, 1e-300)), b)
    response = signal.lfilter([dt], [1.0, -np.exp(pole * dt)], force.astype(complex))
    gain = complex(np.sum(force * dt * np.exp(-pole * (t - onset))))
    return np.stack([response.real, response.imag], axis=1), abs(gain), pole


def _free(t, onset, pole):
    s = t - onset
    decay = np.exp(pole.real * s)
    return np.stack([decay * np.cos(pole.imag * s), decay * np.sin(pole.imag * s)], axis=1)


def fit_crosstalk(t, y, sensor, onset, pulse, fitted, post_start, modes):
    """The crosstalk of the given structure modes in a stretch of a record.

    Parameters
    ----------
    t, y : numpy.ndarray
        The stretch: uniformly spaced times [s] and the record (any unit), holding the
        impact, samples before it and its ringing after.
    sensor : Sensor
    onset : float
        The impact's onset [s] (the responses' time reference).
    pulse : numpy.ndarray of bool
        Samples of the pulse (from the onset to the contact's end): the force the
        structure answers, read as the record less the median of the fitted samples
        before the onset.
    fitted : numpy.ndarray of bool
        Samples the crosstalk is fitted on: before the impact and after its contact
        (none inside the pulse).
    post_start : float
        Start of the ringing after the contact [s] (the sensor's free ringing starts
        there).
    modes : list of (float, float)
        ``(frequency [Hz], damping ratio [-])`` (e.g. from :func:`structure_modes`).

    Returns
    -------
    Crosstalk
    """
    before = fitted & (t < onset)
    level = float(np.median(y[before])) if before.sum() >= 8 else 0.0
    force = np.where(pulse, y - level, 0.0)
    pre_span = float(np.ptp(t[before])) if before.any() else 0.0
    base = np.concatenate([_quadratic(t), _sensor_ringing(t, post_start, sensor)], axis=1)
    kept = list(modes)
    while True:
        columns, parts = [base], []
        for frequency, zeta in kept:
            response, gain, pole = _responses(t, force, onset, frequency, zeta)
            free = pre_span >= 0.5 / frequency  # earlier ringing can be told apart
            columns += [response, _free(t, onset, pole)] if free else [response]
            parts.append((frequency, zeta, gain, free))
        if not parts:
            return Crosstalk((), np.zeros(t.size))
        design = np.concatenate(columns, axis=1)
        coefficients, covariance = _least_squares(design[fitted], y[fitted])
        significant, found, index = [], [], base.shape[1]
        for frequency, zeta, gain, free in parts:
            norm, enough = _pair(coefficients, covariance, index)
            significant.append(enough)
            found.append(StructureMode(frequency, zeta, gain * norm))
            index += 4 if free else 2
        if all(significant):
            crosstalk = design[:, base.shape[1] :] @ coefficients[base.shape[1] :]
            return Crosstalk(tuple(found), crosstalk)
        kept = [mode for mode, keep in zip(kept, significant, strict=True) if keep]
