"""Benchmark: onset estimates on realistic records (issue 22's "onsets within 2 samples").

Records of the paper's 5 mm grain on the 40 kHz disc sensor, with a linear contact (the
hard test grain, k2 = 4e4 N/m, c2 = 0.5 N*s/m: its force steps at the touch) and with a
Hertz contact (k_hertz = 1.5e6 N/m**1.5: its force rises as t**1.5), built by
``dem_check.campaign.realistic_record``: 4 records of 4 impacts of 0.5-2.5 m/s and their
bounces per configuration, every effect of ``Effects.everything`` but crosstalk,
clipping and offset steps (``--all``: with them). Onsets of the analysed impacts against
the model's first touch, by significance (peak over the random noise): the detector's
5-sigma crossing (``crossing``) and the whole-lobe fit with the contact family read per
record (``lobe``, what ``find_impacts`` reports), largest and 95th-percentile errors in
samples and microseconds, and the median Cramér-Rao bound of the onset under the
record's white noise (``bound``; its 1/f noise adds to it), also scaled to 30 sigma; the
median stated uncertainty (``uncertainty``: the fitted onset's standard deviation under
the record's white and 1/f noise, the campaign's ``onset_uncertainty [s]``) and the
fraction of errors within two of it (``within 2``).

``--law``, ``--rate``: a subset; ``--noise-model white``: the lobe fit without whitening
(as before it; the bound is then the white noise's).

Run: ``.venv/bin/python benchmarks/bench_onsets.py [--all] [--records N] [--law NAME]
[--rate HZ] [--noise-model white]``
"""

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.inverse.lobe_onset import fit_lobe
from contactlab.inverse.noise_colour import NOISE_MODELS
from dem_check.campaign import find_impacts, onsets
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.local import record_noise
from dem_check.campaign.onsets import _lobe, record_onsets

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
import bench_realistic  # noqa: E402  (the records of bench_realistic.py --accuracy)

MATCH = 60e-6  # [s] a detected onset this close to a true one is that impact


def setup():
    _, sensor, linear = bench_realistic.hard()
    return sensor, {"linear": linear, "hertz": cl.laws.Hertz(k_hertz=1.5e6)}


def records(law, rate, seeds, everything):
    # Effects.everything's levels: a 16-bit ADC at 1.2 times the 3 N peak, two 8-sigma steps
    changes = {"full_scale": 3.6, "steps": 2} if everything else {"crosstalk": 0.0}
    return bench_realistic._records(rate, seeds, changes, law)


def errors(record, sensor, rate):
    """Per analysed impact: the onsets' errors [samples], the bound [samples] and its
    significance."""
    found = find_impacts(record.trace, sensor, fit_onsets=False)
    analysed = [w for w in found.impacts if w.status in ANALYSED]
    noise = record_noise(found, sensor)
    fitted, notes, family, damping, spreads, _ = record_onsets(found, analysed, sensor, noise)
    truth, rows = record.truth, []
    for window, onset, note, spread in zip(analysed, fitted, notes, spreads, strict=True):
        gap = np.abs(truth["onset [s]"] - window.onset)
        if gap.min() > MATCH:
            continue
        true = truth.iloc[int(gap.argmin())]
        bound = np.nan
        if not note:  # the bound at the fit (the white noise of the record)
            t, y, guess, _, model = _lobe(found, window, sensor)
            fit = fit_lobe(t, y, sensor, guess, record.noise, family, damping, noise_model=model)
            bound = fit.bound * rate
        rows.append(
            {
                "significance": true["peak_sensor_force [N]"] / record.noise,
                "crossing": (window.onset - true["onset [s]"]) * rate,
                "lobe": (onset - true["onset [s]"]) * rate,
                "bound": bound,
                "uncertainty": spread * rate,
                "fallback": bool(note),
                "family": f"{family} {damping}",
            }
        )
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--all", action="store_true", help="crosstalk, clipping, steps on")
    parser.add_argument("--records", type=int, default=4)
    parser.add_argument("--law", action="append", choices=["linear", "hertz"])
    parser.add_argument("--rate", action="append", type=float, help="[Hz]")
    parser.add_argument(
        "--noise-model",
        choices=list(NOISE_MODELS),
        default=onsets.NOISE_MODEL,
        help="the lobe fit's noise model (white: as before the whitened fit)",
    )
    args = parser.parse_args()
    onsets.NOISE_MODEL = args.noise_model
    print(f"lobe fit's noise model: {args.noise_model}")
    sensor, laws = setup()
    rows = []
    for name, law in laws.items():
        if args.law and name not in args.law:
            continue
        for rate in args.rate or (1e6, 2e6, 5e6):
            for record in records(law, rate, range(args.records), args.all):
                for row in errors(record, sensor, rate):
                    rows.append({"law": name, "rate [MHz]": rate / 1e6, **row})
    table = pd.DataFrame(rows)
    table["band"] = pd.cut(table["significance"], [0, 10, 30, 100, np.inf])
    keys = ["law", "rate [MHz]", "band"]
    columns = ["crossing", "lobe"]
    grouped = table.groupby(keys, observed=True)[columns]
    largest = grouped.agg(lambda v: np.nanmax(np.abs(v)))
    high = grouped.agg(lambda v: np.nanpercentile(np.abs(v), 95))
    megahertz = largest.index.get_level_values("rate [MHz]").to_numpy()[:, None]
    for name, worst in (("largest", largest), ("95th percentile", high)):
        print(f"{name} |error| [samples]:")
        shown = worst.copy()
        if name == "largest":
            shown["impacts"] = table.groupby(keys, observed=True).size()
            shown["bound (median)"] = table.groupby(keys, observed=True)["bound"].median()
            # the bound scales as noise over peak for one shape: each impact's at 30 sigma
            at30 = table["bound"] * table["significance"] / 30.0
            shown["bound at 30 sigma"] = at30.groupby(
                [table[k] for k in keys], observed=True
            ).median()
            shown["fallbacks"] = table.groupby(keys, observed=True)["fallback"].sum()
            grouping = table.groupby(keys, observed=True)
            shown["uncertainty (median)"] = grouping["uncertainty"].median()
            ratio = (table["lobe"] / table["uncertainty"]).abs()
            within = (ratio <= 2.0).groupby([table[k] for k in keys], observed=True)
            shown["within 2"] = within.mean()
        print(shown.round(2).to_string())
        print(f"{name} |error| [us]:")
        print((worst / megahertz).round(3).to_string())
    print("mean error [samples] (sign: late > 0):")
    print(grouped.mean().round(2).to_string())
    print("record families and dampings read:")
    print(table.groupby(["law", "rate [MHz]"])["family"].agg(lambda v: sorted(set(v))).to_string())


if __name__ == "__main__":
    main()
