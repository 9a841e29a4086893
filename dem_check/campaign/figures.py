"""The report's figures as inline SVG text (matplotlib, no pyplot state, text as paths).

Every figure is drawn on its own ``matplotlib.figure.Figure`` and returned as an
``<svg>`` element ready to paste into HTML: glyphs are drawn as paths
(``svg.fonttype = "path"``), so the report needs no font, and each figure gets its own
id salt so that ids never collide between the figures of one page.
"""

import io
import itertools
import re

import numpy as np

from dem_check.campaign.detection import ANALYSED

__all__ = [
    "MAX_POINTS",
    "distributions_svg",
    "gallery_svg",
    "record_svg",
    "regressions_svg",
]

MAX_POINTS = 1500
"""Largest number of points drawn per line in the gallery (every k-th sample); the
tables and CSV files hold the full-resolution numbers."""

DISTRIBUTIONS = (
    ("peak_contact_force [N]", "reconstructed peak force [N]"),
    ("contact_time [s]", "reconstructed contact time [us]"),
    ("peak_sensor_force [N]", "peak sensor signal [N]"),
    ("impulse [N*s]", "impulse [mN*s]"),
)
"""Histogram panels: column and axis label (times in us, impulses in mN*s)."""

_SCALE = {"[s]": 1e6, "[N*s]": 1e3}
_salt = itertools.count()


def _scale(column):
    """Display factor of a column (us for seconds, mN*s for impulses)."""
    return next((f for unit, f in _SCALE.items() if column.endswith(unit)), 1.0)


def _figure(width, height):
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def _svg(fig):
    """The figure as an ``<svg>`` element string (no XML prolog, no date), every id in it
    prefixed with the figure's number: matplotlib names groups and glyphs alike in every
    figure (``xtick_1``, ``DejaVuSans-30``), and ids must be unique in one page."""
    import matplotlib

    number = next(_salt)
    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.fonttype": "path", "svg.hashsalt": f"f{number}"}):
        fig.savefig(buffer, format="svg", metadata={"Date": None})
    text = buffer.getvalue()
    text = text[text.index("<svg") :]
    ids = set(re.findall(r'\bid="([^"]+)"', text))
    prefix = f"fig{number}-"

    def renamed(match):
        name = match.group(2)
        return f"{match.group(1)}{prefix}{name}" if name in ids else match.group(0)

    # definitions (id="x") and references (href="#x", url(#x))
    return re.sub(r'(\bid="|href="#|url\(#)([^")]+)', renamed, text)


def record_svg(envelope, onsets, statuses, name):
    """A whole record as its min/max envelope, with the impacts marked by status.

    Parameters
    ----------
    envelope : (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        Bin times [s], bin minima and maxima [N].
    onsets, statuses : sequence
        Onset [s] and status of each impact found.
    name : str
        Title.
    """
    t, low, high = envelope
    fig = _figure(9.0, 2.0)
    ax = fig.add_subplot()
    ax.fill_between(t, low, high, color="0.35", linewidth=0.5, step="mid")
    for onset, status in zip(onsets, statuses, strict=True):
        ax.axvline(onset, color="tab:green" if status in ANALYSED else "tab:red", lw=0.8, alpha=0.7)
    ax.set(xlabel="t [s]", ylabel="signal [N]", title=name)
    return _svg(fig)


def distributions_svg(ok):
    """Histograms of the headline numbers of the ok impacts, stacked by file."""
    panels = [(c, label) for c, label in DISTRIBUTIONS if c in ok.columns]
    fig = _figure(9.0, 2.2 * ((len(panels) + 1) // 2))
    files = list(dict.fromkeys(ok["file"]))
    for k, (column, label) in enumerate(panels):
        ax = fig.add_subplot((len(panels) + 1) // 2, 2, k + 1)
        groups = [ok.loc[ok["file"] == f, column].dropna() * _scale(column) for f in files]
        values = np.concatenate([g.to_numpy() for g in groups]) if groups else np.array([])
        if values.size:
            bins = np.histogram_bin_edges(values, bins=min(30, max(5, values.size // 2)))
            ax.hist([g.to_numpy() for g in groups], bins=bins, stacked=True, label=files)
        ax.set(xlabel=label, ylabel="impacts")
    drawn = [ax for ax in fig.axes if ax.get_legend_handles_labels()[0]]
    if drawn and len(files) <= 10:
        drawn[0].legend(fontsize="x-small")
    return _svg(fig)


def regressions_svg(joined, lines):
    """Scatter of each regressed response against its predictor, with the fitted line."""
    fitted = lines[lines["note"] == ""]
    ok = joined[joined["status"] == "ok"]
    fig = _figure(9.0, 2.6 * ((len(fitted) + 1) // 2))
    for k, (_, line) in enumerate(fitted.iterrows()):
        ax = fig.add_subplot((len(fitted) + 1) // 2, 2, k + 1)
        x = ok[line["predictor"]].to_numpy(dtype=float)
        scale = _scale(line["response"])
        ax.plot(x, ok[line["response"]].to_numpy(dtype=float) * scale, "o", ms=3)
        span = np.array([np.nanmin(x), np.nanmax(x)])
        ax.plot(span, (line["intercept"] + line["slope"] * span) * scale, "-")
        name = line["response"].split(" [")[0]
        ax.set(
            xlabel=line["predictor"],
            ylabel=f"{name} [us]" if scale == 1e6 else line["response"],
            title=f"r = {line['r']:.3f}, p = {line['p_value']:.2g}",
        )
    return _svg(fig)


def gallery_svg(traces, onset, title):
    """One impact: the signal and the reconstructed force against time from onset [us]."""
    step = max(1, traces.t.size // MAX_POINTS)
    us = (traces.t[::step] - onset) * 1e6
    fig = _figure(4.2, 2.4)
    ax = fig.add_subplot()
    ax.plot(us, traces.signal[::step], color="0.55", lw=0.8, label="sensor signal")
    ax.plot(us, traces.force[::step], color="tab:blue", lw=1.2, label="reconstructed force")
    ax.set(xlabel="t - onset [us]", ylabel="force [N]", title=title)
    ax.title.set_fontsize("small")
    ax.legend(fontsize="x-small")
    return _svg(fig)
