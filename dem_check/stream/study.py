"""One call that runs a stream case and writes everything: ``dem-check stream``.

:func:`stream_study` simulates the case, writes its files
(:meth:`~dem_check.stream.result.StreamResult.write`), scores the campaign's detector
(or the user's) against the truth, classifies the hits grain/chaff, optionally runs the
pile-up curve and the calibration curve, and writes the report. Under ``mpiexec`` only
rank 0 writes.
"""

import json
from pathlib import Path

from contactlab.entry_checks import check_callable, check_flag, check_instance
from contactlab.tables import write_csv
from contactlab.validation import check_number, check_path, check_values
from dem_check.stream.calibration import calibration_curve
from dem_check.stream.case import StreamCase
from dem_check.stream.report import write_report
from dem_check.stream.result import run_stream
from dem_check.stream.scoring import discrimination, hit_features, pileup_curve, score

__all__ = ["stream_study"]


def stream_study(case, out, *, detector=None, pileup_rates=None, capacity=None, progress=False):
    """Run ``case`` and write its files, scores and report into ``out``.

    Parameters
    ----------
    case : StreamCase
    out : str or os.PathLike
        Output folder.
    detector : callable, optional
        ``detector(trace, sensor) -> onsets [s]``; default the campaign's.
    pileup_rates : sequence of float, optional
        Count rates [1/s] of a pile-up curve (one run each).
    capacity : float, optional
        Mass flow [kg/s] of an impact-plate calibration at 25/50/75/100 % (eight runs).
    progress : bool, default False

    Returns
    -------
    dict
        Summary: impacts, the detector's counts, the confusion matrix, the calibration's
        errors [%] (written to ``summary.json`` too).
    """
    check_instance("case", case, StreamCase, "read_case or DEFAULT_CASE.with_")
    progress = check_flag("progress", progress)
    out = Path(check_path("out", out))
    check_callable("detector", detector, "detector(trace, sensor) -> onsets [s]")
    if pileup_rates is not None:
        pileup_rates = check_values("pileup_rates", pileup_rates, unit="1/s")
    if capacity is not None:
        capacity = check_number("capacity", capacity, low=0.0, unit="kg/s")
    result = run_stream(case, progress=progress)
    curve = None if pileup_rates is None else pileup_curve(case, pileup_rates, detector)
    calibration = None if capacity is None else calibration_curve(case, capacity)
    if result.rank != 0:  # under mpiexec, rank 0 writes
        return {}
    trace = result.trace()
    result.write(out, trace)
    scored = score(result, detector, trace)
    write_csv(scored.matches, out / "matches.csv")
    features = hit_features(result, scored, trace)
    confusion = discrimination(features) if features["kind"].nunique() > 1 else None
    if curve is not None:
        write_csv(curve, out / "pileup.csv")
    if calibration is not None:
        write_csv(calibration.table, out / "calibration.csv")
    write_report(out, result, scored, features, confusion, curve, calibration)
    summary = {
        "impacts": len(result.truth),
        "detector": scored.counts,
        "confusion": None if confusion is None else confusion.to_dict(),
        "calibration_error [%]": None
        if calibration is None
        else dict(zip(calibration.table["fraction"], calibration.table["error [%]"], strict=True)),
        "ranks": result.ranks,
        "time_step [s]": result.time_step,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=1, default=str), "utf-8")
    return summary
