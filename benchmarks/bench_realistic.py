"""Benchmark: campaigns on realistic records (issue 22), speed and accuracy.

Records of the hard test grain (k2 = 4e4 N/m, c2 = 0.5 N*s/m on the 40 kHz disc
sensor, contact 100 us) built by ``dem_check.campaign.realistic_record`` with every
laboratory effect on (``Effects.everything``: 1/f noise, drift, hum, crosstalk, a 16-bit
ADC, offset steps, bounces; white noise 1 % of the 3 N peak at 2 m/s).

- ``--speed``: one record of 1.5 million samples at 5 MHz with 20 impacts and their
  bounces, written as HDF5 (not timed); ``run_campaign`` on it, timed, against reading
  the file alone (same run).
- ``--accuracy``: 4 records of 4 impacts (and their bounces) per configuration (1, 2 and
  5 MHz without crosstalk, 2 MHz with crosstalk of 2 % of each peak, 1, 2 and 5 MHz with
  crosstalk and 1/f noise of 0.3 sigma), with the crosstalk removal of ``run_campaign``
  (``--no-crosstalk``: without it), impacts of
  0.5-2.5 m/s, clipping off (a clipped impact is flagged, not measured) and offset steps
  off (docs/campaign.md);
  the largest and 95th-percentile errors of the analysed impacts against the model's
  truth, by significance (peak over noise), and the count of impacts found, missed and
  invented. ``--noise-model white``: the reconstruction with the white-noise model it had
  before the coloured-noise one. ``--contact-edges level``: the contact read at 2 % of
  the reconstructed peak (and the dip rule), as before the significance rule.
  ``--crosstalk-only``: the configurations with crosstalk only; ``--no-refine``: the
  joint pencil's structure poles without their variable-projection refinement (as
  before it); ``--no-prediction``: the local baseline's ordinary line, without the noise
  under the pulse predicted from both sides (as before it); ``--records N``: records per
  configuration. Also printed: the root-mean-square error of the peak signal and
  impulse scaled to 30 sigma over the impacts above it (to set against
  ``bench_bounds.py``). ``--law hertz``: the records with a Hertz contact (:data:`HERTZ`)
  instead of the linear one; ``--linear-flanks``: the reconstructed contact's edges read
  with a line on each flank whatever the contact family the onset fit read on the record
  (as before the family was passed to the reconstruction); ``--largest-value``: the
  reconstructed peak as the regularised force's largest value and the contact time from
  its significance edges (``read_family=False``: as before the peak and contact were
  read from the family fitted to the signal). ``--law hertz-damped``: Tsuji's damped
  Hertz contact (:func:`hertz_damped`, restitution about that of the linear contact).
  ``--rows FILE``: every analysed impact's errors, the family read on its record and its
  velocity, written as CSV (to trace a row).

Run: ``.venv/bin/python benchmarks/bench_realistic.py [--speed] [--accuracy]
[--configuration NAME] [--crosstalk-only] [--no-crosstalk] [--no-refine]
[--no-prediction] [--records N]
[--noise-model white] [--contact-edges level] [--law hertz] [--linear-flanks]
[--largest-value] [--law hertz-damped] [--rows FILE]``
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
import contactlab.inverse.reconstruct as reconstruct_module
import dem_check.campaign.analysis as analysis_module
from contactlab.config import load_config
from dem_check import read_trace, write_trace
from dem_check.campaign import Effects, find_impacts, realistic_record, run_campaign
from dem_check.campaign.analysis import analyse_impact
from dem_check.campaign.detection import ANALYSED
from dem_check.campaign.drawn_records import accuracy_record
from dem_check.campaign.local import record_noise
from dem_check.campaign.structure import record_modes

ROOT = Path(__file__).resolve().parents[1]
NOISE = 0.03  # [N]
RECORDS = 4  # per configuration
MATCH = 60e-6  # [s] a detected onset this close to a true one is that impact


HERTZ = cl.laws.Hertz(k_hertz=1.5e6)
"""The Hertz contact of ``--law hertz`` (``bench_onsets.py``'s) on the hard grain and
sensor: its force rises as t**1.5."""

TSUJI_ALPHA = 0.394
"""Tsuji's damping factor of ``--law hertz-damped`` [-]: EDEM's mapping
``sqrt(5) (-ln e) / sqrt(pi**2 + ln(e)**2)`` for e = 0.57, the hard grain's linear
contact's restitution (``exp(-pi zeta / sqrt(1 - zeta**2))``, zeta = 0.177)."""


def hertz_damped(grain):
    """The damped Hertz contact of ``--law hertz-damped`` (Tsuji's, as EDEM and LIGGGHTS
    build it) on ``grain``: :data:`HERTZ`'s stiffness, ``eta = alpha sqrt(m kH)``
    [N*s/m**1.25] with alpha :data:`TSUJI_ALPHA` and m the grain's mass (the sensor is
    2000 times stiffer than the contact)."""
    eta = TSUJI_ALPHA * np.sqrt(grain.mass * HERTZ.k_hertz)
    return cl.laws.HertzDamped(k_hertz=HERTZ.k_hertz, damping=float(eta))


def hard():
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    return config.grain, config.sensor, cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5)


def speed_record():
    """The speed benchmark's record: 1.5 million samples at 5 MHz, 20 impacts of 1-2.5
    m/s and their bounces, every effect of ``Effects.everything``."""
    grain, sensor, law = hard()
    rate, length = 5e6, 0.3  # 1.5 million samples
    rng = np.random.default_rng(7)
    onsets = np.arange(20) * 14e-3 + 2e-3 + rng.uniform(0, 5e-3, 20)
    return realistic_record(
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


def speed(workers=1):
    grain, sensor, _ = hard()
    record = speed_record()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "day.h5"
        write_trace(path, record.trace, "hdf5", name="day/sensor", time="attrs")
        started = time.perf_counter()
        read_trace(path)
        read = time.perf_counter() - started
        started, cpu = time.perf_counter(), time.process_time()
        result = run_campaign([path], sensor, grain, workers=workers)
        total, cpu = time.perf_counter() - started, time.process_time() - cpu
        load = os.getloadavg()[0]
    print(f"load average before the run: {os.getloadavg()[0]:.1f} (1 min)")
    print(f"{len(record.trace)} samples, {len(record.truth)} true impacts (with bounces)")
    print(f"run_campaign: {total:.2f} s ({total / read:.0f} x reading the file, {read:.3f} s)")
    print(f"workers: {workers} (processes reading the impacts)")
    print(f"run_campaign CPU time of this process: {cpu:.2f} s (wall time on a loaded machine")
    print("  is larger; run_campaign keeps BLAS to one thread itself)")
    print(f"load average after the run: {load:.1f} (1 min)")
    for stage, seconds in result.timings.items():
        print(f"  {stage}: {seconds:.2f} s")
    print(result.impacts["status"].value_counts().to_string())


CONFIGURATIONS = {
    # name: (sample rate [Hz], Effects changes from Effects.everything), clipping and
    # offset steps off (a clipped impact is flagged, not measured; steps: docs/campaign.md)
    "1 MHz": (1e6, {"crosstalk": 0.0}),
    "2 MHz": (2e6, {"crosstalk": 0.0}),
    "5 MHz": (5e6, {"crosstalk": 0.0}),
    "2 MHz, 1/f 0.3": (2e6, {"crosstalk": 0.0, "pink": 0.3 * NOISE}),
    "2 MHz, no 1/f": (2e6, {"crosstalk": 0.0, "pink": 0.0}),
    "2 MHz, crosstalk 0.2 %": (2e6, {"crosstalk": 0.002}),
    "2 MHz, crosstalk 2 %": (2e6, {"crosstalk": 0.02}),
    "2 MHz, 1/f 0.3, crosstalk 2 %": (2e6, {"crosstalk": 0.02, "pink": 0.3 * NOISE}),
    "5 MHz, 1/f 0.3, crosstalk 2 %": (5e6, {"crosstalk": 0.02, "pink": 0.3 * NOISE}),
    "1 MHz, 1/f 0.3, crosstalk 2 %": (1e6, {"crosstalk": 0.02, "pink": 0.3 * NOISE}),
}
"""Configurations of ``--accuracy``: every effect of ``Effects.everything`` (1/f noise as
large as the white noise, drift of 20 sigma, hum of 1.5 sigma, bounces at 40 % of the
velocity 2 ms later) with these changes."""


def _records(rate, seeds, changes, law=None):
    """Records of 4 impacts of 0.5-2.5 m/s (and their bounces), one per seed: the hard
    grain's, or ``law``'s on its grain and sensor (``bench_onsets.py``)."""
    grain, sensor, hard_law = hard()
    law = hard_law if law is None else law
    for seed in seeds:
        yield accuracy_record(seed, grain, sensor, law, rate, NOISE, **changes)


def _errors(row, true, rate, noise):
    """Errors of one analysed impact against the model's truth."""

    def relative(column):
        return row.get(column, np.nan) / true[column] - 1.0

    return {
        "status": row["status"],
        "velocity [m/s]": true["velocity [m/s]"],
        "onset [s]": true["onset [s]"],
        "significance": true["peak_sensor_force [N]"] / noise,
        "onset [samples]": (row["onset [s]"] - true["onset [s]"]) * rate,
        "onset_uncertainty [samples]": row.get("onset_uncertainty [s]", np.nan) * rate,
        "peak_sensor_force": relative("peak_sensor_force [N]"),
        "impulse": relative("impulse [N*s]"),
        "peak_force": relative("peak_contact_force [N]"),
        "contact_time": relative("contact_time [s]"),
    }


def _analyse(record, sensor, grain, rate, counts, crosstalk=True, refine=True, predict=True):
    """Detection and analysis of one record in memory (what ``run_campaign`` does for
    each impact, without the files and the report); the errors of its impacts."""
    found = find_impacts(record.trace, sensor)
    levels = record_noise(found, sensor)
    modes = record_modes(found, sensor, refine=refine, noise=levels) if crosstalk else []
    noise = levels if predict else None
    truth, rows = record.truth, []
    for window in found.impacts:
        gap = np.abs(truth["onset [s]"] - window.onset)
        if gap.min() > MATCH:
            counts["invented"] += 1
            continue
        true = truth.iloc[int(gap.argmin())]
        if window.status not in ANALYSED:
            rows.append({"status": window.status})
            continue
        row, _ = analyse_impact(
            found, window, sensor, grain, crosstalk=crosstalk, modes=modes, noise=noise
        )
        errors = _errors(row, true, rate, record.noise) if row["status"] == "ok" else row
        rows.append({"family": found.contact_family, **errors})
    onsets = np.array([w.onset for w in found.impacts])
    for onset in truth["onset [s]"]:
        hit = onsets.size and np.abs(onsets - onset).min() <= MATCH
        counts["found" if hit else "missed"] += 1
    return rows


def accuracy(
    names=None, crosstalk=True, refine=True, predict=True, records=RECORDS, law=None, save=None
):
    grain, sensor, _ = hard()
    rows, counts = [], {"found": 0, "missed": 0, "invented": 0}
    print(f"crosstalk removal {'on' if crosstalk else 'off'}, joint poles refined: {refine}")
    print(f"noise under the pulse predicted from both sides: {predict}")
    for name in names or CONFIGURATIONS:
        rate, changes = CONFIGURATIONS[name]
        for seed, record in enumerate(_records(rate, range(records), changes, law)):
            analysed = _analyse(record, sensor, grain, rate, counts, crosstalk, refine, predict)
            for row in analysed:
                rows.append({"configuration": name, "seed": seed, **row})
    table = pd.DataFrame(rows)
    if save:
        table.to_csv(save, index=False)
    print(counts)
    print(table["status"].value_counts().to_string())
    ok = table[table["status"] == "ok"].copy()
    ok["band"] = pd.cut(ok["significance"], [0, 10, 30, 100, np.inf])
    columns = ["onset [samples]", "peak_sensor_force", "impulse", "peak_force", "contact_time"]
    keys = ["configuration", "band"]
    grouped = ok.groupby(keys, observed=True, sort=False)[columns]
    largest = grouped.agg(lambda v: np.nanmax(np.abs(v)))
    largest["impacts"] = ok.groupby(keys, observed=True, sort=False).size()
    print("largest errors (onset in samples, the others relative):")
    print(largest.round(4).to_string())
    print("95th percentile of the errors:")
    print(grouped.agg(lambda v: np.nanpercentile(np.abs(v), 95)).round(4).to_string())
    strong = ok[ok["significance"] >= 30.0]
    scaled = strong[["peak_sensor_force", "impulse"]].mul(strong["significance"] / 30.0, axis=0)
    rms = scaled.groupby(strong["configuration"], sort=False).agg(
        lambda v: np.sqrt(np.nanmean(v**2))
    )
    rms["impacts"] = strong.groupby("configuration", sort=False).size()
    print("root-mean-square error scaled to 30 sigma (error x significance / 30), over 30 sigma:")
    print(rms.round(4).to_string())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speed", action="store_true")
    parser.add_argument(
        "--workers", type=int, default=1, help="run_campaign's processes for --speed (1)"
    )
    parser.add_argument("--accuracy", action="store_true")
    parser.add_argument("--configuration", action="append", choices=list(CONFIGURATIONS))
    parser.add_argument(
        "--crosstalk-only",
        action="store_true",
        help="accuracy on the configurations with crosstalk only",
    )
    parser.add_argument(
        "--no-crosstalk", action="store_true", help="accuracy without the crosstalk removal"
    )
    parser.add_argument(
        "--no-refine",
        action="store_true",
        help="the joint pencil's poles as they are, without the variable projection",
    )
    parser.add_argument(
        "--no-prediction",
        action="store_true",
        help="the local baseline's ordinary line, without the noise predicted under the pulse",
    )
    parser.add_argument("--records", type=int, default=RECORDS, help="records per configuration")
    parser.add_argument(
        "--noise-model",
        choices=["ar", "white"],
        default=reconstruct_module.DEFAULT_NOISE_MODEL,
        help="the reconstruction's noise model (white: before the coloured-noise model)",
    )
    parser.add_argument(
        "--contact-edges",
        choices=list(reconstruct_module.CONTACT_EDGES),
        default=reconstruct_module.DEFAULT_CONTACT_EDGES,
        help="how the reconstructed contact's edges are read (level: 2 %% of the peak, before)",
    )
    parser.add_argument(
        "--law",
        choices=["linear", "hertz", "hertz-damped"],
        default="linear",
        help="the contact law of --accuracy's records (hertz: k_hertz = 1.5e6 N/m**1.5; "
        "hertz-damped: with Tsuji's damping, alpha 0.394)",
    )
    parser.add_argument("--rows", help="CSV file for every impact's errors (--accuracy)")
    parser.add_argument(
        "--linear-flanks",
        action="store_true",
        help="the reconstructed contact's edges read with a line on each flank whatever the "
        "record's contact family (as before the family was passed)",
    )
    parser.add_argument(
        "--largest-value",
        action="store_true",
        help="the reconstructed peak as the force's largest value, the contact from its "
        "significance edges (as before the family's fit read them)",
    )
    args = parser.parse_args()
    changed = {"contact_family": None} if args.linear_flanks else {}
    changed.update({"read_family": False} if args.largest_value else {})
    if changed:

        def campaign_call(*given, **options):  # the campaign's call, changed
            return reconstruct_module.reconstruct_force(*given, **{**options, **changed})

        analysis_module.reconstruct_force = campaign_call
    reconstruct_module.DEFAULT_NOISE_MODEL = args.noise_model
    reconstruct_module.DEFAULT_CONTACT_EDGES = args.contact_edges
    print(f"noise model {args.noise_model}, contact edges {args.contact_edges}")
    if args.speed or not args.accuracy:
        speed(args.workers)
    if args.accuracy or not args.speed:
        names = args.configuration
        if args.crosstalk_only:
            names = [n for n in names or CONFIGURATIONS if CONFIGURATIONS[n][1]["crosstalk"]]
        laws = {"hertz": HERTZ, "hertz-damped": hertz_damped(hard()[0])}
        law = laws.get(args.law)
        print(f"contact law {args.law}, flanks {'linear' if args.linear_flanks else 'family'}")
        print(f"peak and contact: {'largest value' if args.largest_value else 'family fit'}")
        accuracy(
            names,
            crosstalk=not args.no_crosstalk,
            refine=not args.no_refine,
            predict=not args.no_prediction,
            records=args.records,
            law=law,
            save=args.rows,
        )


if __name__ == "__main__":
    main()
