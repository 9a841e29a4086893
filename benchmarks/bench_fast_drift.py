"""Benchmark: records that start at their impact under fast drift (issue 22).

Records of the hard test grain (``bench_steps.hard``) whose first impact is at the
record's first sample or two samples in (no pre-trigger), at 1, 2 or 5 MHz, 6-20 ms
long, 1-3 impacts of 0.3-2.5 m/s with bounces of 0.25-0.5 of the velocity 1.5-3 ms later,
white noise 0.03 N, 1/f noise of 0-2 sigma, drift of 20-50 sigma (over so short a record,
hundreds of N/s), hum of 0-1.5 sigma and a 12-bit ADC at 0.8-3 times the largest peak.
The detection of ``find_impacts`` with the running baseline fitted after the impact at
the start and extrapolated back under it (``contactlab._head_level``, the default) and,
in the same run, with the block levels alone (as before: ``--compare``). Reported: the
records where something went wrong (an invented or a missed clear impact, judged as
``bench_steps.judge``), and the baseline under the first impact against the record
without its impacts: the largest distance from the drift and hum over the first 0.2 ms,
in noise sigmas (the 1/f noise's slow part is noise: no baseline reads it under a pulse).

Run: ``.venv/bin/python benchmarks/bench_fast_drift.py [--records N] [--compare]``
"""

import argparse
import sys
import time
from pathlib import Path
from unittest import mock

import numpy as np
from bench_steps import hard, judge

import dem_check.campaign.noise as noise_module
from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.drawn_records import NOISE

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "dem_check" / "campaign"))
# the test's drift and hum alone (the generator's draws replayed)
from test_realistic_detection import _drift_and_hum as drift_and_hum


def record_at_start(seed):
    """One record that starts at its impact (module docstring) and its effects."""
    rng = np.random.default_rng(seed)
    rate = float(rng.choice([1e6, 2e6, 5e6]))
    count = int(rng.integers(1, 4))
    delay = rng.uniform(1.5e-3, 3e-3)
    gaps = rng.uniform(delay + 1.5e-3, 8e-3, count)
    first = float(rng.choice([0.0, 2.0 / rate]))
    onsets = first + np.concatenate([[0.0], np.cumsum(gaps[:-1])])
    velocities = rng.uniform(0.3, 2.5, count)
    effects = Effects(
        pink=rng.uniform(0.0, 2.0) * NOISE,
        drift=rng.uniform(20.0, 50.0) * NOISE,
        hum=rng.uniform(0.0, 1.5) * NOISE,
        full_scale=rng.uniform(0.8, 3.0) * 3.0 * 2.5 / 2.0,
        bits=12,
        bounce=rng.uniform(0.25, 0.5),
        bounce_delay=delay,
    )
    sampling = {"length": float(onsets[-1] + 6e-3), "sample_rate": rate}
    record = realistic_record(
        *hard(), velocities, onsets, **sampling, noise=NOISE, effects=effects, seed=seed
    )
    return record, effects, drift_and_hum(record, effects, seed)


def baseline_error(record, truth, found):
    """Largest distance of the detection's baseline from the drift and hum over the
    first impact's first 0.2 ms [noise sigmas]."""
    level = np.asarray(record.trace.values) - np.asarray(found.signal.values)
    under = np.asarray(record.trace.t) < 0.2e-3
    return float(np.max(np.abs(level - truth)[under])) / record.noise


def run(records, variant):
    _, sensor, _ = hard()
    failing, kinds, errors, cpu = [], {"invented": 0, "missed": 0}, [], 0.0
    for seed in range(records):
        record, effects, clean = record_at_start(seed)
        started = time.process_time()
        found = find_impacts(record.trace, sensor)
        cpu += time.process_time() - started
        wrong = [w for w in judge(record, effects, found) if w[0] in kinds]
        for kind, _ in wrong:
            kinds[kind] += 1
        if wrong:
            failing.append((seed, wrong))
        errors.append(baseline_error(record, clean, found))
    errors = np.array(errors)
    print(
        f"{variant}: {len(failing)} of {records} records wrong ({kinds}); baseline under "
        f"the first impact: median {np.median(errors):.2f}, 95th percentile "
        f"{np.percentile(errors, 95):.2f}, largest {errors.max():.2f} noise sigmas; "
        f"detection {cpu:.1f} s of CPU"
    )
    for seed, wrong in failing:
        print(f"  seed {seed}: {wrong}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=60)
    parser.add_argument("--compare", action="store_true")
    args = parser.parse_args()
    run(args.records, "head fit")
    if args.compare:
        with mock.patch.object(noise_module, "_head", lambda mask, longest: 0):
            run(args.records, "block levels alone")


if __name__ == "__main__":
    main()
