"""Benchmark: a 1.5-million-sample campaign of about 20 impacts, and where the time goes.

Three synthetic long records of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the
40 kHz disc sensor; raw peak 38 % above the true force) at 5 MHz with 1 % noise, written
as HDF5, TDMS and a generic CSV in volts (``dem_check.campaign.synthetic_record``; the
writing is not timed). Then, timed in the same run:

- ``run_campaign(..., out=DIR)``: reading, detection, per-impact analysis (signal numbers
  and the Tikhonov reconstruction), statistics and the HTML report;
- references: reading the files alone (``read_trace``), and detection plus
  ``reconstruct_force`` on every impact alone (the per-impact floor of any analysis).

Prints the stage times, the ratios to the references and the accuracy against the truth.

Run: ``.venv/bin/python benchmarks/bench_campaign.py [--samples N] [--impacts K]``
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.config import load_config
from contactlab.inverse import reconstruct_force
from dem_check import read_trace, write_trace
from dem_check.campaign import find_impacts, run_campaign, synthetic_record

ROOT = Path(__file__).resolve().parents[1]
RATE = 5e6  # [Hz]
SENSITIVITY = 0.01124  # [V/N]
LAYOUTS = (
    ("day1.h5", "hdf5", {"name": "day1/sensor", "time": "attrs"}),
    ("day1.tdms", "tdms", {"group": "day1", "channel": "sensor"}),
    ("day1.csv", "generic", {}),
)


def write_records(folder, samples, impacts):
    """The records and their truth tables (file path -> DataFrame)."""
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    law = cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)
    rng = np.random.default_rng(2024)
    truth = {}
    per_file = np.array_split(np.arange(impacts), len(LAYOUTS))
    for (name, layout, options), which in zip(LAYOUTS, per_file, strict=True):
        length = samples / len(LAYOUTS) / RATE
        onsets = np.sort(rng.uniform(2e-3, length - 3e-3, which.size))
        while which.size > 1 and np.diff(onsets).min() < 2.5e-3:  # ringing lasts ~1 ms
            onsets = np.sort(rng.uniform(2e-3, length - 3e-3, which.size))
        trace, table = synthetic_record(
            config.grain,
            config.sensor,
            law,
            rng.uniform(1.5, 2.5, which.size),
            onsets,
            length=length,
            sample_rate=RATE,
            noise=0.03,
            sensitivity=SENSITIVITY,
            offset=0.003,
            seed=int(which[0]) if which.size else 0,
        )
        path = folder / name
        write_trace(path, trace, layout, **options)
        truth[str(path)] = table
    return config, truth


def timed(function, *args, **kwargs):
    start = time.perf_counter()
    value = function(*args, **kwargs)
    return value, time.perf_counter() - start


def reference_reconstruction(paths, sensor):
    """Reading, detection and reconstruct_force on every ok impact, nothing else."""
    for path in paths:
        found = find_impacts(read_trace(path, sensitivity=SENSITIVITY), sensor)
        for window in found.impacts:
            part = slice(window.first, window.stop)
            reconstruct_force(
                found.signal.t[part],
                found.signal.values[part],
                sensor,
                baseline_window=window.baseline_window,
            )


def accuracy(result, truth):
    """Largest errors against the truth, and counts found / true."""
    rows = []
    for path, table in truth.items():
        found = result.impacts[result.impacts["file"] == path].reset_index(drop=True)
        if len(found) != len(table):
            print(f"  {path}: {len(found)} impacts found, {len(table)} true")
            continue
        rows.append(pd.DataFrame({c: found[c] for c in table.columns if c in found}))
        rows[-1]["true_onset"] = table["onset [s]"]
        for column in ("peak_sensor_force [N]", "peak_contact_force [N]", "contact_time [s]"):
            rows[-1][f"err {column}"] = found[column] / table[column] - 1.0
        rows[-1]["raw error"] = table["peak_sensor_force [N]"] / table["peak_contact_force [N]"] - 1
    both = pd.concat(rows)
    return {
        "onset [us]": 1e6 * np.abs(both["onset [s]"] - both["true_onset"]).max(),
        "peak signal [%]": 100 * both["err peak_sensor_force [N]"].abs().max(),
        "peak contact force [%]": 100 * both["err peak_contact_force [N]"].abs().max(),
        "contact time [%]": 100 * both["err contact_time [s]"].abs().max(),
        "raw peak vs true force [%]": 100 * both["raw error"].mean(),
    }


ACCURACY_CASES = (
    # law, sample rate [Hz], noise [N]
    ("hard", 5e6, 0.005),
    ("hard", 5e6, 0.03),
    ("hard", 2e6, 0.03),
    ("hard", 1e6, 0.03),
    ("hard", 5e6, 0.15),
    ("fig6", 5e6, 0.05),
    ("soft", 2e6, 0.03),
    ("soft", 2e6, 0.1),
    ("hertz", 1e6, 0.005),
    ("hertz", 5e6, 0.03),
)
"""The accuracy table of docs/campaign.md: 8 impacts per case, 1.5-2.5 m/s."""


def accuracy_table():
    """Largest errors per case of :data:`ACCURACY_CASES` (one record of 8 impacts each)."""
    from dem_check.campaign.analysis import analyse_impact

    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    laws = {
        "hard": cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5),
        "fig6": config.law,
        "soft": load_config(ROOT / "data" / "traces" / "model_soft.toml").law,
        "hertz": load_config(ROOT / "data" / "traces" / "model_hertz.toml").law,
    }
    print("case                      found  noise/peak  onset[us]  signal  impulse  force  time")
    for law, rate, noise in ACCURACY_CASES:
        rng = np.random.default_rng(1)
        onsets = 1e-3 + np.cumsum(rng.uniform(3e-3, 6e-3, 8))
        trace, truth = synthetic_record(
            config.grain,
            config.sensor,
            laws[law],
            rng.uniform(1.5, 2.5, 8),
            onsets,
            length=onsets[-1] + 5e-3,
            sample_rate=rate,
            noise=noise,
        )
        found = find_impacts(trace, config.sensor)
        rows = pd.DataFrame(
            [analyse_impact(found, w, config.sensor, config.grain)[0] for w in found.impacts]
        )
        if len(rows) != len(truth) or (rows["status"] != "ok").any():
            print(f"{law} {rate:.0e} {noise}: {len(rows)} found, statuses {set(rows['status'])}")
            continue
        worst = {
            c: 100 * (rows[c] / truth[c] - 1).abs().max()
            for c in (
                "peak_sensor_force [N]",
                "impulse [N*s]",
                "peak_contact_force [N]",
                "contact_time [s]",
            )
        }
        onset = 1e6 * (rows["onset [s]"] - truth["onset [s]"]).abs().max()
        ratio = 100 * noise / truth["peak_sensor_force [N]"].mean()
        print(
            f"{law:<6}{rate / 1e6:>4.0f} MHz {noise:>6} N  {len(rows)}/{len(truth)}  "
            f"{ratio:>8.2f} %  {onset:>8.2f}  " + "  ".join(f"{v:5.2f}%" for v in worst.values())
        )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--samples", type=int, default=1_500_000, help="total samples")
    parser.add_argument("--impacts", type=int, default=20, help="impacts in all")
    parser.add_argument(
        "--accuracy", action="store_true", help="also print docs/campaign.md's accuracy table"
    )
    args = parser.parse_args()
    if args.accuracy:
        accuracy_table()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        config, truth = write_records(folder, args.samples, args.impacts)
        paths = list(truth)
        _, read_time = timed(lambda: [read_trace(p, sensitivity=SENSITIVITY) for p in paths])
        _, floor_time = timed(reference_reconstruction, paths, config.sensor)
        result, total = timed(
            run_campaign,
            paths,
            config.sensor,
            config.grain,
            sensitivity=SENSITIVITY,
            out=folder / "out",
        )
        report_size = (folder / "out" / "report.html").stat().st_size
    print(f"campaign: {args.samples} samples in {len(paths)} files, {len(result.impacts)} impacts")
    print(f"{'stage':<34}{'time [s]':>10}")
    for stage, seconds in result.timings.items():
        print(f"  {stage:<32}{seconds:>10.2f}")
    print(f"  {'total run_campaign':<32}{total:>10.2f}   (goal < 60 s)")
    print(
        f"  {'reference: read_trace alone':<32}{read_time:>10.2f}   ratio {total / read_time:.1f}"
    )
    print(
        f"  {'reference: detect + reconstruct':<32}{floor_time:>10.2f}   "
        f"ratio {total / floor_time:.2f}"
    )
    print(f"  report.html: {report_size / 1e6:.2f} MB")
    print("largest errors against the truth:")
    for name, value in accuracy(result, truth).items():
        print(f"  {name:<32}{value:>10.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
