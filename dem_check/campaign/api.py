""":func:`run_campaign`: every impact of every record, the statistics, the report."""

import os
import time
from collections.abc import Mapping

import numpy as np
import pandas as pd

from contactlab.blas import one_blas_thread
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.inverse import FIT_MODELS, lobe_onset
from contactlab.quantities import columns
from contactlab.validation import check_choice, check_count, check_number, check_path
from dem_check.campaign import detection, noise, onsets
from dem_check.campaign.analysis import window_row
from dem_check.campaign.inputs import check_out_folder, expand_paths, for_file, read_record
from dem_check.campaign.local import record_noise
from dem_check.campaign.overlaps import separate_overlaps
from dem_check.campaign.result import CampaignResult
from dem_check.campaign.statistics import (
    join_metadata,
    numeric_predictors,
    population_statistics,
    regressions,
)
from dem_check.campaign.structure import record_modes
from dem_check.campaign.workers import analysed_impacts

__all__ = ["ENVELOPE_BINS", "IMPACT_COLUMNS", "run_campaign"]

ENVELOPE_BINS = 2000
"""Bins of the min/max envelope kept per record for the report's record plots."""

IMPACT_COLUMNS = (
    "file",
    "impact",
    "status",
    "reason",
    *columns(
        "onset",
        "significance",
        "noise",
        "peak_sensor_force",
        "sensor_response_time",
        "impulse",
        "velocity_change",
        "peak_contact_force",
        "contact_time",
    ),
)
"""Columns of the impact table (``velocity_change`` only with a grain), before the
``fit_*`` columns and the joined metadata."""

_FILE_COLUMNS = (
    "file",
    "status",
    "reason",
    "impacts",
    "impacts_ok",
    "format",
    "unit",
    "sensitivity [V/N]",
    "sample_rate [Hz]",
    "samples",
    "length [s]",
    "noise [N]",
    "threshold [N]",
    "largest_threshold [N]",
    "wander [N]",
)


def _check_per_file(name, option, check):
    """A per-file option (value or mapping of file -> value), each value checked."""
    if option is None:
        return None
    if isinstance(option, Mapping):
        return {str(k): check(f"{name}[{k!r}]", v) for k, v in option.items()}
    return check(name, option)


def _check_channel(name, value):
    if isinstance(value, bool) or not isinstance(value, str | int):
        raise ParameterError(f"{name} must be a channel name or 0-based index; got {value!r}")
    return value


def _check_channel_found(channel, rows):
    """Refuse one ``channel`` for all files that none of them holds (a misspelt name): a
    per-file dict, or a channel some files lack, leaves rows with status ``"no channel"``."""
    if channel is None or isinstance(channel, Mapping) or not rows:
        return
    if all(row["status"] == "no channel" for row in rows):
        raise ParameterError(f"channel {channel!r} is in none of the records: {rows[0]['reason']}")


def _check_sensitivity(name, value):
    return check_number(name, value, low=0.0, unit="V/N")


def _check_inputs(sensor, grain, fit, gallery):
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if sensor.is_rigid:
        raise ParameterError(
            "sensor is rigid: a campaign reconstructs the contact force through the "
            "sensor's resonance and damping; give the moving sensor"
        )
    if grain is not None and not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain or None; got {grain!r}")
    if fit is not None:
        fit = check_choice("fit", fit, tuple(FIT_MODELS))
        if grain is None:
            raise ParameterError(f"fit={fit!r} needs the grain (grain=...)")
    return fit, check_count("gallery", gallery, low=0)


def _envelope(trace):
    """``(t, low, high)``: min and max of the record in :data:`ENVELOPE_BINS` bins."""
    size = max(1, len(trace) // ENVELOPE_BINS)
    count = len(trace) // size
    values = np.asarray(trace.values[: count * size]).reshape(count, size)
    finite = np.where(np.isfinite(values), values, np.nan)
    t = np.asarray(trace.t[: count * size]).reshape(count, size)[:, 0]
    return t, np.nanmin(finite, axis=1), np.nanmax(finite, axis=1)


def _impact_table(rows):
    """The impact rows as a table, columns in :data:`IMPACT_COLUMNS` order (fit columns
    after them), whichever row comes first; every column is there (empty when no row
    has it), ``velocity_change`` only with a grain."""
    extra = list(dict.fromkeys(k for row in rows for k in row if k not in IMPACT_COLUMNS))
    present = {k for row in rows for k in row}
    columns = [c for c in IMPACT_COLUMNS if c in present or c != "velocity_change [m/s]"]
    return pd.DataFrame(rows, columns=columns + extra)


def _file_row(path, status, reason, trace=None, floor=None, found=()):
    row = dict.fromkeys(_FILE_COLUMNS)
    row.update(file=path, status=status, reason=reason, impacts=len(found))
    row["impacts"] = sum(r["status"] not in detection.NOT_IMPACTS for r in found)
    row["impacts_ok"] = sum(r["status"] in detection.ANALYSED for r in found)
    if trace is not None:
        dt = float(trace.t[1] - trace.t[0]) if len(trace) > 1 else float("nan")
        row.update(
            {
                "format": trace.metadata.get("format"),
                "unit": "V" if "sensitivity [V/N]" in trace.metadata else trace.unit,
                "sensitivity [V/N]": trace.metadata.get("sensitivity [V/N]"),
                "sample_rate [Hz]": 1.0 / dt,
                "samples": len(trace),
                "length [s]": float(trace.t[-1] - trace.t[0]),
            }
        )
    if floor is not None:
        row.update(
            {
                "noise [N]": floor.noise,
                "threshold [N]": floor.threshold,
                "largest_threshold [N]": floor.sigmas * floor.largest_noise,
                "wander [N]": floor.wander,
            }
        )
    return row


class _Progress:
    """A tqdm bar over files (to stderr) that shows the impact being analysed."""

    def __init__(self, total, enabled):
        self.bar = None
        if enabled:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit="file", desc="campaign", dynamic_ncols=True)

    def impact(self, path, k, count):
        if self.bar is not None:
            self.bar.set_postfix_str(f"{os.path.basename(path)}: impact {k + 1}/{count}")

    def file_done(self):
        if self.bar is not None:
            self.bar.update()

    def close(self):
        if self.bar is not None:
            self.bar.close()


def _analyse_file(path, options, timings, progress):
    """Rows of one file: its file row, its impact rows and gallery traces, its envelope."""
    sensor, grain, fit = options["sensor"], options["grain"], options["fit"]
    started = time.perf_counter()
    trace, status, reason = read_record(
        path, for_file("channel", options["channel"], path), for_file("s", options["sens"], path)
    )
    timings["read"] += time.perf_counter() - started
    if trace is None:
        return _file_row(path, status, reason), [], {}, None
    started = time.perf_counter()
    try:
        found = detection.find_impacts(trace, sensor, **options["limits"])
    except ParameterError as exc:
        timings["detect"] += time.perf_counter() - started
        return _file_row(path, "not analysable", f"{path}: {exc}", trace), [], {}, _envelope(trace)
    timings["detect"] += time.perf_counter() - started
    rows, gallery = [], {}
    started = time.perf_counter()
    levels = record_noise(found, sensor)  # white and 1/f noise, once per record
    modes = record_modes(found, sensor, noise=levels) if options["crosstalk"] else []
    crosstalk = options["crosstalk"]
    separated = separate_overlaps(found, sensor, grain, fit, crosstalk, modes, levels)
    analysable = detection.ANALYSED
    read = [k for k, w in enumerate(found.impacts) if k not in separated and w.status in analysable]
    settings = (sensor, grain, fit, crosstalk, modes, levels)
    analysed = analysed_impacts(found, read, settings, options["workers"])
    for k, window in enumerate(found.impacts):
        progress.impact(path, k, len(found.impacts))
        if k in separated:  # an overlapping impact, read apart or flagged with why not
            row, traces = separated[k]
        elif k in analysed:
            row, traces = analysed[k]
        else:
            row, traces = {**window_row(window), "significance [-]": window.significance}, None
        if traces is not None:
            gallery[(path, k)] = traces
        rows.append({"file": path, "impact": k, **row})
    listed = (*found.steps, *found.swings, *found.unconfirmed)  # not impacts, not analysed
    for k, step in enumerate(listed, start=len(found.impacts)):
        rows.append(
            {"file": path, "impact": k, **window_row(step), "significance [-]": step.significance}
        )
    timings["analyse"] += time.perf_counter() - started
    if any(r["status"] not in detection.NOT_IMPACTS for r in rows):
        status, reason = "ok", ""
    else:
        status = "no impact"
        floor = found.floor
        reason = (
            f"{path}: no impact: the smoothed signal never exceeds the detection threshold "
            f"({floor.sigmas:.3g} sigma of its local noise: {floor.threshold:.4g} N where the "
            f"noise is typical, up to {floor.sigmas * floor.largest_noise:.4g} N)"
        )
    row = _file_row(path, status, reason, trace, found.floor, rows)
    return row, rows, gallery, _envelope(trace)


def _settings(paths, options, metadata):
    sensor, grain = options["sensor"], options["grain"]
    named = [paths] if isinstance(paths, str | os.PathLike) else paths
    table = metadata is None or isinstance(metadata, pd.DataFrame)
    return {
        "paths": [os.fspath(p) for p in named],
        "sensor": sensor.to_dict(),
        "grain": None if grain is None else grain.to_dict(),
        "sensitivity [V/N]": options["sens"],
        "channel": options["channel"],
        "fit": options["fit"],
        "crosstalk": options["crosstalk"],
        "metadata": None if table else os.fspath(metadata),
        "gallery": options["gallery"],
        "reconstruction": "contactlab.inverse.reconstruct_force (tikhonov, gcv)",
        "detection": {
            "smoothing -3 dB [Hz]": detection.CUTOFF_FACTOR * sensor.resonance,
            "false alarms per record": detection.FALSE_ALARMS,
            "onset [sigma]": detection.ONSET_SIGMAS,
            "onset fit: contact family read on [impacts]": onsets.FAMILY_IMPACTS,
            "onset fit: families [-]": sorted(lobe_onset.FAMILIES),
            "running baseline block [sensor periods]": noise.BLOCK_PERIODS,
            "running baseline block, fewest [samples]": noise.BLOCK_MIN_SAMPLES,
            "min_force [N]": options["limits"]["min_force"],
            "min_separation [s]": options["limits"]["min_separation"],
            "noise floor [sigma]": detection.FLOOR_SIGMAS,
            "quiet time to end an impact [s]": detection.QUIET_PERIODS * sensor.period,
            "largest local baseline [s]": detection.BASELINE_PERIODS * sensor.period,
            "ringing growth that flags an overlap [-]": detection.GROWTH_FACTOR,
        },
    }


def run_campaign(
    paths,
    sensor,
    grain=None,
    *,
    sensitivity=None,
    channel=None,
    out=None,
    fit=None,
    metadata=None,
    gallery=24,
    progress=False,
    min_force=None,
    min_separation=None,
    crosstalk=True,
    workers=1,
):
    """Analyse every impact in a set of long records, as a laboratory does after a
    measurement day.

    For each file: read it (any format :func:`dem_check.read_trace` reads), find every
    impact (:func:`dem_check.campaign.detection.find_impacts`: noise floor from the
    record itself, impacts separated once the ringing has decayed, overlaps flagged),
    read each impact's signal and reconstruct its true force
    (:mod:`dem_check.campaign.analysis`); then population statistics and, with
    ``metadata``, regressions on its numeric columns. See ``docs/campaign.md``.

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        A folder (its files), a glob pattern or a list of files and folders.
    sensor : Sensor
        The moving sensor (its resonance and damping ratio enter the reconstruction).
    grain : Grain, optional
        The grain: adds ``velocity_change [m/s]`` (impulse / mass) and allows ``fit``.
    sensitivity : float or dict, optional
        Sensor sensitivity [V/N] converting volt records to newtons; a dict maps file
        paths or names to their own sensitivity (several instruments). A volt record
        without one is listed with status ``"no sensitivity"``.
    channel : str, int or dict, optional
        Channel of multi-channel files (name or 0-based index; a dict per file).
    out : str or os.PathLike, optional
        Folder for ``impacts.csv``, ``files.csv``, ``statistics.csv``,
        ``regressions.csv``, ``settings.json`` and ``report.html``; refused if it holds
        one of the records (they would be overwritten).
    fit : str, optional
        Fit this law (a key of :data:`contactlab.inverse.FIT_MODELS`) to every ok impact
        (needs ``grain``): the ``fit_*`` columns.
    metadata : str, os.PathLike or pandas.DataFrame, optional
        CSV with a ``file`` column (and optionally ``impact``) joined to the impacts;
        its numeric columns are regressed on (see
        :func:`dem_check.campaign.statistics.join_metadata`). Never read as a record.
    gallery : int, default 24
        Impacts drawn in the report's gallery (evenly spaced; 0 for none).
    progress : bool, default False
        Show a progress bar (tqdm, on stderr).
    min_force : float, optional
        Smallest peak signal [N] of an impact; weaker candidates are listed with status
        ``"below min_force"`` and not analysed.
    min_separation : float, optional
        Shortest time between impact onsets [s]; closer candidates are listed with
        status ``"too close"`` and not analysed.
    crosstalk : bool, default True
        Remove the structure's crosstalk (its modes ringing after each hit, found on the
        record: :mod:`dem_check.campaign.structure`) before each impact is measured; the
        columns ``crosstalk [N]`` and ``crosstalk_modes`` say what was removed. On
        records without crosstalk it finds no mode (measured, ``docs/campaign.md``).
    workers : int, default 1
        Processes that read a record's impacts (their signal numbers, crosstalk and
        reconstructed force), forked from this one where the platform can
        (:mod:`dem_check.campaign.workers`); the rows are the same as with one. Detection
        and the record's structure modes stay on this process.

    Returns
    -------
    CampaignResult

    Raises
    ------
    ParameterError
        Bad arguments, ``paths`` naming no file at all, ``out`` holding a record, or a bad
        metadata table. Problems with single files or impacts never raise: they are rows
        with a status and a reason (an unexpected error in one file too: ``"failed"``).
    """
    fit, gallery = _check_inputs(sensor, grain, fit, gallery)
    for name, flag in (("crosstalk", crosstalk), ("progress", progress)):
        if not isinstance(flag, bool):
            raise ParameterError(f"{name} must be True or False; got {flag!r}")
    options = {
        "workers": check_count("workers", workers),
        "crosstalk": crosstalk,
        "sensor": sensor,
        "grain": grain,
        "fit": fit,
        "gallery": gallery,
        "sens": _check_per_file("sensitivity", sensitivity, _check_sensitivity),
        "channel": _check_per_file("channel", channel, _check_channel),
        "limits": dict(
            zip(
                ("min_force", "min_separation"),
                detection.check_limits(min_force, min_separation),
                strict=True,
            )
        ),
    }
    if metadata is not None and not isinstance(metadata, pd.DataFrame):
        metadata = check_path("metadata", metadata)
    skip = () if metadata is None or isinstance(metadata, pd.DataFrame) else (metadata,)
    files, problems = expand_paths(paths, skip)
    if out is not None:
        check_out_folder(check_path("out", out), files)
    timings = dict.fromkeys(("read", "detect", "analyse", "statistics", "report"), 0.0)
    file_rows = [_file_row(p.file, p.status, p.reason) for p in problems]
    impact_rows, gallery_traces, records = [], {}, {}
    bar = _Progress(len(files), progress)
    # one BLAS thread: each impact's linear algebra is small (contactlab.blas)
    blas = one_blas_thread()
    try:
        for path in files:
            try:
                row, rows, traces, envelope = _analyse_file(path, options, timings, bar)
            except Exception as exc:  # one bad file never costs the others their rows
                reason = f"{path}: {type(exc).__name__}: {exc}"
                row, rows, traces, envelope = _file_row(path, "failed", reason), [], {}, None
            file_rows.append(row)
            impact_rows += rows
            gallery_traces.update(traces)
            if envelope is not None:
                records[path] = envelope
            bar.file_done()
    finally:
        bar.close()
        blas.restore_original_limits()
    _check_channel_found(channel, file_rows[len(problems) :])
    started = time.perf_counter()
    impacts = _impact_table(impact_rows)
    notes, lines = [], pd.DataFrame()
    if metadata is not None:
        own = list(impacts.columns)
        impacts, notes = join_metadata(impacts, metadata)
        added = [c for c in impacts.columns if c not in own]
        lines = regressions(impacts, numeric_predictors(impacts, added))
    result_settings = _settings(paths, options, metadata)
    timings["statistics"] = time.perf_counter() - started
    result = CampaignResult(
        impacts=impacts,
        files=pd.DataFrame(file_rows, columns=list(_FILE_COLUMNS)),
        statistics=population_statistics(impacts),
        regressions=lines,
        settings=result_settings,
        notes=notes,
        timings=timings,
        gallery=gallery_traces,
        records=records,
    )
    if out is not None:
        started = time.perf_counter()
        result.write(out)
        timings["report"] = time.perf_counter() - started
    return result
