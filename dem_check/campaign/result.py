"""The result of a campaign: tables, what was set, and its files on disk."""

import json
import math
from dataclasses import dataclass, field

import pandas as pd

from contactlab.tables import write_csv
from contactlab.validation import make_folder
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.inputs import SKIPPED_STATUSES

__all__ = ["CampaignResult"]


def _json_ready(value):
    """Settings as JSON: floats that are not finite become null, tuples lists."""
    if isinstance(value, dict):
        return {str(k): _json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_ready(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


@dataclass(frozen=True, eq=False)
class CampaignResult:
    """Everything a campaign found (see :func:`dem_check.campaign.run_campaign`).

    Attributes
    ----------
    impacts : pandas.DataFrame
        One row per impact found: ``file``, ``impact`` (0-based index in its file),
        ``status`` (``"ok"`` or why it was not analysed), ``reason``, ``onset [s]``,
        ``noise [N]``, ``peak_sensor_force [N]``, ``sensor_response_time [s]``, ``impulse [N*s]``,
        ``peak_contact_force [N]``, ``contact_time [s]``; with a grain
        ``velocity_change [m/s]``; with a fit the ``fit_*`` columns.
    files : pandas.DataFrame
        One row per file (and per path that named none): ``file``, ``status``,
        ``reason``, ``impacts``, ``impacts_ok``, ``format``, ``unit``,
        ``sensitivity [V/N]``, ``sample_rate [Hz]``, ``samples``, ``length [s]``,
        ``noise [N]``, ``threshold [N]``.
    statistics : pandas.DataFrame
        Per file and overall (:func:`dem_check.campaign.statistics.population_statistics`).
    regressions : pandas.DataFrame
        Responses against metadata columns (empty without metadata).
    settings : dict
        What was asked and the detection constants (JSON-ready).
    notes : list of str
        Remarks that belong to no row (metadata that matched nothing).
    timings : dict
        Wall time [s] per stage: ``read``, ``detect``, ``analyse``, ``statistics``.
    gallery : dict
        ``(file, impact) -> ImpactTraces`` of the ok impacts, for the report.
    records : dict
        ``file -> (t, low, high)``: each record's min/max envelope, for the report.
    """

    impacts: pd.DataFrame
    files: pd.DataFrame
    statistics: pd.DataFrame
    regressions: pd.DataFrame
    settings: dict
    notes: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)
    gallery: dict = field(default_factory=dict, repr=False)
    records: dict = field(default_factory=dict, repr=False)

    @property
    def ok(self):
        """The analysed impacts: status ``"ok"``, ``"short pre-trigger"`` or an overlap
        read apart (:data:`dem_check.campaign.detection.ANALYSED`)."""
        return self.impacts[self.impacts["status"].isin(ANALYSED)]

    def summary(self):
        """Counts by status, for files and impacts (JSON-ready)."""
        return {
            "files": len(self.files),
            "files_ok": int((self.files["status"] == "ok").sum()),
            "files_skipped": int(self.files["status"].isin(SKIPPED_STATUSES).sum()),
            "file_status": self.files["status"].value_counts().to_dict(),
            "impacts": len(self.impacts),
            "impacts_ok": len(self.ok),
            "impact_status": self.impacts["status"].value_counts().to_dict()
            if len(self.impacts)
            else {},
            "notes": list(self.notes),
        }

    def to_html(self, title="Measurement campaign"):
        """The report as one self-contained HTML page (see :mod:`.report`)."""
        from dem_check.campaign.report import render_report

        return render_report(self, title)

    def write(self, out):
        """Write ``impacts.csv``, ``files.csv``, ``statistics.csv``, ``regressions.csv``,
        ``settings.json`` and ``report.html`` into the folder ``out`` (created).

        Returns
        -------
        list of pathlib.Path
            The files written.
        """
        out = make_folder("out", out)
        tables = {
            "impacts.csv": self.impacts,
            "files.csv": self.files,
            "statistics.csv": self.statistics,
            "regressions.csv": self.regressions,
        }
        written = []
        for name, table in tables.items():
            write_csv(table, out / name)
            written.append(out / name)
        settings = {**_json_ready(self.settings), "timings [s]": self.timings}
        (out / "settings.json").write_text(json.dumps(settings, indent=2) + "\n", "utf-8")
        (out / "report.html").write_text(self.to_html(), encoding="utf-8")
        return [*written, out / "settings.json", out / "report.html"]

    def __repr__(self):
        s = self.summary()
        return (
            f"CampaignResult({s['files']} files, {s['files_ok']} ok; {s['impacts']} impacts, "
            f"{s['impacts_ok']} ok)"
        )
