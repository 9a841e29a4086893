"""A run at a record's edge: a level step or an impact's lobe, told apart by their fits
(issue 22).

:func:`dem_check.campaign.step_edges.edge_steps` reads a first-pass run from the record's
first sample, or to its last, as a DC offset step when one side of a split stays at one
level. Two records fooled a flatness test of that side:

- a weak impact at the first sample under strong 1/f noise: its lobe, a few sensor
  periods of a slow hump, spreads no more than the 1/f noise beside it, and read as a
  level that steps down at its end;
- a step a few samples before the last one: too few samples to read a spread on, listed
  as a ``negative`` candidate (the start of a lobe).

An impact's signal is not any shape: it is a contact's force through the sensor, whose
response is known (its resonance and damping: the force ``A h((t - t0) / tau)`` of a
contact family, :class:`contactlab.inverse.lobe_model.LobeModel`, as the onset fit
uses). A DC offset step is a level that changes within one sample and stays. So both
models are fitted to the window at the edge, each with a line for the drift, by
generalised least squares under the record's noise (an autoregressive model fitted on
the quiet samples beside the window, :func:`contactlab.inverse.noise_colour.fit_ar_noise`,
which holds the 1/f noise: its slow part weighs as little as it carries):

- **step**: the line and a unit step at sample ``s``, for every ``s`` within a sensor
  period of the split (exact: one column each);
- **lobe**: the line and a contact's signal from ``t0`` with duration ``tau``, for
  each family of :data:`EDGE_FAMILIES`, on a grid of ``t0`` (every
  :data:`SCAN_PERIODS` sensor period) and ``tau`` (:data:`DURATIONS`), the best point
  refined by Nelder-Mead. At the start the force may begin up to a contact's duration
  before the first sample; at the end it begins inside the window, only its rise seen.

Both chi-squared values are of the whitened residual (over the innovation's variance).
The model with the lower Akaike information criterion (``chi2 + 2 k``; ``k`` = 4 for
the step: the line, its height and place; 5 for the lobe: the line, ``A``, ``t0`` and
``tau``) is taken (:func:`judge_edge`): a level change within one sample is no
sensor's response, and a lobe's hump and ringing are no level. :func:`start_fit` and
:func:`end_fit` choose the window, the noise model's quiet samples and the lobe's onsets
at each edge.

References
----------
Akaike, H. (1974) A new look at the statistical model identification. IEEE Trans.
Autom. Control 19, 716-723.
"""

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from contactlab.errors import ParameterError
from contactlab.inverse.lobe_model import LobeModel
from contactlab.inverse.noise_colour import fit_ar_noise
from contactlab.inverse.pulse import difference_noise

__all__ = [
    "DURATIONS",
    "EDGE_FAMILIES",
    "QUIET_PERIODS",
    "SCAN_PERIODS",
    "EdgeFit",
    "edge_noise",
    "end_fit",
    "judge_edge",
    "start_fit",
    "start_window",
    "tail_fit",
    "window_samples",
]

EDGE_FAMILIES = (("linear", 0.0), ("linear", 0.25), ("linear", 0.5), ("hertz", 0.0))
"""Contact families and damping ratios [-] of the lobe model (those of
:data:`contactlab.inverse.lobe_model.FAMILIES`): undamped, moderately and strongly
damped linear contacts (whose force steps on at the touch) and an undamped Hertz
contact (whose force starts as ``s**1.5``)."""

DURATIONS = (0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.3, 16.0)
"""Contact durations ``tau`` of the lobe model's grid [sensor periods] (a factor
sqrt(2) apart, refined after): 12.5 us to 0.4 ms for a 40 kHz sensor."""

SCAN_PERIODS = 1.0 / 16.0
"""Step of the grid of onsets ``t0`` [sensor periods] (at least one sample)."""

QUIET_PERIODS = 16.0
"""Sensor periods of quiet record beside the window the noise model is fitted on [-]."""

STEP_PARAMETERS = 4
"""Free parameters of the step model [-]: offset, slope, height, place."""

LOBE_PARAMETERS = 5
"""Free parameters of the lobe model [-]: offset, slope, ``A``, ``t0``, ``tau``."""


@dataclass(frozen=True)
class EdgeFit:
    """The two models fitted to an edge window (module docstring)."""

    step: bool
    """Whether the step model is the better one (lower Akaike criterion)."""
    index: int
    """The step model's place: first sample at the new level (record index)."""
    height: float
    """The step model's height [N] (new level less old)."""
    significance: float
    """The step's height over its standard error under the noise model [-]."""
    step_chi2: float
    """Chi-squared of the step model [-]."""
    lobe_chi2: float
    """Chi-squared of the best lobe model [-]."""
    lobe: tuple
    """``(family, damping, t0 [s from the record's start], tau [s], A [N])`` of it."""
    samples: int
    """Samples fitted (after the whitening filter's first ones) [-]."""
    note: str = ""
    """What the row of a step found so says (:func:`end_fit`)."""

    def reason(self):
        """The comparison in words, for a candidate's row."""
        family, damping, t0, tau, amplitude = self.lobe
        return (
            f"a step fits the {self.samples} samples at the record's edge with chi-squared "
            f"{self.step_chi2:.4g}, a contact's force through the sensor ({family}, "
            f"damping {damping:.2g}, {amplitude:.3g} N from {t0:.4g} s over "
            f"{tau:.3g} s) with {self.lobe_chi2:.4g}"
        )


def edge_noise(values, quiet, period):
    """The noise model of a window's quiet neighbourhood.

    Parameters
    ----------
    values : numpy.ndarray
        Quiet record beside the window [N] (no impact, no step).
    quiet : int
        Fewest samples it must hold to fit an autoregressive model on.
    period : int
        The sensor's period [samples] (a line over the samples is taken off first).

    Returns
    -------
    ARNoise or float
        The autoregressive model (:func:`contactlab.inverse.noise_colour.fit_ar_noise`),
        or, with fewer than ``quiet`` samples, the white noise's standard deviation [N]
        on first differences of the record (:func:`contactlab.inverse.pulse.difference_noise`).
    """
    values = np.asarray(values, dtype=float)
    if values.size >= max(quiet, 2 * period):
        s = np.arange(values.size) - 0.5 * (values.size - 1)
        levelled = values - np.polyval(np.polyfit(s, values, 1), s)
        try:
            return fit_ar_noise(levelled)
        except ParameterError:  # constant samples
            pass
    return difference_noise(values) if values.size > 2 else math.nan


class _Projector:
    """Generalised least squares of a window on a line (and ``fixed`` columns) plus one
    more column."""

    def __init__(self, y, period, noise, fixed=None):
        n = y.size
        line = np.column_stack([np.ones(n), (np.arange(n) - 0.5 * (n - 1)) / period])
        if fixed is not None:
            line = np.column_stack([line, fixed])
        if isinstance(noise, float):
            self.whiten, scale = (lambda x: np.asarray(x, dtype=float)), noise
            self.order = 0
        else:
            self.whiten, scale = noise.whiten, noise.innovation
            self.order = noise.order
        if not scale > 0.0:
            raise ParameterError("the noise beside the record's edge is zero")
        self.scale = scale
        self.basis = np.linalg.qr(self.whiten(line))[0]
        y_w = self.whiten(y)
        self.y_off = y_w - self.basis @ (self.basis.T @ y_w)
        self.samples = int(y_w.size)

    def fit(self, columns):
        """Chi-squared [-], amplitude and its standard error of each column [N]."""
        return self.fit_white(self.whiten(columns))

    def fit_white(self, c_w):
        """:meth:`fit` of columns already whitened (``order`` rows fewer than ``y``)."""
        c_off = c_w - self.basis @ (self.basis.T @ c_w)
        norm = np.einsum("ij,ij->j", c_off, c_off)
        norm = np.where(norm > 0.0, norm, np.nan)
        amplitude = (c_off.T @ self.y_off) / norm
        rss = float(self.y_off @ self.y_off) - amplitude**2 * norm
        return np.maximum(rss, 0.0) / self.scale**2, amplitude, self.scale / np.sqrt(norm)


def _step_fit(projector, n, places):
    """Best step column among ``places`` (window indices): chi-squared, place, height
    and its standard error."""
    columns = (np.arange(n)[:, None] >= np.asarray(places)[None, :]).astype(float)
    chi2, height, error = projector.fit(columns)
    k = int(np.nanargmin(chi2))
    return float(chi2[k]), int(places[k]), float(height[k]), float(error[k])


class _Lobes:
    """The lobe model's columns on a window, force starting up to ``lead`` samples
    before it."""

    def __init__(self, n, lead, ring):
        self.sensor, self.dt = ring
        self.n, self.lead = n, lead
        t = self.dt * np.arange(-lead, n)
        self.models = {
            spec: LobeModel(t, np.zeros(t.size), self.sensor, *spec) for spec in EDGE_FAMILIES
        }
        self.signals = {}  # white_columns' signals, by family, duration and onsets

    def columns(self, spec, t0s, tau):
        """Unit-peak signals [-] on the window for onsets ``t0s`` [s from its first
        sample] and duration ``tau`` [s]."""
        model = self.models[spec]
        unit = model.unit(tau)
        return np.column_stack([model.response(t0, tau, unit)[self.lead :] for t0 in t0s])

    def white_columns(self, spec, starts, tau, projector):
        """:meth:`columns` for onsets at whole samples ``starts`` [samples from the
        window's first], whitened by ``projector``'s filter. A sample's signal depends
        only on its time since the onset and the filter is the same at every sample, so
        each whitened column is one whitened signal shifted: it is computed once, on
        every time since the onset the window sees (and kept for the next fits on the
        window), and sampled."""
        starts = np.asarray(starts, dtype=int)
        key = (spec, tau, int(starts.min()), int(starts.max()))
        if key not in self.signals:
            s, r = self.models[spec].unit(tau)
            lags = np.arange(-key[3], self.n - key[2])
            self.signals[key] = np.interp(self.dt * lags, s, r, left=0.0)
        white = projector.whiten(self.signals[key])
        rows = np.arange(self.n - projector.order)
        return white[rows[:, None] + (key[3] - starts)[None, :]]


def _lobe_fit(projector, lobes, starts, positive=False):
    """Best lobe: chi-squared and ``(family, damping, t0, tau, A)`` (``t0`` [s] from the
    window's first sample), on the grid of onsets ``starts`` [samples from the window's
    first] then refined; ``positive``: a compressive force's only (``A > 0``)."""
    period = lobes.sensor.period
    best = (math.inf, None)
    onsets = lobes.dt * np.asarray(starts, dtype=float)

    def fit(chi2, amplitude):
        return np.where(amplitude > 0.0, chi2, math.inf) if positive else chi2

    for spec in EDGE_FAMILIES:
        for tau in period * np.asarray(DURATIONS):
            kept = onsets > -tau
            t0s = onsets[kept]
            if not t0s.size:
                continue
            white = lobes.white_columns(spec, np.asarray(starts)[kept], tau, projector)
            chi2 = fit(*projector.fit_white(white)[:2])
            k = int(np.nanargmin(chi2)) if np.isfinite(chi2).any() else None
            if k is not None and chi2[k] < best[0]:
                best = (float(chi2[k]), (spec, float(t0s[k]), float(tau)))
    if best[1] is None:
        return math.inf, None
    spec, t0, tau = best[1]
    low, high = float(onsets.min()), float(onsets.max())

    def cost(x):
        t0, tau = x[0], x[1]
        if not (tau > 0.0 and low <= t0 <= high and t0 + tau > 0.0):
            return math.inf
        return float(fit(*projector.fit(lobes.columns(spec, [t0], tau))[:2])[0])

    simplex = np.array([[t0, tau], [t0 + lobes.dt, tau], [t0, 1.1 * tau]])
    solved = optimize.minimize(
        cost,
        [t0, tau],
        method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": 0.05 * lobes.dt, "fatol": 0.01},
    )
    if solved.fun < best[0]:
        t0, tau = float(solved.x[0]), float(solved.x[1])
    chi2, amplitude, _ = projector.fit(lobes.columns(spec, [t0], tau))
    return float(chi2[0]), (*spec, t0, tau, float(amplitude[0]))


def window_samples(values, window, ring):
    """A window's samples [N] and the sensor's period [samples]: ``(y, period)``.

    ``window`` is ``(first, stop)`` [samples], ``ring`` ``(sensor, dt)`` as in
    :func:`judge_edge`.
    """
    first, stop = window
    sensor, dt = ring
    return np.asarray(values[first:stop], dtype=float), max(1, round(sensor.period / dt))


def judge_edge(values, window, split, ring, noise, onsets):
    """The step model against the lobe model on a window at a record's edge.

    Parameters
    ----------
    values : numpy.ndarray
        The record [N].
    window : tuple
        ``(first, stop)`` sample indices of the window fitted.
    split : int
        Where a split between two levels placed the step (record index): the step
        model's place is sought within a sensor period of it.
    ring : tuple
        ``(sensor, dt)``: the :class:`~contactlab.bodies.Sensor` and the sampling
        interval [s].
    noise : ARNoise or float
        The noise model (:func:`edge_noise`).
    onsets : tuple
        ``(earliest, latest)`` onsets of the lobe model [samples from the window's first
        sample; the earliest may be negative: a force that began before the record].

    Returns
    -------
    EdgeFit
    """
    first, stop = window
    dt = ring[1]
    y, period = window_samples(values, window, ring)
    projector = _Projector(y, period, noise)
    places = np.arange(max(split - period, first + 1), min(split + period + 1, stop)) - first
    step_chi2, place, height, error = _step_fit(projector, y.size, places)
    step = max(1, round(SCAN_PERIODS * period))
    earliest, latest = onsets
    lobes = _Lobes(y.size, max(0, -earliest) + 2, ring)
    lobe_chi2, lobe = _lobe_fit(projector, lobes, np.arange(earliest, latest + 1, step))
    if lobe is not None:
        lobe = (*lobe[:2], lobe[2] + first * dt, *lobe[3:])
    else:
        lobe = ("none", 0.0, math.nan, math.nan, math.nan)
    better = step_chi2 + 2 * STEP_PARAMETERS < lobe_chi2 + 2 * LOBE_PARAMETERS
    return EdgeFit(
        step=bool(better),
        index=first + place,
        height=height,
        significance=abs(height) / error if error > 0.0 else math.inf,
        step_chi2=step_chi2,
        lobe_chi2=lobe_chi2,
        lobe=lobe,
        samples=projector.samples,
    )


def _quiet(values, lo, hi, runs, reach):
    """The record from ``lo`` to ``hi`` cut at the first-pass runs (with their quiet
    hold) that overlap it: the longest piece without one."""
    free = np.ones(max(hi - lo, 0), dtype=bool)
    for first, last in runs:
        a, b = max(first, lo), min(last + reach + 1, hi)
        if a < b:
            free[a - lo : b - lo] = False
    edges = np.flatnonzero(np.diff(np.r_[0, free.astype(int), 0]))
    if not edges.size:
        return values[lo:lo]
    starts, stops = edges[::2], edges[1::2]
    k = int(np.argmax(stops - starts))
    return values[lo + starts[k] : lo + stops[k]]


def _side_noise(values, quiet, fallback, runs, reach, period):
    """:func:`edge_noise` of the quiet record in ``quiet`` (``(lo, hi)`` indices, cut at
    the runs), or where there is none, of the samples in ``fallback`` (one level)."""
    noise = edge_noise(_quiet(values, *quiet, runs, reach), 2 * period, period)
    if isinstance(noise, float) and not noise > 0.0:
        noise = edge_noise(values[fallback[0] : fallback[1]], 2 * period, period)
    return noise


def start_fit(values, index, runs, reach, ring):
    """:func:`judge_edge` for a step found ``index`` samples after the record's start.

    The window reaches as far past the step as it lies from the start (at least
    four sensor periods, up to the next run); the noise model is fitted on the quiet
    record after the run from the start (:data:`QUIET_PERIODS`); the lobe may begin up to
    its longest duration before the first sample and up to half a sensor period after it
    (a lobe that begins later leaves the first samples at the level: the run would not
    start there; let begin later, it reads a step as the rise of a negative lobe).

    Parameters
    ----------
    values : numpy.ndarray
        The record [N].
    index : int
        First sample at the new level.
    runs : list of tuple
        ``(first, last)`` of the first pass's runs.
    reach : int
        Samples past a run's last one that still belong to it.
    ring : tuple
        ``(sensor, dt)``.

    Returns
    -------
    EdgeFit
    """
    window, noise, onsets = start_window(values, index, runs, reach, ring)
    return judge_edge(values, window, index, ring, noise, onsets)


def start_window(values, index, runs, reach, ring):
    """The window, noise model and lobe onsets of :func:`start_fit` (its docstring):
    ``(0, stop)`` sample indices, the ARNoise (or float), and ``(earliest, latest)``
    [samples from the first sample]."""
    period = max(1, round(ring[0].period / ring[1]))
    n = len(values)
    later = [first for first, _ in runs if first > index]
    stop = min(n, index + max(index, 4 * period), *later)
    own = [last for first, last in runs if first <= index] or [index]
    lo = max(own) + reach
    quiet = (lo, lo + round(QUIET_PERIODS * period))
    noise = _side_noise(values, quiet, (index, stop), runs, reach, period)
    longest = round(DURATIONS[-1] * period)
    return (0, stop), noise, (-longest, min(index - 1, period // 2))


def end_fit(values, at, first, runs, reach, ring):
    """:func:`judge_edge` for a step in the last sensor period of a run from ``first``
    to the record's last sample: too few samples for a spread, and for the tail's
    median a split (at ``at``) reads the new level on, so the step is sought there.

    The window holds the run and four sensor periods before it (at least twice the
    samples after the step); the noise model is fitted on the quiet record before it;
    the lobe begins between a period before the run and the last sample.

    Returns
    -------
    EdgeFit
        Its ``step`` only for a step placed within the last period, with its ``note``.
    """
    period = max(1, round(ring[0].period / ring[1]))
    n = len(values)
    index = at if 2 <= n - at < period else n - max(1, period // 2)
    lo = max(0, min(first, n - 2 * (n - index)) - 4 * period)
    quiet = (max(0, lo - round(QUIET_PERIODS * period)), lo)
    noise = _side_noise(values, quiet, (lo, index), runs, reach, period)
    earliest = max(0, first - lo - period)
    fit = judge_edge(values, (lo, n), index, ring, noise, (earliest, n - 1 - lo))
    note = (
        f"; in the record's last {n - fit.index} samples, fewer than a sensor period: "
        f"{fit.reason()}: a lobe's start follows the sensor's response, a level change "
        "within one sample does not"
    )
    return dataclasses.replace(fit, step=fit.step and n - fit.index < period, note=note)


def tail_fit(values, index, first, runs, reach, ring):
    """:func:`judge_edge` for a step the period means placed at ``index``, in a run from
    ``first`` to the record's last sample: an impact cut by the record's end moves the
    period means' shortened windows there as a step does (a 1 m/s impact 30-150 us
    before the end read as one to four steps, white noise alone). The window holds the
    run and four sensor periods before it, the noise model is fitted on the quiet record
    before that, and the lobe begins between a period before the run and the last
    sample (as :func:`end_fit`'s)."""
    period = max(1, round(ring[0].period / ring[1]))
    n = len(values)
    lo = max(0, min(first, index) - 4 * period)
    quiet = (max(0, lo - round(QUIET_PERIODS * period)), lo)
    noise = _side_noise(values, quiet, (lo, index), runs, reach, period)
    earliest = max(0, first - lo - period)
    return judge_edge(values, (lo, n), index, ring, noise, (earliest, n - 1 - lo))
