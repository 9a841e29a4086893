"""Benchmark: a run at a record's edge, a level step or an impact's lobe (issue 22).

Two families of records of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40
kHz disc sensor, contact 100 us; white noise 0.03 N, 12-bit ADC) at 1, 2 and 5 MHz:

- **start**: one impact at the record's first sample, 0.2-0.3 m/s (weak, 10-15 noise
  sigmas) or 1-2 m/s, 1/f noise of 1-2 sigma; or no impact there and an offset step of
  8-15 sigma, up or down, 0.02-0.15 ms after the start (an impact 1 ms in);
- **end**: an offset step of 5-10 sigma, up or down, 3-24 us before the last sample
  (an impact 1 ms in), 1/f noise of 1-2 sigma;
- **box** (only with ``--families box``): two offset steps of 10-30 sigma, up or down,
  0.03-0.22 ms after the start, over an impact of 0.3-1 m/s at the first sample, 1/f
  noise of one sigma, 3 ms at 1, 2 or 5 MHz (drawn with the seed; ``--records`` of them
  per rate): the boxes of :mod:`dem_check.campaign.edge_boxes`.

Counted as ``tests/dem_check/campaign/test_realistic_detection.py`` asserts: a record
fails when an impact row lies more than 60 us from every true onset, a true impact has
no row within 60 us, or a step row lies more than 60 us from every true step; and how
many true steps got a row. Prints the failing records and the CPU time of
``find_impacts``.

Run: ``.venv/bin/python benchmarks/bench_edges.py [--records 20] [--families start end
box]`` (records per family and rate; default: start and end).
"""

import argparse
import time
from pathlib import Path

import numpy as np

import contactlab as cl
from contactlab.config import load_config
from dem_check.campaign import Effects, find_impacts, realistic_record

ROOT = Path(__file__).resolve().parents[1]
NOISE = 0.03  # [N]
MATCH = 60e-6  # [s]
LENGTH = 6e-3  # [s]


def hard():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    return config.grain, config.sensor, cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)


def edge_record(family, rate, seed):
    """One record of ``family`` ("start" or "end", module docstring)."""
    rng = np.random.default_rng(seed)
    if family == "box":
        return box_record(rate, rng, seed)
    pink = rng.uniform(1.0, 2.0) * NOISE
    sign = rng.choice((-1.0, 1.0))
    offsets, velocities, onsets = (), [1.0], [1e-3]
    if family == "end":
        at = LENGTH - rng.uniform(3e-6, 24e-6)
        offsets = ((at, sign * rng.uniform(5.0, 10.0) * NOISE),)
    elif seed % 2:  # an impact at the first sample
        weak = seed % 4 == 1
        velocities, onsets = [rng.uniform(0.2, 0.3) if weak else rng.uniform(1.0, 2.0)], [0.0]
    else:
        offsets = ((rng.uniform(0.02e-3, 0.15e-3), sign * rng.uniform(8.0, 15.0) * NOISE),)
    effects = Effects(pink=pink, full_scale=3.75, bits=12, offsets=offsets)
    sampling = {"length": LENGTH, "sample_rate": rate, "noise": NOISE, "seed": seed}
    return realistic_record(*hard(), velocities, np.array(onsets), **sampling, effects=effects)


def box_record(rate, rng, seed):
    """A box of two steps over an impact at the first sample (module docstring)."""
    velocity = rng.uniform(0.3, 1.0)
    times = np.sort(rng.uniform(0.03e-3, 0.22e-3, 2))
    heights = rng.choice((-1.0, 1.0), 2) * rng.uniform(10.0, 30.0, 2) * NOISE
    effects = Effects(pink=NOISE, offsets=tuple(zip(times, heights, strict=True)))
    sampling = {"length": 3e-3, "sample_rate": rate, "noise": NOISE, "seed": seed}
    return realistic_record(*hard(), [velocity], np.array([0.0]), **sampling, effects=effects)


def judge(record, found):
    """What went wrong: a list of strings."""
    truth = record.truth["onset [s]"].to_numpy()
    wrong = []
    for w in found.impacts:
        if not truth.size or np.abs(truth - w.onset).min() > MATCH:
            wrong.append(f"invented {w.status} at {w.onset:.6g} s ({w.peak:.3g} N)")
    onsets = np.array([w.onset for w in found.impacts])
    for at in truth:
        if not onsets.size or np.abs(onsets - at).min() > MATCH:
            wrong.append(f"missed the impact at {at:.6g} s")
    for s in found.steps:
        if not record.step_times.size or np.abs(record.step_times - s.onset).min() > MATCH:
            wrong.append(f"invented step at {s.onset:.6g} s ({s.peak:.3g} N)")
    return wrong


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=20)
    parser.add_argument(
        "--families", nargs="+", default=["start", "end"], choices=["start", "end", "box"]
    )
    args = parser.parse_args()
    _, sensor, _ = hard()
    for family in args.families:
        failing, cpu, steps, rows = 0, 0.0, 0, 0
        for rate in (1e6, 2e6, 5e6):
            for seed in range(args.records):
                record = edge_record(family, rate, seed)
                started = time.process_time()
                found = find_impacts(record.trace, sensor)
                cpu += time.process_time() - started
                steps += record.step_times.size
                rows += sum(
                    bool(found.steps) and min(abs(s.onset - at) for s in found.steps) <= MATCH
                    for at in record.step_times
                )
                wrong = judge(record, found)
                if wrong:
                    failing += 1
                    print(f"{family} {rate / 1e6:g} MHz seed {seed}: " + "; ".join(wrong))
        total = 3 * args.records
        print(
            f"{family}: {failing} of {total} records failing, {rows} of {steps} steps listed, "
            f"find_impacts CPU {cpu:.1f} s"
        )


if __name__ == "__main__":
    main()
