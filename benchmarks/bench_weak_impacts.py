"""Benchmark: a weak impact in a strong one's ringing (issue 22).

Records of :func:`dem_check.campaign.drawn_records.weak_in_ringing`: the hard test grain
(k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz disc sensor, contact 100 us; white noise
0.03 N) at 1, 2 or 5 MHz, a 1-2.5 m/s impact at 1 ms and a weak one (10-15 noise sigmas,
the structure's ringing counted) 0.3-1.5 ms later, every effect but offset steps on at
random levels over the realistic sweep's ranges. Each record is read twice: as drawn
(the weak impact must be found, within 60 us, and nothing invented) and without the
weak impact (nothing may be found in the strong one's ringing).

Counted as ``bench_steps.py`` counts them (:func:`bench_steps.judge`), by the weak
impact's delay (0.2 ms bins). Prints the failing records and the CPU time.

Run: ``.venv/bin/python benchmarks/bench_weak_impacts.py [--records 200] [--seeds 3 17 ...]``
"""

import time

from bench_steps import drawn_seeds, hard, judge

from dem_check.campaign import find_impacts
from dem_check.campaign.drawn_records import weak_in_ringing

BIN = 0.2e-3
"""Width of the delay bins [s]."""


def main():
    seeds = drawn_seeds(__doc__, 200)
    setup = hard()
    bins, alone_wrong, cpu = {}, {}, 0.0
    for seed in seeds:
        for alone in (False, True):
            record, effects = weak_in_ringing(seed, *setup, alone=alone)
            started = time.process_time()
            found = find_impacts(record.trace, setup[1])
            cpu += time.process_time() - started
            wrong = judge(record, effects, found)
            rows = [(w.status, round(w.onset * 1e3, 4)) for w in found.impacts]
            if alone:
                for kind, _ in wrong:
                    alone_wrong[kind] = alone_wrong.get(kind, 0) + 1
                if wrong:
                    print(f"seed {seed} without the weak impact: {wrong}; rows {rows}")
                continue
            onsets = record.truth["onset [s]"].to_numpy()
            delay = onsets[1] - onsets[0]
            counts = bins.setdefault(int(delay // BIN), {"records": 0, "missed": 0, "invented": 0})
            counts["records"] += 1
            for kind, _ in wrong:
                counts[kind] = counts.get(kind, 0) + 1
            if wrong:
                rate = 1.0 / float(record.trace.t[1] - record.trace.t[0])
                print(
                    f"seed {seed}: {rate / 1e6:g} MHz, delay {delay * 1e3:.3f} ms: {wrong}; "
                    f"rows {rows}"
                )
    total = {"records": 0, "missed": 0, "invented": 0}
    for k in sorted(bins):
        low = k * BIN * 1e3
        print(f"delay {low:.1f}-{low + BIN * 1e3:.1f} ms: {bins[k]}")
        for name, count in bins[k].items():
            total[name] = total.get(name, 0) + count
    print(f"all: {total}; without the weak impact: {alone_wrong or 'nothing wrong'}")
    print(f"find_impacts CPU time: {cpu:.2f} s")


if __name__ == "__main__":
    main()
