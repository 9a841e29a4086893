"""Benchmark: detection under DC offset steps and strong drift (issue 22), a hard mix.

100 records of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz disc
sensor, contact 100 us; white noise 0.03 N, 1 % of the 3 N peak at 2 m/s) at 1, 2 and
5 MHz, 1-4 impacts of 0.2-2.5 m/s with bounces (40 % of the velocity, 1.5-3 ms later),
every other effect of ``Effects.everything`` on (1/f noise as large as the white noise,
hum of 1.5 sigma, crosstalk of 2 %, a 16-bit ADC clipping at 1.2 times the largest
peak plus the drift and the steps), drift of 20-50 noise sigmas (10 when the record
starts at its impact: the known limit of docs/campaign.md) and **two offset steps** of
3-30 noise sigmas, up or down, each at a random place of one kind: anywhere, within
0.2 ms of the record's start or end, up to 0.3 ms before an impact, or up to 0.3 ms
after one (in its ringing).

Counted, as ``tests/dem_check/campaign/test_realistic_detection.py`` asserts them:
*invented* (an impact row more than 60 us from every true onset), *missed* (a true
impact of at least 10 noise sigmas, the structure's ringing counted, with no row within
60 us), and for the step rows (status ``"offset step"``) how many lie within 60 us of a
true step. Prints the failing records (seed, what went wrong) and the CPU time.

Run: ``.venv/bin/python benchmarks/bench_steps.py [--records 100] [--seeds 14 15 ...]``
(``--seeds``: only those records, as numbered in the full run).
"""

import argparse
import time
from pathlib import Path

import numpy as np

import contactlab as cl
from contactlab.config import load_config
from dem_check.campaign import find_impacts
from dem_check.campaign.drawn_records import hard_mix as draw_hard_mix
from dem_check.campaign.records import ringing_at_onsets

ROOT = Path(__file__).resolve().parents[1]
MATCH = 60e-6  # [s] a detected onset this close to a true one is that impact
CLEAR = 10.0  # true impacts of at least this many noise sigmas must be found


def hard():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    return config.grain, config.sensor, cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)


def hard_mix(seed):
    """One record of the hard mix (:func:`dem_check.campaign.drawn_records.hard_mix`) of the
    hard grain, and its effects."""
    return draw_hard_mix(seed, *hard())


def judge(record, effects, found):
    """What went wrong on one record: a list of ``(kind, detail)``."""
    true_onsets = record.truth["onset [s]"].to_numpy()
    wrong = []
    for window in found.steps:
        steps = np.abs(record.step_times - window.onset)
        if not steps.size or steps.min() > MATCH:
            wrong.append(("invented step", f"{window.onset:.6g} s {window.reason}"))
    for window in found.impacts:
        near = np.abs(true_onsets - window.onset).min() if true_onsets.size else np.inf
        if near > MATCH:
            wrong.append(("invented", f"{window.status} at {window.onset:.6g} s"))
    onsets = np.array([w.onset for w in found.impacts])
    structure = ringing_at_onsets(record.truth, effects)
    for (_, row), ring in zip(record.truth.iterrows(), structure, strict=True):
        noise = np.hypot(record.noise, ring / np.sqrt(2.0))
        if row["peak_sensor_force [N]"] >= CLEAR * noise:
            if not onsets.size or np.abs(onsets - row["onset [s]"]).min() > MATCH:
                what = f"{row['onset [s]']:.6g} s, {row['velocity [m/s]']:.3g} m/s"
                wrong.append(("missed", what))
    return wrong


def drawn_seeds(doc, records):
    """The seeds of the records a drawing benchmark reads: ``--records N`` (default
    ``records``) from 0, or ``--seeds`` listed; ``doc``'s first paragraph is the help."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=records)
    parser.add_argument("--seeds", type=int, nargs="+", help="only these records (seeds)")
    args = parser.parse_args()
    return args.seeds if args.seeds else range(args.records)


def main():
    seeds = drawn_seeds(__doc__, 100)
    _, sensor, _ = hard()
    counts = {"invented": 0, "invented step": 0, "missed": 0, "steps found": 0, "steps": 0}
    cpu, failing = 0.0, 0
    for seed in seeds:
        record, effects = hard_mix(seed)
        started = time.process_time()
        found = find_impacts(record.trace, sensor)
        cpu += time.process_time() - started
        wrong = judge(record, effects, found)
        for kind, _ in wrong:
            counts[kind] += 1
        rows = [w.onset for w in found.steps]
        counts["steps"] += record.step_times.size
        counts["steps found"] += sum(
            bool(rows) and np.abs(np.array(rows) - at).min() <= MATCH for at in record.step_times
        )
        if wrong:
            failing += 1
            steps = ", ".join(f"{a * 1e3:.3f} ms" for a in record.step_times)
            print(f"seed {seed}: steps at {steps}, truth {record.truth['onset [s]'].tolist()}")
            for kind, detail in wrong:
                print(f"    {kind}: {detail}")
    print(counts, f"records failing: {failing} of {len(seeds)}")
    print(f"find_impacts CPU time: {cpu:.2f} s")


if __name__ == "__main__":
    main()
