"""Compare two impacts number by number: engine vs model, or a measured trace vs a model.

:func:`compare` takes any two of

* a simulated result (:class:`contactlab.ImpactResult`, :class:`dem_check.bullet.EngineResult`),
  which has contact force, sensor signal and grain velocities;
* a measured :class:`~dem_check.traces.Trace` in newtons, which is a sensor signal only:
  the quantities it lacks (contact time, peak contact force, restitution) are reported as
  not available, never as failed;

and returns a :class:`Comparison`: a table of quantities with both values, their errors,
the tolerance and whether it holds.

Quantities and default tolerances
---------------------------------
=======================  ======  ==========================  ===========================
quantity                 unit    error measured as           default tolerance
=======================  ======  ==========================  ===========================
contact_time             s       relative, ``(a - b) / b``   0.005
peak_contact_force       N       relative                    0.01
peak_sensor_force        N       relative                    0.01
sensor_response_time     s       relative                    0.01
restitution              -       absolute, ``a - b``         0.01
waveform_rms_error       N       relative to b's S1 peak     0.02
waveform_max_error       N       relative to b's S1 peak     0.05
=======================  ======  ==========================  ===========================

``b`` is the reference (the model). The tolerances are sized for the engine bench at its
default step (errors of 0.1-0.3 %, restitution low by ``~k2 dt`` / 3; see
``docs/dem_check.md``); a measured trace with noise needs looser ones, passed by name.

Waveforms
---------
The sensor signals S1 are compared after a time alignment (``align``): ``"onset"`` makes
the first crossings of :data:`ONSET_LEVEL` times each signal's peak coincide (the same
reading for a noise-free simulation and a noisy trace), ``"xcorr"`` maximises their
cross-correlation (parabolic refinement of the best lag), ``None`` keeps the time axes.
Both signals are then interpolated linearly onto a common uniform grid spanning the
window both cover, with the finer of their two sample intervals, and the RMS and largest
differences are taken there.
"""

import difflib
import math
from dataclasses import dataclass

import numpy as np

from contactlab import metrics
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError
from contactlab.validation import check_choice, check_number
from dem_check.traces.prepare import noise_level, remove_baseline
from dem_check.traces.trace import Trace

__all__ = [
    "ALIGNMENTS",
    "DEFAULT_TOLERANCES",
    "ONSET_LEVEL",
    "QUANTITIES",
    "Comparison",
    "Quantity",
    "compare",
    "compare_trace",
    "noise_tolerances",
]

ALIGNMENTS = ("onset", "xcorr", None)
"""Accepted values of ``align``."""

ONSET_LEVEL = 0.1
"""Fraction of a signal's peak whose first crossing is its onset for ``align="onset"``:
high enough to clear measurement noise, low enough to sit on the steep first rise."""


@dataclass(frozen=True)
class Quantity:
    """One compared quantity.

    Attributes
    ----------
    unit : str
        SI unit of the values and of ``abs_error``.
    basis : {"relative", "absolute", "peak"}
        What the tolerance bounds: ``|a - b| / |b|``, ``|a - b|``, or an error over the
        peak of b's sensor signal.
    tolerance : float
        Default tolerance.
    reason : str
        Why the default has that size.
    """

    unit: str
    basis: str
    tolerance: float
    reason: str


QUANTITIES = {
    "contact_time": Quantity(
        "s", "relative", 0.005, "engine at 500 steps per contact: 0.1-0.2 %; measured: n/a"
    ),
    "peak_contact_force": Quantity(
        "N", "relative", 0.01, "engine at its default step: 0.1-0.3 % (first-order in dt)"
    ),
    "peak_sensor_force": Quantity(
        "N", "relative", 0.01, "engine at its default step: 0.1-0.2 % (first-order in dt)"
    ),
    "sensor_response_time": Quantity(
        "s", "relative", 0.01, "the lobe's ends are read on the step grid: ~0.2 %"
    ),
    "restitution": Quantity(
        "-", "absolute", 0.01, "implicit contact damping k2 dt lowers it by ~0.003 at 1e-7 s"
    ),
    "waveform_rms_error": Quantity(
        "N", "peak", 0.02, "peak and phase errors of 0.1-0.3 % give an RMS error ~0.5 %"
    ),
    "waveform_max_error": Quantity(
        "N", "peak", 0.05, "the largest difference sits on the steepest slope: ~1 %"
    ),
}
"""The compared quantities, in table order."""

DEFAULT_TOLERANCES = {name: q.tolerance for name, q in QUANTITIES.items()}
"""Default tolerance of each quantity (see :data:`QUANTITIES` for the basis)."""

_SCALARS = (
    "contact_time",
    "peak_contact_force",
    "peak_sensor_force",
    "sensor_response_time",
    "restitution",
)
_SENSOR_SCALARS = {"peak_sensor_force": "peak", "sensor_response_time": "duration"}
_COLUMNS = (
    "quantity",
    "unit",
    "a",
    "b",
    "abs_error",
    "rel_error",
    "tolerance",
    "basis",
    "passed",
    "note",
)


def _tolerances(tolerances):
    """Defaults updated with ``tolerances``; unknown names raise listing the valid ones."""
    if tolerances is not None and not isinstance(tolerances, dict):
        raise ParameterError(
            f"tolerances must be a dict of quantity name -> tolerance; got {tolerances!r}"
        )
    merged = dict(DEFAULT_TOLERANCES)
    for name, value in (tolerances or {}).items():
        if name not in merged:
            near = difflib.get_close_matches(str(name), merged, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise ParameterError(
                f"unknown tolerance {name!r}{hint}; valid names: {', '.join(merged)}"
            )
        merged[name] = check_number(f"tolerance {name}", value, low=0.0, low_open=False)
    return merged


def _signal(obj, label):
    """``(t, S1)`` of a result or a trace (which must be in newtons)."""
    if isinstance(obj, Trace):
        if obj.unit != "N":
            raise ParameterError(
                f"{label}: the trace is in {obj.unit!r}; compare needs newtons: read it with "
                "sensitivity=<V/N> (or dem_check.traces.to_force)"
            )
        return obj.t, obj.values
    if not all(hasattr(obj, name) for name in ("t", "sensor_force")):
        raise ParameterError(
            f"{label}: expected a simulated result or a Trace; got {type(obj).__name__}"
        )
    return obj.t, obj.sensor_force


def _scalar(obj, name, threshold, hysteresis):
    """Value of a scalar quantity, or None when the object does not have it."""
    if name not in _SENSOR_SCALARS:
        return getattr(obj, name, None)  # a trace has no contact force or grain velocity
    if isinstance(obj, Trace):
        pulse = obj.metrics(threshold or 0.0, hysteresis)
    elif threshold is not None:
        pulse = metrics.pulse_metrics(obj.t, obj.sensor_force, threshold, hysteresis=hysteresis)
    else:
        return getattr(obj, name)
    return getattr(pulse, _SENSOR_SCALARS[name])


def _onset(t, y):
    peak = float(np.max(y))
    if not peak > 0.0:
        raise ParameterError("align='onset' needs a signal with a positive peak")
    return metrics.first_lobe(t, y, ONSET_LEVEL * peak)[0]


def _uniform(t, y, step):
    grid = np.arange(t[0], t[-1] + 0.5 * step, step)
    grid = grid[grid <= t[-1]]
    return grid, np.interp(grid, t, y)


def _xcorr_shift(sig_a, sig_b, step):
    """Shift [s] added to a's times that maximises the cross-correlation with b."""
    from scipy import signal

    ta, ya = _uniform(*sig_a, step)
    tb, yb = _uniform(*sig_b, step)
    corr = signal.correlate(yb, ya, mode="full", method="fft")
    lags = signal.correlation_lags(yb.size, ya.size, mode="full")
    k = int(np.argmax(corr))
    offset = 0.0
    if 0 < k < corr.size - 1:  # vertex of the parabola through the best lag and neighbours
        left, mid, right = corr[k - 1], corr[k], corr[k + 1]
        curvature = left - 2.0 * mid + right
        if curvature < 0.0:
            offset = 0.5 * (left - right) / curvature
    return tb[0] - ta[0] + (lags[k] + offset) * step


def _step(t):
    return float(np.median(np.diff(t)))


def _shift(sig_a, sig_b, align):
    if align is None:
        return 0.0
    if align == "onset":
        return _onset(*sig_b) - _onset(*sig_a)
    return _xcorr_shift(sig_a, sig_b, min(_step(sig_a[0]), _step(sig_b[0])))


def _waveform_errors(sig_a, sig_b, shift):
    """RMS and largest difference of the two signals on their common window [N]."""
    ta, ya = sig_a[0] + shift, sig_a[1]
    tb, yb = sig_b
    lo, hi = max(ta[0], tb[0]), min(ta[-1], tb[-1])
    if hi <= lo:
        raise ParameterError(
            f"after alignment the signals do not overlap in time (a: {ta[0]:.4g}..{ta[-1]:.4g}"
            f" s, b: {tb[0]:.4g}..{tb[-1]:.4g} s)"
        )
    step = min(_step(ta), _step(tb))
    grid = np.linspace(lo, hi, max(2, math.floor((hi - lo) / step) + 1))
    diff = np.interp(grid, ta, ya) - np.interp(grid, tb, yb)
    return float(np.sqrt(np.mean(diff**2))), float(np.max(np.abs(diff))), (lo, hi)


def _row(name, a, b, tolerance, note=""):
    """One table row; ``a`` or ``b`` None means not available."""
    quantity = QUANTITIES[name]
    row = dict.fromkeys(_COLUMNS)
    row.update(quantity=name, unit=quantity.unit, tolerance=tolerance, basis=quantity.basis)
    row["note"] = note
    if a is None or b is None:
        row.update(a=None if a is None else float(a), b=None if b is None else float(b))
        return row
    a, b = row["a"], row["b"] = float(a), float(b)
    if math.isnan(a) and math.isnan(b):
        row["note"] = "not available: nan on both sides"
        return row
    error = a - b
    row["abs_error"] = abs(error)
    row["rel_error"] = error / abs(b) if b else math.nan
    measured = row["abs_error"] if quantity.basis == "absolute" else abs(row["rel_error"])
    row["passed"] = bool(measured <= tolerance)  # nan on one side fails
    return row


def _waveform_row(name, error, scale, tolerance, note):
    row = _row(name, None, None, tolerance, note)
    row["abs_error"] = error
    row["rel_error"] = error / scale if scale > 0.0 else math.nan
    row["passed"] = bool(row["rel_error"] <= tolerance)
    return row


def _label(obj):
    if isinstance(obj, Trace):
        return "trace"
    return str(getattr(obj, "method", type(obj).__name__))


def compare(a, b, tolerances=None, align="onset", threshold=None, labels=None, hysteresis=0.0):
    """Compare two impacts quantity by quantity.

    Parameters
    ----------
    a : ImpactResult, EngineResult or Trace
        The impact under test (engine run, measurement).
    b : ImpactResult, EngineResult or Trace
        The reference (usually :func:`contactlab.simulate_impact`); relative errors are
        ``(a - b) / |b|``.
    tolerances : dict, optional
        Tolerances by quantity name, replacing :data:`DEFAULT_TOLERANCES` (same basis);
        unknown names raise ParameterError listing the valid ones.
    align : {"onset", "xcorr", None}, default "onset"
        Time alignment of the sensor signals before the waveform errors (see the module
        docstring). Durations and peaks do not depend on it.
    threshold : float, optional
        Read both sensor signals' first lobes with :func:`contactlab.metrics.pulse_metrics`
        at this level [N] (e.g. a few times a trace's noise). Default: each result's own
        reading (exact for :class:`~contactlab.ImpactResult`), and 0 for a trace.
    labels : (str, str), optional
        Names of a and b in the table and plot; default from their types.
    hysteresis : float, default 0
        With ``threshold``: how far below it a signal must fall to end its lobe [N] (see
        :func:`contactlab.metrics.first_lobe`).

    Returns
    -------
    Comparison

    Examples
    --------
    >>> import contactlab as cl
    >>> law = cl.laws.LinearViscoelastic(1e5, 1.0)
    >>> grain = cl.Grain(diameter=5e-3, density=765.0)
    >>> res = cl.simulate_impact(grain, cl.Sensor.rigid(), law, 2.0)
    >>> compare(res, res).passed
    True
    """
    tolerances = _tolerances(tolerances)
    align = check_choice("align", align, ALIGNMENTS)
    if threshold is not None:
        threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    hysteresis = check_number("hysteresis", hysteresis, low=0.0, low_open=False, unit="N")
    labels = tuple(labels) if labels is not None else (_label(a), _label(b))
    if len(labels) != 2:
        raise ParameterError(f"labels must be two names; got {labels!r}")
    sig_a, sig_b = _signal(a, labels[0]), _signal(b, labels[1])
    rows = []
    for name in _SCALARS:
        va = _scalar(a, name, threshold, hysteresis)
        vb = _scalar(b, name, threshold, hysteresis)
        missing = [lab for lab, v in zip(labels, (va, vb), strict=True) if v is None]
        note = f"not available: {' and '.join(missing)} has no {name}" if missing else ""
        rows.append(_row(name, va, vb, tolerances[name], note))
    shift = _shift(sig_a, sig_b, align)
    rms, largest, window = _waveform_errors(sig_a, sig_b, shift)
    scale = float(np.max(np.abs(sig_b[1])))
    note = f"sensor signal, over b's peak {scale:.4g} N"
    rows.append(
        _waveform_row("waveform_rms_error", rms, scale, tolerances["waveform_rms_error"], note)
    )
    rows.append(
        _waveform_row("waveform_max_error", largest, scale, tolerances["waveform_max_error"], note)
    )
    return Comparison(rows, a, b, labels, align, shift, window, threshold)


class Comparison:
    """The outcome of :func:`compare`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per quantity: ``quantity``, ``unit``, ``a``, ``b``, ``abs_error`` (in
        ``unit``), ``rel_error`` (signed ``(a - b) / |b|``; over b's peak for waveforms),
        ``tolerance``, ``basis`` (what the tolerance bounds), ``passed`` (True, False, or
        None when not available) and ``note``.
    a, b
        The compared objects; ``labels`` their names.
    align : str or None
        The alignment used; ``shift`` [s] was added to a's times.
    window : (float, float)
        Common time window of the waveform errors, in b's time [s].
    notes : dict
        Context added by the caller (engine settings, baseline removal), shown and saved.
    """

    def __init__(self, rows, a, b, labels, align, shift, window, threshold):
        import pandas as pd

        self.table = pd.DataFrame(rows, columns=list(_COLUMNS))
        self.a, self.b = a, b
        self.labels = labels
        self.align, self.shift, self.window = align, float(shift), window
        self.threshold = threshold
        self.notes = {}

    @property
    def passed(self):
        """Whether every available quantity is within its tolerance."""
        verdicts = [p for p in self.table["passed"] if p is not None]
        return bool(verdicts) and all(verdicts)

    @property
    def failed(self):
        """Names of the quantities outside their tolerance."""
        return [row.quantity for row in self.table.itertuples() if row.passed is False]

    def to_dict(self):
        """The comparison as JSON-ready data (``nan`` -> None)."""

        def clean(value):
            if isinstance(value, float | np.floating):
                return None if math.isnan(value) else float(value)
            if isinstance(value, np.bool_):
                return bool(value)
            return value

        records = [
            {k: clean(v) for k, v in row.items()}
            for row in self.table.astype(object).to_dict(orient="records")
        ]
        return {
            "a": self.labels[0],
            "b": self.labels[1],
            "passed": self.passed,
            "align": self.align,
            "shift [s]": self.shift,
            "window [s]": list(self.window),
            "threshold [N]": self.threshold,
            "notes": {k: clean(v) for k, v in self.notes.items()},
            "quantities": records,
        }

    def __str__(self):
        def fmt(value):
            if value is None or (isinstance(value, float) and math.isnan(value)):
                return "n/a"
            if isinstance(value, bool):
                return "yes" if value else "NO"
            if isinstance(value, float):
                return f"{value:.6g}"
            return str(value)

        header = [
            "quantity",
            "unit",
            self.labels[0],
            self.labels[1],
            "abs_error",
            "rel_error",
            "tolerance",
            "passed",
        ]
        keys = ["quantity", "unit", "a", "b", "abs_error", "rel_error", "tolerance", "passed"]
        body = [[fmt(row[k]) for k in keys] for row in self.table.astype(object).to_dict("records")]
        widths = [max(len(r[i]) for r in [header, *body]) for i in range(len(header))]
        lines = [
            f"{self.labels[0]} vs {self.labels[1]}: "
            f"{'PASSED' if self.passed else 'FAILED ' + ', '.join(self.failed)}"
        ]
        lines.append(
            f"align = {self.align} (shift {self.shift:.6g} s), tolerances: relative "
            "except restitution (absolute) and waveforms (over b's peak S1)"
        )
        lines += [
            f"{k}: {v:.6g}" if isinstance(v, float) else f"{k}: {v}" for k, v in self.notes.items()
        ]
        lines.append("  ".join(h.ljust(w) for h, w in zip(header, widths, strict=True)))
        lines += ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) for r in body]
        return "\n".join(lines)

    def __repr__(self):
        verdict = "passed" if self.passed else f"failed={self.failed}"
        return f"Comparison({self.labels[0]!r} vs {self.labels[1]!r}, {verdict})"

    def plot(self, ax=None, title=None):
        """Overlay of both sensor signals S1 (and contact forces S2 where known), aligned.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw into; a new figure when None.
        title : str, optional

        Returns
        -------
        (matplotlib.figure.Figure, matplotlib.axes.Axes)
        """
        from contactlab.plotting import axes_or_new

        fig, ax = axes_or_new(ax)
        styles = (("tab:red", self.shift), ("black", 0.0))
        for obj, label, (color, shift) in zip((self.a, self.b), self.labels, styles, strict=True):
            t, y = _signal(obj, label)
            ax.plot((t + shift) * 1e6, y, lw=1.2, color=color, label=f"{label}: $S_1$")
            force = getattr(obj, "contact_force", None)
            if force is not None:
                ax.plot(
                    (t + shift) * 1e6, force, lw=1.0, ls="--", color=color, label=f"{label}: $S_2$"
                )
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.axvspan(self.window[0] * 1e6, self.window[1] * 1e6, color="0.95", zorder=0)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("force [N]")
        ax.set_title(title or str(self).splitlines()[0])
        ax.legend(loc="upper right", frameon=False)
        return fig, ax


def noise_tolerances(noise, peak):
    """Default tolerances widened for a measured signal with baseline noise.

    The largest sample near a noisy peak overshoots the true peak by about two to three
    standard deviations, and the largest of thousands of noisy differences reaches four
    to five; the RMS difference contains the noise itself. So, on the bases of
    :data:`QUANTITIES`: ``peak_sensor_force`` gets ``+ 4 noise / peak``,
    ``waveform_max_error`` ``+ 5 noise / peak`` and ``waveform_rms_error``
    ``+ 2 noise / peak``; the others keep their defaults.

    Parameters
    ----------
    noise : float
        Standard deviation of the trace's baseline [N].
    peak : float
        Peak of the reference sensor signal [N], > 0.

    Returns
    -------
    dict
        Tolerance by quantity name.
    """
    noise = check_number("noise", noise, low=0.0, low_open=False, unit="N")
    peak = check_number("peak", peak, low=0.0, unit="N")
    widen = {"peak_sensor_force": 4.0, "waveform_max_error": 5.0, "waveform_rms_error": 2.0}
    return {
        name: tolerance + widen.get(name, 0.0) * noise / peak
        for name, tolerance in DEFAULT_TOLERANCES.items()
    }


def compare_trace(trace, config, tolerances=None, align="onset", k=5.0, threshold=None):
    """Compare a measured sensor trace with the model of an impact set-up.

    The trace's baseline (its samples before the trigger) is removed when it has one, and
    both sensor signals are then read at ``k`` times the trace's noise, so the
    measurement and the model are read alike. A lobe ends at its last crossing of that
    level before the signal is back at the baseline (hysteresis equal to the threshold),
    so noise on a slow rise or fall cannot cut it short. Without a baseline the trace is
    used as is and read at 0 N; :attr:`Comparison.notes` says which was done.

    Parameters
    ----------
    trace : Trace
        The measured sensor signal in newtons (read it with ``sensitivity=``).
    config : contactlab.config.ImpactConfig
        The impact set-up (:func:`contactlab.config.load_config`); simulated with its
        ``[simulation]`` settings.
    tolerances : dict, optional
        See :func:`compare`; by default the engine tolerances widened by the trace's
        noise (:func:`noise_tolerances`), and any given here replace those.
    align : {"onset", "xcorr", None}, default "onset"
    k : float, default 5
        Lobe threshold in units of the baseline noise [-].
    threshold : float, optional
        Lobe threshold [N] instead of ``k`` times the noise.

    Returns
    -------
    Comparison
        ``a`` is the measurement (after baseline removal), ``b`` the model.
    """
    _signal(trace, "measured")
    if not isinstance(config, ImpactConfig):
        raise ParameterError(
            "config must be a contactlab.config.ImpactConfig (from load_config or "
            f"load_preset); got {type(config).__name__}"
        )
    k = check_number("k", k, low=0.0, low_open=False)
    trigger = trace.metadata.get("trigger_time")
    trigger = 0.0 if trigger is None else trigger
    before = int(np.count_nonzero(trace.t < trigger))
    if before >= 2:
        trace = remove_baseline(trace)
        baseline = f"removed: mean of the {before} samples before {trigger:.6g} s"
        noise = noise_level(trace)
    else:
        baseline = "kept: no samples before the trigger"
        noise = 0.0
    if threshold is None:
        threshold = k * noise
    model = config.simulate()
    tolerances = {**noise_tolerances(noise, model.peak_sensor_force), **(tolerances or {})}
    result = compare(
        trace, model, tolerances, align, threshold, ("measured", "model"), hysteresis=threshold
    )
    result.notes.update({"baseline": baseline, "lobe threshold [N]": threshold})
    return result
