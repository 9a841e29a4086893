"""Benchmark: overlapping impacts read apart (issue 22), against the record model's truth.

- ``--pairs``: two impacts of the hard grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz
  disc sensor, contact 100 us) at 2 MHz, 2 m/s then 2 or 1 m/s, 0.11-0.5 ms apart,
  white noise 0.03 N (1 % of the 3 N peak) and 1/f noise as large
  (``tests/dem_check/campaign/test_two_impacts.py``'s records), seeds 0-2: each impact's
  status and its errors against its own truth (onset in samples, peak signal, impulse,
  reconstructed peak and contact time, relative), and the largest over the seeds.
  With ``--before REF``, the module ``dem_check/campaign/overlaps.py`` of the git
  revision ``REF`` reads the same detections in the same run (rows ``version`` "before"
  and "now").
- ``--mixes``: the records of ``bench_realistic.py --accuracy`` (every configuration, 4
  records each) and of ``bench_steps.py``'s hard mix (100 records): how many impacts
  the detection flags ``overlap``, how many of them are now read apart with numbers,
  and their errors where they match a true impact (within 60 us).

Run: ``.venv/bin/python benchmarks/bench_overlaps.py [--pairs] [--mixes] [--seeds N]
[--before REF] [--gaps 200 300 ...]``
"""

import argparse
import importlib.util
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
from bench_realistic import CONFIGURATIONS, RECORDS, _records, hard  # beside this script
from bench_steps import hard_mix

from dem_check.campaign import find_impacts
from dem_check.campaign.analysis import analyse_impact
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.local import record_noise
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


def _rows(record, sensor, grain, everything=True, versions=None):
    """Every impact row of a record (overlaps read apart) with its onset and the
    detection's status; ``everything=False``: only the impacts flagged ``overlap``.
    ``versions``: ``{name: separate_overlaps}`` to compare on the same detection (rows
    carry ``version``)."""
    found = find_impacts(record.trace, sensor)
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


def pairs(seeds, gaps, ratios, versions):
    grain, sensor, law = hard()
    table = []
    for gap in gaps:
        for ratio in ratios:
            for seed in range(seeds):
                record = pair((grain, sensor, law), gap, ratio, seed)
                for row in _rows(record, sensor, grain, versions=versions):
                    errors = _errors(row, record.truth, 2e6) or {}
                    table.append(
                        {
                            "version": row["version"],
                            "gap [us]": gap * 1e6,
                            "ratio": ratio,
                            "seed": seed,
                            "status": row["status"],
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
    args = parser.parse_args()
    versions = {"now": separate_overlaps}
    if args.before:
        versions = {"before": _before(args.before), **versions}
    gaps = GAPS if args.gaps is None else tuple(g * 1e-6 for g in args.gaps)
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    started = time.process_time()
    if args.pairs:
        pairs(args.seeds, gaps, args.ratios, versions)
    if args.mixes:
        mixes()
    print(
        f"CPU {time.process_time() - started:.1f} s, load average after: {os.getloadavg()[0]:.1f}"
    )


if __name__ == "__main__":
    main()
