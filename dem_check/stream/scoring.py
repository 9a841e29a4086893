"""Scoring a detector on a simulated stream against the truth.

A **detector** is a callable ``detector(trace, sensor) -> onsets [s]`` (array-like), or
``-> [(onset [s], peak [N]), ...]`` to have its peaks scored too, or
``None`` for the campaign's (:func:`dem_check.campaign.detection.find_impacts`, every
window it lists). Matching: each true impact (its ``touch [s]``) goes to the detection
with the latest onset at or before ``touch + tolerance``, if that onset is less than
``reach`` before the touch; ``tolerance`` defaults to two sensor periods (smoothing
moves an onset by about a period) and ``reach`` to :data:`REACH_PERIODS` sensor periods
(a signal's ringing has decayed by then, so a later impact is a new one). Then:

True impacts are the truth's impacts and those re-contacts that start more than
``reach`` after the particle's previous contact (:func:`true_events`): contact chatter on
the ringing plate belongs to the signal it interrupts.

* a **hit** is a detection holding exactly one true impact; its onset error is
  ``onset - touch``;
* a **merge** is a detection holding two or more (the detector saw one impact where
  there were several; each true impact in it counts as merged);
* a **miss** is a true impact with no detection before it in reach;
* a **false alarm** is a detection holding none.

:func:`pileup_curve` runs a case at several flow rates and tabulates these against the
rate. :func:`discrimination` classifies hits by kind (grain, chaff, straw) from signal features
(peak, rise time, impulse, duration) with a nearest-centroid rule on log-features
scaled by their pooled within-kind spread (a diagonal linear discriminant), trained and
tested by two-fold cross-validation, and returns the confusion matrix.
"""

import numpy as np
import pandas as pd

from contactlab.entry_checks import check_callable, check_instance, check_shaped
from contactlab.errors import ParameterError
from contactlab.validation import check_number, check_values
from dem_check.campaign.detection import find_impacts
from dem_check.stream.result import STREAM_RESULT
from dem_check.traces import Trace

__all__ = [
    "FEATURES",
    "REACH_PERIODS",
    "Score",
    "campaign_detector",
    "discrimination",
    "hit_features",
    "pileup_curve",
    "score",
    "true_events",
]

REACH_PERIODS = 20.0
"""How long after a detection's onset a true impact still belongs to it [sensor periods]:
the ringing of a sensor of damping ratio 0.02 has decayed to 8 % by then."""

FEATURES = ("peak [N]", "rise_time [s]", "impulse [N*s]", "duration [s]")
"""Signal features of a hit used to tell the kinds apart (grain, chaff, straw)."""


def campaign_detector(trace, sensor):
    """``(onset [s], peak [N])`` of every impact window the campaign's detector lists
    (the peak of its low-passed signal)."""
    return [(w.onset, w.peak) for w in find_impacts(trace, sensor).impacts]


def _detections(found):
    """Onsets [s] and peaks [N] (NaN where the detector gives none), sorted by onset."""
    found = np.asarray(found, dtype=float)
    if found.ndim == 2 and found.shape[1] == 2:
        order = np.argsort(found[:, 0], kind="stable")
        return found[order, 0], found[order, 1]
    onsets = np.sort(found.reshape(-1))
    return onsets, np.full(onsets.size, np.nan)


def _signal_peaks(result, touch, onsets, owner, period):
    """Largest clean S1 [N] from each touch to the next detection or four sensor periods."""
    t = result.steps["t [s]"].to_numpy()
    s1 = result.steps["sensor_force [N]"].to_numpy()
    peaks = np.full(touch.size, np.nan)
    for k, (at, who) in enumerate(zip(touch, owner, strict=True)):
        stop = at + 4.0 * period
        if who + 1 < onsets.size:
            stop = min(stop, onsets[who + 1])
        inside = (t >= at) & (t <= stop)
        if inside.any():
            peaks[k] = s1[inside].max()
    return peaks


def true_events(truth, reach):
    """The contacts a detector should find: every impact, and every re-contact that
    starts more than ``reach`` [s] after the particle's previous contact ended (closer
    ones, e.g. contact chatter on the ringing plate, belong to the signal of the contact
    before)."""
    if "contact" not in truth or truth.empty:
        return truth
    ordered = truth.sort_values(["pid", "touch [s]"], kind="stable")
    gap = ordered["touch [s]"] - ordered.groupby("pid")["separation [s]"].shift()
    keep = (ordered["contact"] == 0) | (gap > reach)
    return ordered[keep].sort_values("touch [s]", kind="stable").reset_index(drop=True)


class Score:
    """A detector's result on one stream.

    Attributes
    ----------
    matches : pandas.DataFrame
        Per true impact: ``pid``, ``kind``, ``touch [s]``, ``detection`` (index, -1 for
        a miss), ``outcome`` (``"hit"``, ``"merged"``, ``"miss"``), ``onset_error
        [s]`` (hits), ``signal_peak [N]`` (the noise-free S1's largest value from the
        touch to the next detection, at most four sensor periods) and ``peak_error [N]``
        (the detector's peak minus it, hits of detectors that give peaks).
    detections : numpy.ndarray
        Onsets [s], sorted.
    counts : dict
        ``impacts``, ``hits``, ``merged``, ``misses``, ``false_alarms``,
        ``detections``.
    """

    def __init__(self, matches, detections, counts):
        self.matches, self.detections, self.counts = matches, detections, counts


def score(result, detector=None, trace=None, tolerance=None, reach=None):
    """Match a detector's onsets on ``result``'s trace to its truth (module docstring).

    ``tolerance`` and ``reach`` are in seconds; ``trace`` defaults to ``result.trace()``.
    """
    check_shaped("result", result, ("case", "truth", "steps"), STREAM_RESULT)
    check_callable("detector", detector, "detector(trace, sensor) -> onsets [s]")
    if tolerance is not None:
        tolerance = check_number("tolerance", tolerance, low=0.0, unit="s")
    if reach is not None:
        reach = check_number("reach", reach, low=0.0, unit="s")
    sensor = result.case.sensor
    trace = result.trace() if trace is None else trace
    onsets, peaks = _detections((detector or campaign_detector)(trace, sensor))
    tolerance = 2.0 * sensor.period if tolerance is None else tolerance
    reach = REACH_PERIODS * sensor.period if reach is None else reach
    truth = true_events(result.truth, reach)
    touch = truth["touch [s]"].to_numpy()
    owner = np.searchsorted(onsets, touch + tolerance, side="right") - 1
    owner[(owner >= 0) & (touch - onsets[np.maximum(owner, 0)] > reach)] = -1
    held = np.bincount(owner[owner >= 0], minlength=onsets.size)
    outcome = np.where(
        owner < 0, "miss", np.where(held[np.maximum(owner, 0)] == 1, "hit", "merged")
    )
    hit = outcome == "hit"
    error = np.where(hit, onsets[np.maximum(owner, 0)] - touch, np.nan)
    true_peak = _signal_peaks(result, touch, onsets, owner, sensor.period)
    peak_error = np.where(hit, peaks[np.maximum(owner, 0)] - true_peak, np.nan)
    matches = pd.DataFrame(
        {
            "pid": truth["pid"].to_numpy(),
            "kind": truth["kind"].to_numpy(),
            "contact": truth["contact"].to_numpy() if "contact" in truth else 0,
            "touch [s]": touch,
            "detection": owner,
            "outcome": outcome,
            "onset_error [s]": error,
            "signal_peak [N]": true_peak,
            "peak_error [N]": peak_error,
        }
    )
    counts = {
        "impacts": int(touch.size),
        "hits": int((outcome == "hit").sum()),
        "merged": int((outcome == "merged").sum()),
        "misses": int((outcome == "miss").sum()),
        "false_alarms": int((held == 0).sum()),
        "detections": int(onsets.size),
    }
    return Score(matches, onsets, counts)


def pileup_curve(case, rates, detector=None, run=None):
    """Hits, merges, misses and false alarms against the count flow rate.

    Parameters
    ----------
    case : StreamCase
        Its flow rate is replaced by each of ``rates`` [1/s].
    rates : sequence of float
    detector : callable, optional
        As for :func:`score`.
    run : callable, optional
        ``run(case) -> StreamResult`` (default :func:`~dem_check.stream.result.run_stream`).

    Returns
    -------
    pandas.DataFrame
        Per rate: ``rate [1/s]``, ``impacts``, the fractions of true impacts hit,
        merged and missed, the false alarms, and the hits' median absolute onset error
        [s] and peak error [%] (of the noise-free signal's peak).
    """
    from dataclasses import replace

    from dem_check.stream.case import StreamCase
    from dem_check.stream.result import run_stream

    check_instance("case", case, StreamCase, "read_case or DEFAULT_CASE.with_")
    rates = check_values("rates", rates, unit="1/s")
    check_callable("detector", detector, "detector(trace, sensor) -> onsets [s]")
    run = check_callable("run", run, "run(case) -> StreamResult") or run_stream
    rows = []
    for rate in rates:
        result = run(case.with_(flow=replace(case.flow, rate=float(rate), kind="count")))
        s = score(result, detector)
        n = max(s.counts["impacts"], 1)
        rows.append(
            {
                "rate [1/s]": float(rate),
                "impacts": s.counts["impacts"],
                "hit_fraction": s.counts["hits"] / n,
                "merged_fraction": s.counts["merged"] / n,
                "miss_fraction": s.counts["misses"] / n,
                "false_alarms": s.counts["false_alarms"],
                "median_onset_error [s]": _median_abs(s.matches["onset_error [s]"]),
                "median_peak_error [%]": _median_abs(
                    100.0 * s.matches["peak_error [N]"] / s.matches["signal_peak [N]"]
                ),
            }
        )
    return pd.DataFrame(rows)


def _median_abs(values):
    values = np.abs(np.asarray(values, dtype=float))
    values = values[np.isfinite(values)]
    return float(np.median(values)) if values.size else float("nan")


def hit_features(result, scored, trace=None):
    """:data:`FEATURES` of each hit, read from the trace between its onset and the next
    detection (or four sensor periods, whichever is first); with the hit's true kind."""
    check_shaped("result", result, ("case", "trace"), STREAM_RESULT)
    check_instance("scored", scored, Score, "score")
    check_instance("trace", trace, Trace, "StreamResult.trace", optional=True)
    trace = result.trace() if trace is None else trace
    t, v = np.asarray(trace.t), np.asarray(trace.values)
    period = result.case.sensor.period
    hits = scored.matches[scored.matches["outcome"] == "hit"]
    rows = []
    for _, hit in hits.iterrows():
        k = int(hit["detection"])
        start = scored.detections[k]
        stop = min(start + 4.0 * period, *scored.detections[k + 1 : k + 2], t[-1])
        inside = (t >= start) & (t < stop)
        if inside.sum() < 3:
            continue
        tw, vw = t[inside], v[inside]
        top = int(np.argmax(vw))
        above = vw > 0.5 * vw[top]
        rows.append(
            {
                "kind": hit["kind"],
                "peak [N]": float(vw[top]),
                "rise_time [s]": float(tw[top] - start) + 1e-12,
                "impulse [N*s]": float(np.clip(vw, 0.0, None).sum() * (tw[1] - tw[0])),
                "duration [s]": float(above.sum() * (tw[1] - tw[0])),
            }
        )
    return pd.DataFrame(rows, columns=["kind", *FEATURES])


def discrimination(features):
    """Two-fold cross-validated nearest-centroid classification of hits by kind.

    Parameters
    ----------
    features : pandas.DataFrame
        :func:`hit_features`' table.

    Returns
    -------
    pandas.DataFrame
        Confusion matrix: rows the true kinds, columns the predicted ones (counts).
    """
    check_instance("features", features, pd.DataFrame, "hit_features")
    missing = [c for c in ("kind", *FEATURES) if c not in features.columns]
    if missing:
        raise ParameterError(f"features has no column(s) {missing} (see hit_features)")
    if len(features) < 2:
        raise ParameterError(
            f"features needs at least 2 hits (one per cross-validation fold); got {len(features)}"
        )
    kinds = sorted(features["kind"].unique())
    x = np.log(np.maximum(features[list(FEATURES)].to_numpy(dtype=float), 1e-300))
    y = features["kind"].to_numpy()
    predicted = np.empty(y.size, dtype=object)
    fold = np.arange(y.size) % 2
    for f in (0, 1):
        train, test = fold != f, fold == f
        present = [k for k in kinds if (y[train] == k).any()]
        centroids = np.array([x[train & (y == k)].mean(axis=0) for k in present])
        # scaled by the pooled within-kind spread (a diagonal linear discriminant): a
        # feature that does not tell the kinds apart then weighs no more than its noise
        spread = x[train] - centroids[np.searchsorted(present, y[train])]
        sd = np.sqrt((spread**2).mean(axis=0)) + 1e-12
        z, centroids = x / sd, centroids / sd
        distance = ((z[test][:, None, :] - centroids[None]) ** 2).sum(axis=2)
        predicted[test] = np.array(present, dtype=object)[distance.argmin(axis=1)]
    matrix = pd.crosstab(
        pd.Categorical(y, categories=kinds),
        pd.Categorical(predicted, categories=kinds),
        rownames=["true"],
        colnames=["predicted"],
        dropna=False,
    )
    return matrix
