"""Benchmark: onset estimates on realistic records (issue 22's "onsets within 2 samples").

Records of the paper's 5 mm grain on the 40 kHz disc sensor, with a linear contact (the
hard test grain, k2 = 4e4 N/m, c2 = 0.5 N*s/m: its force steps at the touch) and with a
Hertz contact (k_hertz = 1.5e6 N/m**1.5: its force rises as t**1.5), built by
``dem_check.campaign.realistic_record``: 4 records of 4 impacts of 0.5-2.5 m/s and their
bounces per configuration, every effect of ``Effects.everything`` but crosstalk,
clipping and offset steps (``--all``: with them). Onsets of the analysed impacts against
the model's first touch, by significance (peak over the random noise): the detector's
5-sigma crossing (``crossing``), the sensor-response fit with the exponent chosen per
impact (``own``) and per record (``record``, what ``find_impacts`` reports), largest and
95th-percentile errors in samples and microseconds.

Run: ``.venv/bin/python benchmarks/bench_onsets.py [--all] [--records N]``
"""

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.config import load_config
from contactlab.inverse.onset import BENDS, EXPONENTS
from dem_check.campaign import Effects, find_impacts, realistic_record
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.onsets import record_onsets

ROOT = Path(__file__).resolve().parents[1]
NOISE = 0.03  # [N] white noise, 1 % of the hard grain's 3 N peak at 2 m/s
MATCH = 60e-6  # [s] a detected onset this close to a true one is that impact


def setup():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    laws = {
        "linear": cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5),
        "hertz": cl.laws.Hertz(k_hertz=1.5e6),
    }
    return config.grain, config.sensor, laws


def records(grain, sensor, law, rate, seeds, everything):
    for seed in seeds:
        rng = np.random.default_rng(seed)
        onsets = 1e-3 + np.cumsum(rng.uniform(4e-3, 7e-3, 4)) - 4e-3
        changes = {} if everything else {"crosstalk": 0.0, "full_scale": None, "steps": 0}
        effects = Effects.everything(NOISE, 3.0, **changes)
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


def errors(record, sensor, rate):
    """Per analysed impact: the three onsets' errors [samples] and its significance."""
    found = find_impacts(record.trace, sensor, fit_onsets=False)
    analysed = [w for w in found.impacts if w.status in ANALYSED]
    shared, q, bend = record_onsets(found, analysed, sensor)
    truth, rows = record.truth, []
    for window, onset in zip(analysed, shared, strict=True):
        gap = np.abs(truth["onset [s]"] - window.onset)
        if gap.min() > MATCH:
            continue
        true = truth.iloc[int(gap.argmin())]
        rows.append(
            {
                "significance": true["peak_sensor_force [N]"] / record.noise,
                "crossing": (window.onset - true["onset [s]"]) * rate,
                "record": (onset - true["onset [s]"]) * rate,
                "q": q,
                "bend": bend,
            }
        )
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--all", action="store_true", help="crosstalk, clipping, steps on")
    parser.add_argument("--records", type=int, default=4)
    args = parser.parse_args()
    grain, sensor, laws = setup()
    rows = []
    for name, law in laws.items():
        for rate in (1e6, 2e6, 5e6):
            for record in records(grain, sensor, law, rate, range(args.records), args.all):
                for row in errors(record, sensor, rate):
                    rows.append({"law": name, "rate [MHz]": rate / 1e6, **row})
    table = pd.DataFrame(rows)
    table["band"] = pd.cut(table["significance"], [0, 10, 30, 100, np.inf])
    keys = ["law", "rate [MHz]", "band"]
    columns = ["crossing", "record"]
    grouped = table.groupby(keys, observed=True)[columns]
    print(f"exponents tried: {EXPONENTS}, bends {BENDS}")
    print("largest |error| [samples]:")
    largest = grouped.agg(lambda v: np.nanmax(np.abs(v)))
    largest["impacts"] = table.groupby(keys, observed=True).size()
    print(largest.round(2).to_string())
    print("95th percentile |error| [samples]:")
    print(grouped.agg(lambda v: np.nanpercentile(np.abs(v), 95)).round(2).to_string())
    print("mean error [samples] (sign: late > 0):")
    print(grouped.mean().round(2).to_string())
    print("record exponents and bends chosen:")
    print(
        table.groupby(["law", "rate [MHz]"])[["q", "bend"]]
        .agg(lambda v: sorted(set(np.round(v, 2))))
        .to_string()
    )


if __name__ == "__main__":
    main()
