"""A stream's figures and its self-contained HTML report.

Figures (PNG files, and inline SVG in the page): the sensor signal over the true contact
force with each impact's touch marked (each kind in its colour, the detector's
onsets as ticks); the pile-up curve (fractions hit, merged and missed against the flow
rate); the calibration curve (flow against plate output, with the test points). The
page has no script and no remote resource: it opens from disk and can be mailed.
"""

import html
import io
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

__all__ = ["calibration_figure", "pileup_figure", "signal_figure", "write_report"]

_STYLE = (
    "body{font-family:sans-serif;margin:1.5em auto;max-width:70em;color:#222}"
    "table{border-collapse:collapse;font-size:.85em;margin:.5em 0 1.5em}"
    "th,td{border:1px solid #bbb;padding:.2em .5em;text-align:right}th{background:#eee}"
    "svg{max-width:100%;height:auto}"
)


def signal_figure(result, scored=None, window=None):
    """Signal S1 and the true contact force [N] against time, impacts marked.

    ``window`` is ``(start, stop)`` [s]; default the first 10 ms after the lead time.
    """
    steps = result.steps
    start, stop = window or (result.lead, result.lead + 10e-3)
    part = steps[(steps["t [s]"] >= start) & (steps["t [s]"] <= stop)]
    fig, ax = plt.subplots(figsize=(9, 3.6))
    ms = 1e3 * part["t [s]"]
    ax.plot(ms, part["contact_force [N]"], color="0.6", lw=0.8, label="true contact force")
    ax.plot(ms, part["sensor_force [N]"], color="C0", lw=0.8, label="sensor signal S1")
    truth = result.truth[(result.truth["touch [s]"] >= start) & (result.truth["touch [s]"] <= stop)]
    for k, (kind, rows) in enumerate(truth.groupby("kind")):
        ax.plot(
            1e3 * rows["touch [s]"],
            rows["peak_force [N]"],
            "v",
            color=f"C{k + 1}",
            ms=5,
            label=f"touch: {kind}",
        )
    if scored is not None:
        onsets = scored.detections[(scored.detections >= start) & (scored.detections <= stop)]
        ax.plot(1e3 * onsets, [0.0] * len(onsets), "|", color="k", ms=12, label="detected onset")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("force [N]")
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    return fig


def pileup_figure(curve):
    """Fractions hit, merged and missed against the count flow rate."""
    fig, ax = plt.subplots(figsize=(5, 3.6))
    for column, label in (
        ("hit_fraction", "hit"),
        ("merged_fraction", "merged"),
        ("miss_fraction", "missed"),
    ):
        ax.plot(curve["rate [1/s]"], curve[column], "o-", label=label)
    ax.set_xlabel("flow rate [particles/s]")
    ax.set_ylabel("fraction of impacts")
    ax.set_ylim(-0.02, 1.02)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def calibration_figure(calibration):
    """Mass flow against plate output: the fitted line, calibration and test points."""
    table = calibration.table
    fig, ax = plt.subplots(figsize=(5, 3.6))
    out = table["calibration_output [N]"]
    ax.plot(out, table["flow [kg/s]"], "o", label="calibration runs")
    ax.plot(table["test_output [N]"], table["flow [kg/s]"], "s", mfc="none", label="test runs")
    ax.plot(out, calibration.slope * out + calibration.intercept, "-", color="0.4", label="fit")
    ax.set_xlabel("plate output: mean S1 [N]")
    ax.set_ylabel("mass flow [kg/s]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _svg(fig):
    buffer = io.StringIO()
    fig.savefig(buffer, format="svg", metadata={"Date": None})
    text = buffer.getvalue()
    return text[text.index("<svg") :]


def _table(frame):
    return frame.to_html(index=False, float_format=lambda v: f"{v:.5g}")


def write_report(
    out, result, scored=None, features=None, confusion=None, curve=None, calibration=None
):
    """Write ``report.html`` and the figures' PNGs into ``out`` (a folder); returns the
    page's path. Every argument but ``out`` and ``result`` is optional (a section each)."""
    figures = [("signal", signal_figure(result, scored), "Signal over the true force")]
    if curve is not None:
        figures.append(("pileup", pileup_figure(curve), "Pile-up curve"))
    if calibration is not None:
        figures.append(("calibration", calibration_figure(calibration), "Calibration curve"))
    parts = [f"<h1>Grain stream on a sensor plate</h1><pre>{html.escape(_summary(result))}</pre>"]
    for name, fig, title in figures:
        fig.savefig(out / f"{name}.png", dpi=120)
        parts.append(f"<h2>{html.escape(title)}</h2>{_svg(fig)}")
        plt.close(fig)
    if scored is not None:
        parts.append(
            "<h2>Detector against the truth</h2>"
            + _table(__import__("pandas").DataFrame([scored.counts]))
        )
    if confusion is not None:
        parts.append(
            "<h2>Kinds (grain, chaff, straw) from signal features (rows: true)</h2>"
            + confusion.to_html()
        )
    if curve is not None:
        parts.append("<h2>Pile-up table</h2>" + _table(curve))
    if calibration is not None:
        parts.append(
            f"<h2>Calibration (flow = {calibration.slope:.5g} output + "
            f"{calibration.intercept:.5g})</h2>" + _table(calibration.table)
        )
    parts.append("<h2>Impacts (first 200)</h2>" + _table(result.truth.head(200)))
    page = (
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Stream</title>"
        f"<style>{_STYLE}</style></head><body>{''.join(parts)}</body></html>"
    )
    path = out / "report.html"
    path.write_text(page, encoding="utf-8")
    return path


def _summary(result):
    case = result.case
    truth = result.truth
    kinds = truth.loc[truth["contact"] == 0, "kind"].value_counts().to_dict()
    return json.dumps(
        {
            "particles drawn": len(result.particles),
            "impacts by kind": kinds,
            "re-contacts": int((truth["contact"] > 0).sum()),
            "duration [s]": case.duration,
            "time step [s]": result.time_step,
            "steps": len(result.steps),
            "MPI ranks": result.ranks,
            "sensor resonance [Hz]": case.sensor.resonance,
        },
        indent=1,
    )
