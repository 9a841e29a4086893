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
   with a damping ratio under :data:`MAX_DAMPING` are the candidate modes. Several
   impacts' windows, short ones included, are read together by
   :func:`joint_structure_modes` (a multi-channel matrix pencil, its poles refined by
   variable projection on all the windows).
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

import numpy as np
from scipy import signal

from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError
from contactlab.inverse.crosstalk_result import Crosstalk, StructureMode
from contactlab.inverse.identify import matrix_pencil
from contactlab.inverse.least_squares_covariance import coloured_covariance, linear_least_squares
from contactlab.inverse.local_baseline import _ringing
from contactlab.inverse.ringdown import MIN_DAMPING, free_ringing_residual, refine_unheld
from contactlab.signals import lowpass
from contactlab.validation import check_count, check_samples

__all__ = [
    "BAND_FRACTION",
    "MAX_DAMPING",
    "SIGNIFICANCE",
    "Crosstalk",
    "StructureMode",
    "fit_crosstalk",
    "joint_structure_modes",
    "structure_band",
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

JOINT_PENCIL = 2
"""Pencil parameter of :func:`joint_structure_modes` in pencil orders [-]: each window's
Hankel rows span twice the order (32 decimated samples, 1.1 ms for a 40 kHz sensor), so
windows from 1.1 ms on contribute."""

MAX_DAMPING = 0.06
"""Largest damping ratio of a structure mode [-]: plates, frames and tables ring with
damping ratios of 0.001-0.05; a more damped pole is the pencil's model of 1/f noise,
drift or hum (on 2 MHz records with 1/f noise as large as the white noise, poles of
damping 0.07-0.2 at 700-6600 Hz appeared without a mode there)."""

START_DAMPING = 2.0 * MAX_DAMPING
"""Largest damping ratio of a pencil pole that starts a refinement [-] (moved inside
:data:`MAX_DAMPING` to start; a pole the refinement leaves there is dropped): on short,
noisy windows the pencil's damping is biased up, and a plate's 730 Hz mode (damping
0.01) came out of the joint pencil at 719 Hz, damping 0.061, and was missed in a 1 MHz
record; refined from there, 727 Hz, damping 0.037 (``docs/campaign.md``, "Crosstalk")."""

SIGNIFICANCE = 5.0
"""A mode is removed only when its response amplitude is this many standard errors
above zero [-] (the standard error assumes white noise: 1/f noise makes it optimistic,
hence five rather than three)."""


def _quadratic(t):
    centre, scale = float(t.mean()), max(float(np.ptp(t)), 1e-300)
    return np.vander((t - centre) / scale, 3, increasing=True)


def _sensor_ringing(t, start, sensor):
    """The sensor's free ringing from ``start`` [s] (zero before it), two columns."""
    columns, _, _ = _ringing(np.maximum(t - start, 0.0), sensor)
    return columns * (t >= start)[:, None]


def structure_modes(t, y, sensor, *, max_modes=MAX_MODES, noise=None, refine=False):
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
    noise : tuple of array_like, optional
        ``(t [s], y)`` of a stretch of the same record without contact or ringing (a
        pre-trigger), at the window's interval: each candidate's standard error is then
        also computed under the noise this stretch shows in the band (its
        autocovariance, the Fourier transform of its spectrum;
        :func:`~contactlab.inverse.least_squares_covariance.coloured_covariance`), and
        the larger of that and the white-noise one is used. 1/f noise puts more power
        near a low-frequency pole than the window's residual shows, and the pencil can
        fit it as a mode.
    refine : bool, default False
        Refine the pencil's poles in the band, growing ones included, on the window's
        block means less a line (:func:`~contactlab.inverse.ringdown.refine_unheld`), as
        :func:`joint_structure_modes` does: on two to three periods the pencil can read a
        mode growing (a record that starts at its impact: 730 Hz at damping -0.006,
        dropped). :func:`~contactlab.inverse.single_crosstalk.single_impact_crosstalk`
        refines; the campaign's window-by-window
        identification does not (its joint pencil does).

    Returns
    -------
    list of (float, float)
        ``(frequency [Hz], damping ratio [-])`` of each oscillating pole of the window
        (refined with ``refine``) between one period per window and
        :data:`BAND_FRACTION` of the sensor resonance, damping ratio in ``(0,
        MAX_DAMPING)``.

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
    refine = check_flag("refine", refine)
    order = 2 * max_modes + SLOW_POLES
    tau, decimated, step = structure_band(t, y, sensor, degree=1 if refine else 2, blocks=refine)
    if t.size // round(step / float(t[1] - t[0])) < 3 * order:
        raise ParameterError(
            f"the window of {np.ptp(t):.3g} s is too short to identify {max_modes} structure "
            f"modes: it needs {3 * order * step:.3g} s (three decimated samples per "
            "pencil order)"
        )
    poles = matrix_pencil(decimated, step, order)
    band = (1.0 / float(np.ptp(t)), BAND_FRACTION * sensor.resonance)
    candidates = _in_band(poles, *band, growing=refine)
    if refine and candidates:
        poles = [pole for *_, pole in candidates]
        poles = refine_unheld([(tau, decimated)], poles, (MIN_DAMPING, MAX_DAMPING))
        candidates = _in_band(poles, *band)
    autocovariance = None if noise is None else _autocovariance(noise, sensor, decimated.size)
    keep = _significant(tau, decimated, candidates, degree=0, autocovariance=autocovariance)
    return sorted((f, z) for (f, z, _), k in zip(candidates, keep, strict=True) if k)


def joint_structure_modes(windows, sensor, *, max_modes=MAX_MODES, refine=True):
    """Candidate structure modes common to several windows of ringing, and where each is
    significant: a multi-channel matrix pencil.

    A structure rings at the same poles after every hit, with amplitudes that differ from
    hit to hit. Each window (less a line and the sensor's free ringing, low-passed and
    decimated as in :func:`structure_modes`) gives the rows of a Hankel matrix of
    :data:`JOINT_PENCIL` orders' columns; the rows of every window are stacked and the
    poles are those of the stacked matrix's dominant right singular vectors (the
    multi-channel pencil: the windows share the poles, not the amplitudes). A window too
    short for :func:`structure_modes` (three decimated samples per pencil order: 1.6 ms
    for a 40 kHz sensor) still adds its rows, so impacts 1-2 ms apart contribute.

    With ``refine`` the pencil's poles in the band, growing ones included (noise on
    windows of one to three periods biases them: ``docs/campaign.md``, "Crosstalk"), are
    refined on every window (:func:`contactlab.inverse.ringdown.refine_unheld`: those
    left at :data:`MAX_DAMPING` dropped, the rest refined again without them). Each
    candidate's amplitude is then fitted with the others', a constant and a line on each
    window, and tested as in :func:`structure_modes`.

    Parameters
    ----------
    windows : sequence of (array_like, array_like)
        ``(t [s], y)`` of each window of ringing after a contact, uniformly spaced at one
        interval, each of at least 16 samples.
    sensor : Sensor
    max_modes : int, default 4
    refine : bool, default True
        Refine the pencil's poles (above); False: the pencil's decaying poles as they are.

    Returns
    -------
    candidates : list of (float, float)
        ``(frequency [Hz], damping ratio [-])`` of each oscillating pole (refined) between
        one period per longest window and :data:`BAND_FRACTION` of the sensor resonance,
        damping ratio in ``(0, MAX_DAMPING)``, by frequency.
    significant : numpy.ndarray of bool
        ``(windows, candidates)``: where each candidate's amplitude is
        :data:`SIGNIFICANCE` standard errors above zero.
    """
    max_modes = check_count("max_modes", max_modes)
    bands = []
    for window in windows:
        try:
            t, y = check_samples("t", window[0]), check_samples("y", window[1])
        except (TypeError, IndexError, KeyError):
            raise ParameterError(f"windows must hold (t, y) pairs; got {window!r:.60}") from None
        if t.shape != y.shape or t.size < 16:
            raise ParameterError(
                f"each window must be equal t and y of >= 16 samples; got {t.size}"
            )
        bands.append(structure_band(t, y, sensor, degree=1, blocks=True))
    order = 2 * max_modes + SLOW_POLES
    pencil = JOINT_PENCIL * order
    views = np.lib.stride_tricks.sliding_window_view
    rows = [views(samples, pencil + 1) for _, samples, _ in bands if samples.size > pencil + 1]
    empty = np.zeros((len(bands), 0), dtype=bool)
    if sum(r.shape[0] for r in rows) < 2 * order:
        return [], empty
    _, _, vh = np.linalg.svd(np.concatenate(rows), full_matrices=False)
    v = vh[:order].T
    z = np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:]).astype(complex)
    longest = max(float(tau[-1]) for tau, _, _ in bands)
    band = (1.0 / longest, BAND_FRACTION * sensor.resonance)
    candidates = _in_band(np.log(z) / bands[0][2], *band, growing=refine)
    if refine and candidates:
        poles = [pole for *_, pole in candidates]
        poles = refine_unheld([b[:2] for b in bands], poles, (MIN_DAMPING, MAX_DAMPING))
        candidates = _in_band(poles, *band)
    candidates = sorted(candidates)
    if not candidates:
        return [], empty
    significant = np.array([_significant(tau, x, candidates, degree=1) for tau, x, _ in bands])
    return [(f, z) for f, z, _ in candidates], significant


def structure_band(t, y, sensor, degree, blocks=False):
    """The band in which structure modes are sought: a window less a polynomial and the
    sensor's free ringing, low-passed and decimated.

    Parameters
    ----------
    t, y : numpy.ndarray
        The window's uniform times [s] and samples (unit of the record, N).
    sensor : contactlab.Sensor
        The sensor whose free ringing (resonance and damping ratio) is fitted by least
        squares together with the polynomial.
    degree : int
        Degree of the polynomial [-] (0: the mean only).
    blocks : bool, default False
        Decimate by the means of consecutive blocks instead of a low-pass at
        :data:`BAND_FRACTION` of the sensor resonance (a boxcar: a damped exponential
        stays one, with the same pole, to the window's edges, where the zero-phase
        low-pass's end extension bends a window of a few periods).

    Returns
    -------
    tuple
        ``(tau, samples, interval)``: the decimated times from the window's start [s],
        the band's samples (unit of ``y``) and the decimated interval [s]
        (:data:`DECIMATED_PER_CUTOFF` samples per cutoff period).
    """
    dt = float(t[1] - t[0])
    rest = free_ringing_residual(t, y, sensor, degree)
    cutoff = BAND_FRACTION * sensor.resonance
    step = max(1, int(1.0 / (DECIMATED_PER_CUTOFF * cutoff * dt)))
    if blocks:
        count = rest.size // step
        means = rest[: count * step].reshape(count, step).mean(axis=1)
        return t[: count * step : step] - t[0] + 0.5 * (step - 1) * dt, means, dt * step
    if cutoff < 0.4 / dt and rest.size > 30:
        rest = lowpass(rest, dt, cutoff)
    return t[::step] - t[0], rest[::step], dt * step


def _in_band(poles, low, cutoff, growing=False):
    """``(frequency [Hz], damping ratio [-], pole)`` of the oscillating poles from ``low`` to
    ``cutoff`` [Hz], damping ratio in ``(0, MAX_DAMPING)`` (``growing``: the starts of a
    refinement, from -MAX_DAMPING to :data:`START_DAMPING`)."""
    candidates = []
    largest = START_DAMPING if growing else MAX_DAMPING
    for pole in poles[poles.imag > 0.0]:
        w = abs(pole)
        zeta = -pole.real / w if w > 0.0 else 1.0
        frequency = pole.imag / (2.0 * math.pi)
        if low <= frequency <= cutoff and (-MAX_DAMPING if growing else 0.0) < zeta < largest:
            candidates.append((float(frequency), float(zeta), complex(pole)))
    return candidates


def _autocovariance(noise, sensor, lags):
    """Biased autocovariance of a noise stretch's band (:func:`structure_band` less its
    mean only: a quadratic would take 1/f power near a low pole out of a short pre-trigger) at
    ``lags`` decimated lags, zero beyond the stretch."""
    t, y = check_samples("noise t", noise[0]), check_samples("noise y", noise[1])
    if t.shape != y.shape or t.size < 16:
        raise ParameterError(f"noise must be equal t and y of >= 16 samples; got {t.size}")
    _, band, _ = structure_band(t, y, sensor, degree=0)
    full = signal.correlate(band, band, mode="full", method="fft")[band.size - 1 :] / band.size
    return np.concatenate([full, np.zeros(max(lags - full.size, 0))])[:lags]


def _significant(tau, y, candidates, degree, autocovariance=None):
    """Whether each candidate's amplitude, fitted with the others and a polynomial of
    ``degree`` on the decimated window, is :data:`SIGNIFICANCE` standard errors above
    zero (the decimated samples' residual holds the noise of the band, 1/f noise
    included; with ``autocovariance``, the larger of that and the coloured noise's
    error), one bool per candidate."""
    if not candidates:
        return []
    polynomial = np.vander(tau - tau.mean(), degree + 1, increasing=True)
    columns = [polynomial] + [_free(tau, 0.0, pole) for *_, pole in candidates]
    design = np.concatenate(columns, axis=1)
    coefficients, covariance = linear_least_squares(design, y)
    if autocovariance is not None:
        coloured = coloured_covariance(design, autocovariance)
        return [
            _pair(coefficients, covariance, degree + 1 + 2 * k)[1]
            and _pair(coefficients, coloured, degree + 1 + 2 * k)[1]
            for k in range(len(candidates))
        ]
    return [_pair(coefficients, covariance, degree + 1 + 2 * k)[1] for k in range(len(candidates))]


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


def fit_crosstalk(
    t, y, sensor, onset, pulse, fitted, post_start, modes, *, drop=True, autocovariance=None
):
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
    drop : bool, default True
        Drop the modes whose response is not :data:`SIGNIFICANCE` standard errors above
        zero and refit the others (modes found on this impact's ringing alone); False:
        fit and remove every mode given (modes found after several impacts: a mode left
        out of the fit biases the others' amplitudes where their columns overlap on
        windows of a few periods, ``docs/campaign.md``, "Crosstalk").
    autocovariance : array_like, optional
        The noise's autocovariance at lags of ``0, 1, ...`` samples, at least as many as
        the stretch's (unit of the record squared): the coefficients' covariance
        (:attr:`Crosstalk.covariance`) is then that of least squares under this
        stationary noise, ``(X'X)^-1 X' R X (X'X)^-1``; otherwise that of a white
        residual. The significance test uses the white one either way.

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
        coefficients, covariance = linear_least_squares(design[fitted], y[fitted])
        significant, found, index = [], [], base.shape[1]
        for frequency, zeta, gain, free in parts:
            norm, enough = _pair(coefficients, covariance, index)
            significant.append(enough)
            found.append(StructureMode(frequency, zeta, gain * norm))
            index += 4 if free else 2
        if all(significant) or not drop:
            if autocovariance is not None:
                rows = np.where(fitted[:, None], design, 0.0)
                covariance = coloured_covariance(rows, np.asarray(autocovariance, float)[: t.size])
            own = slice(base.shape[1], None)
            columns = design[:, own]
            values = columns @ coefficients[own]
            return Crosstalk(tuple(found), values, columns, coefficients[own], covariance[own, own])
        kept = [mode for mode, keep in zip(kept, significant, strict=True) if keep]
