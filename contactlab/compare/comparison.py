"""The outcome of a comparison: a table of quantities, a verdict, a printout and a plot."""

import math

import numpy as np

from contactlab.compare.quantities import QUANTITIES
from contactlab.compare.waveform import sensor_signal

__all__ = ["COLUMNS", "Comparison", "quantity_row", "waveform_row"]

COLUMNS = (
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


def quantity_row(name, a, b, tolerance, note=""):
    """One table row; ``a`` or ``b`` None means not available."""
    quantity = QUANTITIES[name]
    row = dict.fromkeys(COLUMNS)
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


def waveform_row(name, error, scale, tolerance, note):
    """The table row of a waveform error [N], judged over the reference peak ``scale`` [N]."""
    row = quantity_row(name, None, None, tolerance, note)
    row["abs_error"] = error
    row["rel_error"] = error / scale if scale > 0.0 else math.nan
    row["passed"] = bool(row["rel_error"] <= tolerance)
    return row


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
    physics : list of str
        What in a measured impact its grain cannot produce
        (:func:`contactlab.compare.physics.physics_problems`; set by
        :func:`contactlab.compare.compare_trace`); any entry fails the comparison.
    """

    def __init__(self, rows, a, b, labels, align, shift, window, threshold):
        import pandas as pd

        self.table = pd.DataFrame(rows, columns=list(COLUMNS))
        self.a, self.b = a, b
        self.labels = labels
        self.align, self.shift, self.window = align, float(shift), window
        self.threshold = threshold
        self.notes = {}
        self.physics = []

    @property
    def passed(self):
        """Whether every available quantity is within its tolerance and the measured
        impact is physically possible (:attr:`physics` empty)."""
        verdicts = [p for p in self.table["passed"] if p is not None]
        return bool(verdicts) and all(verdicts) and not self.physics

    @property
    def failed(self):
        """Names of the quantities outside their tolerance (``physics``: see
        :attr:`physics`)."""
        failed = [row.quantity for row in self.table.itertuples() if row.passed is False]
        return failed + (["physics"] if self.physics else [])

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
            "physics": list(self.physics),
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
        lines += [f"physics: {problem}" for problem in self.physics]
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
            t, y = sensor_signal(obj, label)
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
