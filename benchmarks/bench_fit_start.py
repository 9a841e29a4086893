"""Benchmark: ``fit_contact`` on records that start at their pulse (issue 22).

One impact of the hard grain (linear contact k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz
disc sensor, contact 100 us) at 2 m/s, 2 MHz, 4 ms, white noise 0.03 N (1 % of the 3 N
peak), with one laboratory effect (drift of 20 and 100 noise sigmas, crosstalk of 2 %,
1/f noise as large as the white noise), seeds 3-6; the pulse at the record's first
sample (no pre-trigger: the head level, the noise read after the fit's window) and,
for the same effect and seed, 1 ms into the record (a pre-trigger). The linear law is
fitted with the velocity given; printed: k2 and c2 against the truth, the reduced
chi-squared and the fit's consistency, per record, and the largest errors.

Run: ``.venv/bin/python benchmarks/bench_fit_start.py [--seeds 3 4 5 6]``
"""

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from bench_realistic import hard

from contactlab.inverse import fit_contact

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "dem_check" / "campaign"))
from test_realistic_single_trace import START_EFFECTS
from test_realistic_single_trace import _record as single  # the test's records

EFFECTS = {name: effects for name, (effects, _) in START_EFFECTS.items()}


def _fit(effects, onset, seed):
    grain, sensor, law = hard()
    record = single((grain, sensor, law), effects, onset, seed)
    t, y = np.asarray(record.trace.t), np.asarray(record.trace.values)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = fit_contact(t, y, grain, sensor, "linear", velocity=2.0)
    return {
        "k2": fit.parameters["stiffness"].value / law.stiffness - 1.0,
        "c2": fit.parameters["damping"].value / law.damping - 1.0,
        "chi2": fit.goodness["reduced_chi_squared [-]"],
        "consistent": fit.quality.consistent,
        "status": fit.baseline_status,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[3, 4, 5, 6])
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    started = time.process_time()
    rows = []
    for name, effects in EFFECTS.items():
        for seed in args.seeds:
            for where, onset in (("at the start", 0.0), ("1 ms in", 1e-3)):
                rows.append(
                    {"effect": name, "seed": seed, "pulse": where, **_fit(effects, onset, seed)}
                )
    table = pd.DataFrame(rows)
    pd.set_option("display.width", 200)
    print(table.round(4).to_string())
    largest = table.groupby(["effect", "pulse"], sort=False)[["k2", "c2"]].agg(
        lambda v: np.max(np.abs(v))
    )
    print("largest relative errors:")
    print(largest.round(4).to_string())
    cpu = time.process_time() - started
    print(f"CPU {cpu:.1f} s, load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
