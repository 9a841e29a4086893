"""The campaign report: one self-contained HTML page.

No script, no remote font, stylesheet or image: figures are inline SVG
(:mod:`dem_check.campaign.figures`) and tables plain HTML (``DataFrame.to_html``, which
escapes every cell). The page opens from disk in any browser, also offline, and can be
mailed as one file. Sections: summary, files, statistics, distributions, regressions,
gallery, records, detection (each record's noise and thresholds, every candidate with
its status and reason), failures, settings.
"""

import html
import json
from datetime import UTC, datetime

import numpy as np

from dem_check.campaign import figures
from dem_check.campaign.detection import ANALYSED

__all__ = ["render_report"]

STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 75em; color: #222; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0 1.5em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: right; }
th { background: #eee; }
td:first-child, th:first-child { text-align: left; }
.gallery { display: flex; flex-wrap: wrap; gap: 0.5em; }
.gallery figure { margin: 0; }
svg { max-width: 100%; height: auto; }
.bad { color: #a00; }
pre { background: #f6f6f6; padding: 0.8em; overflow-x: auto; }
"""


STATUS_LEGEND = (
    "<p>Analysed: <em>ok</em>; <em>short pre-trigger</em> (its baseline read after its "
    "ringing); <em>overlap, neighbour held out</em> (an impact another one followed in its "
    "ringing, read up to two sensor periods before that one); <em>overlap, ringing "
    "subtracted</em> (an impact that began in another's ringing, read on the record less "
    "that impact's free ringing fitted after its contact). Not analysed: <em>overlap</em> "
    "(two impacts that could not be read apart: the reason says why), <em>overlap, "
    "unreliable</em> (an impact read apart whose joint fit with the impact before it agrees "
    "with the record's noise for no contact family: its numbers are not to be trusted), "
    "<em>truncated</em>, "
    "<em>no baseline</em>, <em>negative</em>, <em>overrange</em>, <em>clipped</em>, "
    "<em>below min_force</em>, <em>too close</em>, <em>offset step</em>, <em>structure "
    "ringing</em> (a negative swing after an impact that the plate's free ringing explains), "
    "<em>no contact</em> (a candidate under 10 sigma where no contact lobe fits: not an "
    "impact); "
    "and the analysis's <em>reconstruction failed</em>, <em>fit failed</em>, <em>implausible</em> "
    "(docs/campaign.md, Per impact).</p>"
)
"""What each impact status means, under the candidates' table."""


def _table(frame, digits=5):
    if not len(frame):
        return "<p>(none)</p>"
    return frame.to_html(index=False, na_rep="", float_format=lambda v: f"{v:.{digits}g}")


def _section(anchor, title, body):
    return f'<section id="{anchor}"><h2>{html.escape(title)}</h2>\n{body}\n</section>\n'


def _summary(result):
    s = result.summary()
    statuses = ", ".join(f"{html.escape(str(k))}: {v}" for k, v in s["impact_status"].items())
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in result.notes)
    return (
        f'<p><span id="file-count">{s["files"]}</span> files '
        f'(<span id="files-ok">{s["files_ok"]}</span> read and analysed), '
        f'<span id="impact-count">{s["impacts"]}</span> impacts found '
        f'(<span id="impacts-ok">{s["impacts_ok"]}</span> analysed; {statuses or "none"}).</p>'
        + (f"<ul>{notes}</ul>" if notes else "")
    )


def _gallery(result):
    limit = result.settings.get("gallery", 24)
    keys = list(result.gallery)
    if not keys or limit == 0:
        return "<p>(no analysed impact)</p>"
    chosen = [keys[i] for i in np.unique(np.linspace(0, len(keys) - 1, limit).round().astype(int))]
    onsets = result.impacts.set_index(["file", "impact"])
    parts = [
        f"<p>{len(chosen)} of {len(keys)} analysed impacts, evenly spaced through the "
        "campaign (every impact is in the tables and impacts.csv).</p>",
        '<div class="gallery">',
    ]
    for file, impact in chosen:
        row = onsets.loc[(file, impact)]
        title = (
            f"{file} #{impact}: signal {row['peak_sensor_force [N]']:.3g} N, "
            f"force {row['peak_contact_force [N]']:.3g} N, "
            f"{row['contact_time [s]'] * 1e6:.4g} us"
        )
        svg = figures.gallery_svg(result.gallery[(file, impact)], row["onset [s]"], title)
        parts.append(f"<figure>{svg}</figure>")
    return "\n".join([*parts, "</div>"])


def _records(result):
    parts = []
    for file, envelope in result.records.items():
        found = result.impacts[result.impacts["file"] == file]
        parts.append(figures.record_svg(envelope, found["onset [s]"], found["status"], str(file)))
    note = "<p>Green: analysed impacts; red: impacts found but not analysed (see Failures).</p>"
    return note + "\n".join(parts) if parts else "<p>(no record read)</p>"


def _failures(result):
    files = result.files[result.files["status"] != "ok"][["file", "status", "reason"]]
    impacts = result.impacts[~result.impacts["status"].isin(ANALYSED)]
    impacts = impacts[["file", "impact", "status", "reason", "onset [s]"]]
    return (
        "<h3>Files</h3>\n"
        + _table(files)
        + "<h3>Impacts found but not analysed</h3>\n"
        + _table(impacts, digits=8)
    )


_DETECTION_COLUMNS = (
    "file",
    "status",
    "noise [N]",
    "threshold [N]",
    "largest_threshold [N]",
    "wander [N]",
    "impacts",
    "impacts_ok",
)
_CANDIDATE_COLUMNS = (
    "file",
    "impact",
    "status",
    "onset [s]",
    "onset_uncertainty [s]",
    "significance [-]",
    "peak_sensor_force [N]",
    "reason",
)


def _detection(result):
    """What the detector did, per record: the noise and thresholds it used, then every
    candidate it found with its status and reason (analysed ones too)."""
    files = result.files[[c for c in _DETECTION_COLUMNS if c in result.files.columns]]
    candidates = result.impacts[[c for c in _CANDIDATE_COLUMNS if c in result.impacts.columns]]
    note = (
        "<p>Each record's baseline is followed by a running median (blocks of "
        "<code>BLOCK_PERIODS</code> sensor periods) and its noise read locally (median "
        "absolute deviation per block): <em>noise</em> is the typical local noise, "
        "<em>threshold</em> the detection threshold where the noise is typical and "
        "<em>largest_threshold</em> where it is largest (hum, crosstalk, ringing), "
        "<em>wander</em> the range of the running baseline. A candidate is a run of the "
        "smoothed signal above the threshold; <em>significance</em> is its peak over the "
        "local noise. Every candidate is listed with its status and reason.</p>" + STATUS_LEGEND
    )
    return (
        note
        + "<h3>Noise and thresholds per record</h3>\n"
        + _table(files)
        + "<h3>Every candidate</h3>\n"
        + _table(candidates, digits=6)
    )


def _regressions(result):
    if not len(result.regressions):
        return "<p>No metadata joined (run_campaign(..., metadata=CSV)).</p>"
    body = _table(result.regressions)
    if (result.regressions["note"] == "").any():
        body += figures.regressions_svg(result.impacts, result.regressions)
    return body


def render_report(result, title="Measurement campaign"):
    """The HTML page of a :class:`~dem_check.campaign.result.CampaignResult`.

    Parameters
    ----------
    result : CampaignResult
    title : str, default "Measurement campaign"

    Returns
    -------
    str
        A complete HTML document with no external reference.
    """
    ok = result.ok
    settings_text = json.dumps(
        {**result.settings, "timings [s]": result.timings}, indent=2, default=str
    )
    stamp = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    body = [
        f"<h1>{html.escape(title)}</h1>",
        f"<p>Written {stamp} by dem_check.campaign. SI units; times in the tables in s.</p>",
        _section("summary", "Summary", _summary(result)),
        _section("files", "Files", _table(result.files)),
        _section("statistics", "Population statistics (ok impacts)", _table(result.statistics)),
        _section(
            "distributions",
            "Distributions",
            figures.distributions_svg(ok) if len(ok) else "<p>(no analysed impact)</p>",
        ),
        _section("regressions", "Regressions on metadata", _regressions(result)),
        _section("gallery", "Gallery: sensor signal and reconstructed force", _gallery(result)),
        _section("records", "Records", _records(result)),
        _section("detection", "Detection: noise, thresholds, candidates", _detection(result)),
        _section("failures", "Failures", _failures(result)),
        _section("settings", "Settings", f"<pre>{html.escape(settings_text)}</pre>"),
    ]
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{html.escape(title)}</title>\n"
        '<link rel="icon" href="data:,">\n'
        f"<style>{STYLE}</style>\n</head>\n<body>\n" + "\n".join(body) + "\n</body>\n</html>\n"
    )
