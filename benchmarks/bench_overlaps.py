"""Benchmark: overlapping impacts read apart (issue 22), against the record model's truth.

- ``--pairs``: two impacts of the hard grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz
  disc sensor, contact 100 us) at 2 MHz, 2 m/s then 2 or 1 m/s, 0.11-0.5 ms apart,
  white noise 0.03 N (1 % of the 3 N peak) and 1/f noise as large
  (``tests/dem_check/campaign/test_two_impacts.py``'s records), seeds 0-2: each impact's
  status and its errors against its own truth (onset in samples, peak signal, impulse,
  reconstructed peak and contact time, relative), and the largest over the seeds.
  With ``--before REF``, the module ``dem_check/campaign/overlaps.py`` of the git
  revision ``REF`` reads the same detections in the same run (rows ``version`` "before"
  and "now"). ``--misread NAME,ZETA``: the record's contact family replaced by that one
  before the overlaps are read (a misread family: ``linear`` is this contact's). Column
  ``check``: the joint fit's chi-squared excess over the record's noise's expectation
  [standard deviations] as the row's reason gives it (the kept fit's; ``rejected``
  where the record's family's fit was refitted).
- ``--split``: the pairs 110-130 us apart, which the analysis flags by their impulse
  and does not read apart, fitted here (not in the campaign) as two lobes of the contact
  family through the sensor plus a line on one window, from 8 periods before the
  fitted onset to 16 past the lobe (:class:`contactlab.inverse.lobe_model.LobeModel`'s
  signal; onsets and durations scanned, then refined by a simplex restarted a sensor
  period either side, where the residual has its neighbouring minima): each contact's
  errors against its truth. The family is read on the merged lobe (as on a record with
  no other impact) or given (``--family linear,0.175``: as read on the other pairs).
- ``--mixes``: the records of ``bench_realistic.py --accuracy`` (every configuration, 4
  records each) and of ``bench_steps.py``'s hard mix (100 records): how many impacts
  the detection flags ``overlap``, how many of them are now read apart with numbers,
  and their errors where they match a true impact (within 60 us).

Run: ``.venv/bin/python benchmarks/bench_overlaps.py [--pairs] [--mixes] [--seeds N]
[--before REF] [--misread NAME,ZETA] [--gaps 200 300 ...] [--split [--family NAME,ZETA]]``
"""

import argparse
import dataclasses
import importlib.util
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
from bench_realistic import CONFIGURATIONS, RECORDS, _records, hard  # beside this script
from bench_steps import hard_mix
from scipy import optimize

from contactlab.inverse.lobe_model import LobeModel
from dem_check.campaign import find_impacts
from dem_check.campaign.analysis import analyse_impact
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.local import record_noise
from dem_check.campaign.onsets import record_onsets
from dem_check.campaign.overlaps import separate_overlaps
from dem_check.campaign.structure import record_modes

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "dem_check" / "campaign"))
from test_two_impacts import _pair as pair  # the test's records

MATCH = 60e-6  # [s]
GAPS = (110e-6, 120e-6, 130e-6, 200e-6, 300e-6, 500e-6)  # [s]
COLUMNS = {
    "peak_sensor_force [N]": "peak signal",
    "impulse [N*s]": "impulse",
    "peak_contact_force [N]": "reconstructed peak",
    "contact_time [s]": "contact time",
}


def _before(revision):
    """``separate_overlaps`` of ``dem_check/campaign/overlaps.py`` at the git revision
    ``revision``, loaded as a module of its own (its imports are this tree's)."""
    root = Path(__file__).resolve().parents[1]
    source = subprocess.run(
        ["git", "show", f"{revision}:dem_check/campaign/overlaps.py"],
        cwd=root,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    spec = importlib.util.spec_from_loader("overlaps_before", loader=None)
    module = importlib.util.module_from_spec(spec)
    exec(compile(source, f"{revision}:overlaps.py", "exec"), module.__dict__)
    return module.separate_overlaps


def _rows(record, sensor, grain, everything=True, versions=None, family=None):
    """Every impact row of a record (overlaps read apart) with its onset and the
    detection's status; ``everything=False``: only the impacts flagged ``overlap``.
    ``versions``: ``{name: separate_overlaps}`` to compare on the same detection (rows
    carry ``version``); ``family``: the contact family the overlaps are read with."""
    found = find_impacts(record.trace, sensor)
    if family is not None:
        found = dataclasses.replace(found, contact_family=family)
    if not everything and not any(w.status == "overlap" for w in found.impacts):
        return []
    modes = record_modes(found, sensor)
    noise = record_noise(found, sensor)
    rows = []
    for version, separate in (versions or {"now": separate_overlaps}).items():
        separated = separate(found, sensor, grain, None, True, modes, noise)
        rows += _version_rows(found, separated, sensor, grain, everything, modes, noise, version)
    return rows


def _version_rows(found, separated, sensor, grain, everything, modes, noise, version):
    """The rows of one reading of the overlaps (:func:`_rows`)."""
    rows = []
    for k, window in enumerate(found.impacts):
        if k in separated:
            row = separated[k][0]
        elif not everything:
            continue
        elif window.status in ANALYSED:
            row = analyse_impact(found, window, sensor, grain, None, True, modes, noise)[0]
        else:
            row = {"status": window.status, "onset [s]": window.onset}
        rows.append({**row, "flagged": window.status, "version": version})
    return rows


def _errors(row, truth, rate):
    """The row's errors against the nearest true impact (None if none within MATCH)."""
    gap = np.abs(truth["onset [s]"].to_numpy() - row["onset [s]"])
    if gap.min() > MATCH:
        return None
    true = truth.iloc[int(gap.argmin())]
    out = {
        "true #": int(gap.argmin()),
        "onset [samples]": (row["onset [s]"] - true["onset [s]"]) * rate,
    }
    for column, name in COLUMNS.items():
        out[name] = row.get(column, np.nan) / true[column] - 1.0
    return out


def _check(reason):
    """The joint fit's chi-squared excess the reason states [-] (NaN if none), and
    ``rejected`` where the record's family's fit was refitted."""
    found = re.search(r"(agrees|chi-squared) \(?([-+]?[0-9.]+)", reason or "")
    value = np.nan if found is None else float(found.group(2))
    return value, "was rejected" in (reason or "")


def pairs(seeds, gaps, ratios, versions, family=None):
    grain, sensor, law = hard()
    table = []
    for gap in gaps:
        for ratio in ratios:
            for seed in range(seeds):
                record = pair((grain, sensor, law), gap, ratio, seed)
                for row in _rows(record, sensor, grain, versions=versions, family=family):
                    errors = _errors(row, record.truth, 2e6) or {}
                    check, rejected = _check(row.get("reason"))
                    table.append(
                        {
                            "version": row["version"],
                            "gap [us]": gap * 1e6,
                            "ratio": ratio,
                            "seed": seed,
                            "status": row["status"],
                            "check": check,
                            "rejected": rejected,
                            **errors,
                        }
                    )
    table = pd.DataFrame(table)
    pd.set_option("display.width", 200)
    print(table.round(4).to_string())
    numbers = ["onset [samples]", *COLUMNS.values()]
    read = table[table["status"].isin(ANALYSED)]
    by = ["version", "gap [us]", "ratio", "true #"]
    largest = read.groupby(by)[numbers].agg(lambda v: np.nanmax(np.abs(v)))
    print("largest errors of the impacts read (onset in samples, the others relative):")
    print(largest.round(4).to_string())
    print(table.groupby(["version", "gap [us]"])["status"].value_counts().to_string())


def _two_lobes(t, y, onset, length, sensor, family):
    """Two lobes of ``family`` and a line fitted on ``t`` (module docstring, ``--split``):
    per contact its onset [s], contact time [s], force peak [N], impulse [N*s] and
    signal peak [N]."""
    model = LobeModel(t, y, sensor, family[0], family[1])
    period, dt, units = sensor.period, float(t[1] - t[0]), {}

    def unit(tau):
        return units.setdefault(round(tau, 15), model.unit(tau))

    def solve(p):
        t1, tau1, t2, tau2 = p
        if not (tau1 > 0.0 and tau2 > 0.0 and t2 > t1):
            return np.inf, None
        lobes = [model.response(t1, tau1, unit(tau1)), model.response(t2, tau2, unit(tau2))]
        design = np.column_stack([model.line, *lobes])
        c = np.linalg.lstsq(design, y, rcond=None)[0]
        r = y - design @ c
        return float(r @ r), c

    grid = [  # one duration for both; the first touch up to two periods before the onset
        (solve((t1, tau, t2, tau))[0], t1, tau, t2)
        for tau in length * np.linspace(0.35, 1.2, 12)
        for t1 in onset + np.arange(-2.0 * period, 0.5 * period, period / 8)
        for t2 in np.arange(t1 + 0.5 * tau, onset + 1.5 * length, period / 8)
    ]
    _, t1, tau, t2 = min(grid)

    def refine(x):
        simplex = [x, *(x + np.diag([dt, 0.02 * x[1], dt, 0.02 * x[3]]))]
        options = {"initial_simplex": simplex, "xatol": 1e-3 * dt, "fatol": 1e-12}
        return optimize.minimize(lambda p: solve(p)[0], x, method="Nelder-Mead", options=options)

    best = refine(np.array([t1, tau, t2, tau]))
    for shift in (-period, period):
        for moved in ([shift, -shift, 0.0, 0.0], [0.0, 0.0, shift, 0.0]):
            tried = refine(best.x + np.asarray(moved))
            best = tried if tried.fun < best.fun else best
    c = solve(best.x)[1]
    out = []
    for k, (t0, tau) in enumerate((best.x[:2], best.x[2:])):
        a = c[2 + k]
        out.append(
            {
                "onset [s]": t0,
                "contact_time [s]": tau,
                "peak_contact_force [N]": a,
                "impulse [N*s]": a * tau * np.trapezoid(model.h, model.u),
                "peak_sensor_force [N]": a * float(np.max(unit(tau)[1])),
            }
        )
    return out


def split(seeds, gaps, family):
    grain, sensor, law = hard()
    table = []
    for gap in (g for g in gaps if g < 150e-6):
        for ratio in (1.0, 0.5):
            for seed in range(seeds):
                record = pair((grain, sensor, law), gap, ratio, seed)
                found = find_impacts(record.trace, sensor)
                window = found.impacts[0]
                noise = record_noise(found, sensor)
                onsets, _, name, damping, _, _ = record_onsets(found, [window], sensor, noise)
                read = family or (name, damping)
                t = np.asarray(found.record.t)
                y = np.asarray(found.record.values, dtype=float)
                # both contacts' lobe: the time the smoothed signal spends above 0.3 of its
                # peak over 0.8 (onsets.LOBE_LEVEL, LOBE_SPAN), which scales the scan
                smooth = np.asarray(found.smoothed.values)
                above = t[(t >= window.onset) & (smooth >= 0.3 * window.peak)]
                length = float(above[-1] - above[0]) / 0.8
                p = sensor.period
                kept = (t >= onsets[0] - 8 * p) & (t <= onsets[0] + 1.5 * length + 16 * p)
                rows = _two_lobes(t[kept], y[kept], onsets[0], length, sensor, read)
                for k, row in enumerate(rows):
                    errors = _errors(row, record.truth.iloc[[k]], 2e6)
                    errors.pop("true #")  # this contact's own truth
                    table.append(
                        {"gap [us]": gap * 1e6, "ratio": ratio, "seed": seed, "contact": k}
                        | {"family": f"{read[0]} {read[1]:.3f}"}
                        | errors
                    )
    table = pd.DataFrame(table)
    print(table.round(4).to_string())
    numbers = ["onset [samples]", *COLUMNS.values()]
    largest = table.groupby(["gap [us]", "contact"])[numbers].agg(lambda v: np.max(np.abs(v)))
    print("largest errors (onset in samples, the others relative):")
    print(largest.round(4).to_string())


def _mix(records, label, rate_of):
    grain, sensor, _ = hard()
    flagged = read = with_numbers = 0
    errors, reasons = [], []
    for record in records:
        for row in _rows(record, sensor, grain, everything=False):
            if row["flagged"] != "overlap":
                continue
            flagged += 1
            if row["status"] not in ANALYSED:
                near = np.abs(record.truth["onset [s]"].to_numpy() - row["onset [s]"]).min()
                true = f"a true impact {near * 1e6:.3g} us away" if near <= MATCH else "invented"
                reasons.append(f"{row['onset [s]']:.6g} s ({true}): {row['reason'][-120:]}")
            else:
                read += 1
                with_numbers += bool(np.isfinite(row.get("impulse [N*s]", np.nan)))
                found = _errors(row, record.truth, rate_of(record))
                if found is not None:
                    errors.append({"status": row["status"], **found})
    print(f"{label}: {flagged} overlap rows, {read} read apart, {with_numbers} with numbers")
    for row in reasons:
        print("  not read apart:", row)
    if errors:
        print(pd.DataFrame(errors).round(4).to_string())


def mixes():
    def rate(record):
        return 1.0 / float(record.trace.t[1] - record.trace.t[0])

    realistic = (
        record
        for name, (sample_rate, changes) in CONFIGURATIONS.items()
        for record in _records(sample_rate, range(RECORDS), changes)
    )
    _mix(realistic, "bench_realistic --accuracy records", rate)
    _mix((hard_mix(seed)[0] for seed in range(100)), "bench_steps hard mix", rate)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", action="store_true")
    parser.add_argument("--mixes", action="store_true")
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--gaps", type=float, nargs="+", help="[us] (default: all)")
    parser.add_argument("--ratios", type=float, nargs="+", default=[1.0, 0.5])
    parser.add_argument("--before", help="a git revision whose overlaps.py reads them too")
    parser.add_argument("--split", action="store_true")
    parser.add_argument("--family", help="NAME,ZETA for --split (default: read on the lobe)")
    parser.add_argument("--misread", help="NAME,ZETA: the family --pairs reads overlaps with")
    args = parser.parse_args()
    versions = {"now": separate_overlaps}
    if args.before:
        versions = {"before": _before(args.before), **versions}
    gaps = GAPS if args.gaps is None else tuple(g * 1e-6 for g in args.gaps)
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    started = time.process_time()
    if args.pairs:
        misread = None
        if args.misread:
            name, zeta = args.misread.split(",")
            misread = (name, float(zeta))
        pairs(args.seeds, gaps, args.ratios, versions, misread)
    if args.split:
        family = None
        if args.family:
            name, zeta = args.family.split(",")
            family = (name, float(zeta))
        split(args.seeds, gaps, family)
    if args.mixes:
        mixes()
    print(
        f"CPU {time.process_time() - started:.1f} s, load average after: {os.getloadavg()[0]:.1f}"
    )


if __name__ == "__main__":
    main()
