"""Benchmark: campaigns on realistic records (issue 22), speed and accuracy.

Records of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz disc
sensor, contact 100 us) built by ``dem_check.campaign.realistic_record`` with every
laboratory effect on (``Effects.everything``: 1/f noise, drift, hum, crosstalk, a 16-bit
ADC, offset steps, bounces; white noise 1 % of the 3 N peak at 2 m/s).

- ``--speed``: one record of 1.5 million samples at 5 MHz with 20 impacts and their
  bounces, written as HDF5 (not timed); ``run_campaign`` on it, timed, against reading
  the file alone (same run).
- ``--accuracy``: 4 records of 4 impacts (and their bounces) per configuration (1, 2 and
  5 MHz without crosstalk, 2 MHz with crosstalk of 2 % of each peak), impacts of
  0.5-2.5 m/s, clipping off (a clipped impact is flagged, not measured) and offset steps
  off (docs/campaign.md);
  the largest and 95th-percentile errors of the analysed impacts against the model's
  truth, by significance (peak over noise), and the count of impacts found, missed and
  invented.

Run: ``.venv/bin/python benchmarks/bench_realistic.py [--speed] [--accuracy]``
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.config import load_config
from dem_check import read_trace, write_trace
from dem_check.campaign import Effects, realistic_record, run_campaign

ROOT = Path(__file__).resolve().parents[1]
NOISE = 0.03  # [N]
RECORDS = 4  # per configuration
MATCH = 60e-6  # [s] a detected onset this close to a true one is that impact


def hard():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    return config.grain, config.sensor, cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)


def speed():
    grain, sensor, law = hard()
    rate, length = 5e6, 0.3  # 1.5 million samples
    rng = np.random.default_rng(7)
    onsets = np.arange(20) * 14e-3 + 2e-3 + rng.uniform(0, 5e-3, 20)
    record = realistic_record(
        grain,
        sensor,
        law,
        rng.uniform(1.0, 2.5, 20),
        onsets,
        length=length,
        sample_rate=rate,
        noise=NOISE,
        effects=Effects.everything(NOISE, 3.0),
        seed=7,
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "day.h5"
        write_trace(path, record.trace, "hdf5", name="day/sensor", time="attrs")
        started = time.perf_counter()
        read_trace(path)
        read = time.perf_counter() - started
        started, cpu = time.perf_counter(), time.process_time()
        result = run_campaign([path], sensor, grain)
        total, cpu = time.perf_counter() - started, time.process_time() - cpu
    print(f"{len(record.trace)} samples, {len(record.truth)} true impacts (with bounces)")
    print(f"run_campaign: {total:.2f} s ({total / read:.0f} x reading the file, {read:.3f} s)")
    print(f"run_campaign CPU time of this process: {cpu:.2f} s (wall time on a loaded machine")
    print("  is larger; set OPENBLAS_NUM_THREADS=1 on a shared machine)")
    for stage, seconds in result.timings.items():
        print(f"  {stage}: {seconds:.2f} s")
    print(result.impacts["status"].value_counts().to_string())


def _records(rate, seeds, crosstalk):
    grain, sensor, law = hard()
    for seed in seeds:
        rng = np.random.default_rng(seed)
        onsets = 1e-3 + np.cumsum(rng.uniform(4e-3, 7e-3, 4)) - 4e-3
        effects = Effects.everything(NOISE, 3.0, full_scale=None, steps=0, crosstalk=crosstalk)
        yield realistic_record(
            grain,
            sensor,
            law,
            rng.uniform(0.5, 2.5, 4),
            onsets,
            length=onsets[-1] + 6e-3,
            sample_rate=rate,
            noise=NOISE,
            effects=effects,
            seed=seed,
        )


def accuracy():
    grain, sensor, _ = hard()
    rows, counts = [], {"found": 0, "missed": 0, "invented": 0}
    with tempfile.TemporaryDirectory() as folder:
        for rate, crosstalk in ((1e6, 0.0), (2e6, 0.0), (2e6, 0.02), (5e6, 0.0)):
            for k, record in enumerate(_records(rate, range(RECORDS), crosstalk)):
                path = Path(folder) / f"r{int(rate)}_{k}.h5"
                write_trace(path, record.trace, "hdf5", name="r/sensor", time="attrs")
                impacts = run_campaign([path], sensor, grain).impacts
                truth = record.truth
                for _, row in impacts.iterrows():
                    gap = np.abs(truth["onset [s]"] - row["onset [s]"])
                    if gap.min() > MATCH:
                        counts["invented"] += 1
                        continue
                    true = truth.iloc[int(gap.argmin())]
                    rows.append(
                        {
                            "rate [MHz]": rate / 1e6,
                            "crosstalk": crosstalk,
                            "status": row["status"],
                            "significance": true["peak_sensor_force [N]"] / record.noise,
                            "onset [samples]": (row["onset [s]"] - true["onset [s]"]) * rate,
                            "peak_sensor_force": row["peak_sensor_force [N]"]
                            / true["peak_sensor_force [N]"]
                            - 1,
                            "impulse": row["impulse [N*s]"] / true["impulse [N*s]"] - 1,
                            "peak_force": row["peak_contact_force [N]"]
                            / true["peak_contact_force [N]"]
                            - 1,
                            "contact_time": row["contact_time [s]"] / true["contact_time [s]"] - 1,
                        }
                    )
                found = impacts["onset [s]"].to_numpy()
                for onset in truth["onset [s]"]:
                    hit = found.size and np.abs(found - onset).min() <= MATCH
                    counts["found" if hit else "missed"] += 1
    table = pd.DataFrame(rows)
    print(counts)
    print(table["status"].value_counts().to_string())
    ok = table[table["status"].isin(["ok", "short pre-trigger"])].copy()
    ok["band"] = pd.cut(ok["significance"], [0, 10, 30, 100, np.inf])
    columns = ["onset [samples]", "peak_sensor_force", "impulse", "peak_force", "contact_time"]
    keys = ["rate [MHz]", "crosstalk", "band"]
    summary = ok.groupby(keys, observed=True)[columns].agg(lambda v: np.nanmax(np.abs(v)))
    summary["impacts"] = ok.groupby(keys, observed=True).size()
    print("largest errors (onset in samples, the others relative):")
    print(summary.round(3).to_string())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speed", action="store_true")
    parser.add_argument("--accuracy", action="store_true")
    args = parser.parse_args()
    if args.speed or not args.accuracy:
        speed()
    if args.accuracy or not args.speed:
        accuracy()


if __name__ == "__main__":
    main()
