"""What accuracy of the peak signal, the impulse, the peak contact force and the
contact time is possible on realistic records.

For the impacts of ``benchmarks/bench_realistic.py --accuracy`` (the hard grain on the
40 kHz sensor, contact 100 us; white noise 0.03 N, hum 1.5 sigma, 1/f noise of 1, 0.3 or
0 times the white noise on a 25 ms record) at 1, 2 and 5 MHz, the standard deviation of
the best linear unbiased estimator of the peak signal and of the impulse
(:mod:`dem_check.campaign.bounds`: generalised least squares with the noise's true
covariance; the Cramer-Rao bound for Gaussian noise) under three models of the signal:
the contact law's (velocity, stiffness, damping, first touch unknown), any signal below
twice the sensor's resonance over the contact window then the free ringing ("band"),
and any signal in the contact window ("free", impulse only; the peak on one free
sample is that sample's noise less what its neighbours predict). The peak contact force
and the contact time (what the campaign reconstructs) under the law's model, and the peak
contact force also under ``force band``: any contact force below twice the sensor's
resonance over the contact window, through the sensor (what an unbiased deconvolution of
that bandwidth can reach; the contact time has no band bound: a band-limited force has
no edges). Every model has a line for the baseline. Printed relative to the truth at a
significance (peak signal over ``sqrt(white**2 + pink**2)``) of 30 and 100: the errors
scale as 1 / significance; with them the first touch's standard deviation in samples
under the law's model (the onset fit's Cramer-Rao bound under the records' noise).
Then, for the targets of issue 22 (peak signal 2 %, impulse, peak contact force and
contact time 5 %), the significance from which a reader at the
bound keeps the largest error of 17 impacts under the target (2.05 standard
deviations: the median of the largest of 17 half-normal draws).

The segment read: 16 sensor periods before the first touch, the contact window (first
touch to one period after the contact's end) and 16 periods after it.

``--readers DRAWS``: the campaign's impulse reader (``local_baseline``, windows as
``dem_check.campaign.analysis`` sets them: 8 periods before the onset less a tenth, the
contact and a period, 16 periods after) on ``DRAWS`` stretches of noise alone (white,
1/f and hum drawn as ``realistic_record`` draws them on 25 ms records): its standard
deviation with the ordinary line and with the noise under the pulse predicted from both
sides (white and 1/f levels estimated on the rest of each record), against the ``free``
bound of the same windows (same draws for both readers).

``--law hertz``: the same impacts with ``bench_realistic.py``'s undamped Hertz contact
(``HERTZ``, k_hertz = 1.5e6 N/m**1.5; its ``"law"`` model has the velocity, k_hertz and
the first touch unknown; a Hertz pulse's shape depends on the velocity, the contact
time as ``v**-0.2``, so its relative bounds are those of the 1.5 m/s impact, not of
every velocity).

Run: ``.venv/bin/python benchmarks/bench_bounds.py [--readers DRAWS] [--rate HZ]
[--pink RATIO] [--law hertz]``
"""

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.config import load_config
from contactlab.inverse.local_baseline import _ringing, local_baseline
from contactlab.inverse.noise_prediction import estimate_coloured_noise
from dem_check.campaign import Effects
from dem_check.campaign.bounds import (
    band_design,
    blue_variance,
    force_band_design,
    free_variance,
    law_design,
    noise_autocovariance,
)
from dem_check.campaign.records import add_effects

ROOT = Path(__file__).resolve().parents[1]
WHITE = 0.03  # [N], as bench_realistic.py
RECORD = 25e-3  # [s] length of bench_realistic.py's records (4 impacts 4-7 ms apart)
VELOCITY = 1.5  # [m/s] (the relative bounds at a given significance do not depend on it)
PERIODS = 16.0  # sensor periods read on either side
LARGEST_OF_17 = 2.05  # median of the largest of 17 half-normal draws, in standard deviations
COLUMNS = [
    ("peak signal", "law"),
    ("peak signal", "band"),
    ("peak signal", "one free sample"),
    ("impulse", "law"),
    ("impulse", "band"),
    ("impulse", "free"),
    ("peak force", "law"),
    ("peak force", "force band"),
    ("contact time", "law"),
]
"""The printed standard deviations: (reading, model)."""
TARGETS = {"peak signal": 2.0, "impulse": 5.0, "peak force": 5.0, "contact time": 5.0, "onset": 2.0}
"""Issue 22's targets: relative [%], the onset's [samples]."""


LAWS = {
    "linear": cl.laws.LinearViscoelastic(stiffness=4e4, damping=0.5),
    "hertz": cl.laws.Hertz(k_hertz=1.5e6),  # bench_realistic.py's HERTZ
}
"""The contact laws of ``--law``: the hard grain's linear contact, undamped Hertz."""


def _model(name="linear"):
    config = load_config(ROOT / "data" / "traces" / "model_hard.toml")
    return config.grain, config.sensor, LAWS[name]


def bounds(rate, pink, name="linear"):
    """Standard deviations [N], [N*s] of the peak and impulse under the three models,
    the truth and the noise scale, for the contact law ``name`` of :data:`LAWS`."""
    grain, sensor, law = _model(name)
    dt = 1.0 / rate
    impact = cl.simulate_impact(grain, sensor, law, VELOCITY, sample_rate=32.0 / dt)
    contact = impact.contact_time
    onset = PERIODS * sensor.period
    window = (onset, onset + contact + sensor.period)
    t = np.arange(round((window[1] + PERIODS * sensor.period) / dt)) * dt
    effects = Effects.everything(WHITE, 3.0, pink=pink * WHITE)
    autocovariance = noise_autocovariance(t.size, dt, WHITE, effects, RECORD)
    design, functionals, truth = law_design(grain, sensor, law, VELOCITY, t, onset)
    law_sd = np.sqrt(blue_variance(autocovariance, design, functionals))
    touch_to_peak = impact.t[int(np.argmax(impact.sensor_force))]  # to 1/32 of a sample
    top = int(np.argmin(np.abs(t - onset - touch_to_peak)))  # the sample nearest the peak
    band, terms = band_design(t, window, 2.0 * sensor.resonance, sensor)
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    inside = (t >= window[0]) & (t < window[1])
    tail = np.zeros(band.shape[1])
    tail[terms : terms + 2] = (zeta * w / w**2, math.sqrt(1.0 - zeta**2) * w / w**2)
    signal = band.copy()
    signal[:, terms:] = 0.0  # the signal's columns only: the ringing's enters by its tail
    band_functionals = np.column_stack([signal[top], signal[inside].sum(axis=0) * dt + tail])
    band_sd = np.sqrt(blue_variance(autocovariance, band, band_functionals))
    baseline = band[:, terms:]  # the ringing and the line: the signal is free inside
    free_impulse = free_variance(
        autocovariance, ~inside, inside, baseline, inside * dt, tail[terms:]
    )
    single = np.zeros(t.size)
    single[top] = 1.0
    free_peak = free_variance(autocovariance, ~inside, inside, baseline, single, 0.0 * tail[terms:])
    force_band, forces = force_band_design(t, window, 2.0 * sensor.resonance, sensor)
    contact_force = impact.peak_contact_time
    at = int(np.argmin(np.abs(t - onset - contact_force)))  # the sample nearest the force's top
    functional = np.concatenate([forces[at], np.zeros(2)])[:, None]
    force_band_sd = math.sqrt(blue_variance(autocovariance, force_band, functional)[0])
    touch = np.zeros((design.shape[1], 1))
    touch[-3] = 1.0  # the first touch's column: the law's parameters, the touch, the line
    return {
        "onset": math.sqrt(blue_variance(autocovariance, design, touch)[0]) / dt,
        "law": law_sd,
        "band": band_sd,
        "free": (math.sqrt(free_peak), math.sqrt(free_impulse)),
        "force band": force_band_sd,
        "truth": truth,
        "noise": math.hypot(WHITE, pink * WHITE),
    }


def readers(rate, pink, draws, seed=1, name="linear"):
    """Standard deviations [N*s] of the impulse read on noise alone with the ordinary
    line and with the predicted noise, the ``free`` bound of the same windows, the
    truth [N*s] and the noise scale [N] (``--readers``)."""
    grain, sensor, law = _model(name)
    impact = cl.simulate_impact(grain, sensor, law, VELOCITY)
    dt, period = 1.0 / rate, sensor.period
    onset = PERIODS * period
    start, post = onset - 0.1 * period, onset + impact.contact_time + period
    t = np.arange(round((post + PERIODS * period) / dt)) * dt
    base = (start - 8.0 * period, start)
    effects = Effects(pink=pink * WHITE, hum=1.5 * WHITE)
    total = round(RECORD / dt)
    rng = np.random.default_rng(seed)
    read = {"line": [], "predicted": []}
    no_impacts = pd.DataFrame({"onset [s]": [], "peak_sensor_force [N]": []})
    for _ in range(draws):
        noise = add_effects(
            np.arange(total) * dt, np.zeros(total), effects, no_impacts, WHITE, rng
        )[0]
        first = int(rng.integers(0, total - t.size))
        y = noise[first : first + t.size]
        quiet = np.ones(total, dtype=bool)
        quiet[first : first + t.size] = False
        levels = estimate_coloured_noise(noise, quiet, dt, RECORD, period)
        for name, model in (("line", None), ("predicted", levels)):
            read[name].append(local_baseline(t, y, base, start, post, post, sensor, model).impulse)
    inside = (t >= start) & (t < post)
    fitted = ((t >= base[0]) & (t < base[1])) | ((t >= post) & (t <= post + PERIODS * period))
    ringing, a, b = _ringing(np.maximum(t - post, 0.0), sensor)
    ringing[t < post] = 0.0
    design = np.column_stack([np.ones(t.size), t - t.mean(), ringing])
    tail = np.array([0.0, 0.0, a, b]) / sensor.angular_frequency**2
    autocovariance = noise_autocovariance(t.size, dt, WHITE, effects, RECORD)
    bound = math.sqrt(free_variance(autocovariance, fitted, inside, design, inside * dt, tail))
    spread = {name: float(np.std(v)) for name, v in read.items()}
    return spread, bound, impact, math.hypot(WHITE, pink * WHITE)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--readers", type=int, default=0, help="draws of the readers' check")
    parser.add_argument("--rate", type=float, action="append", help="sample rate [Hz]")
    parser.add_argument("--pink", type=float, action="append", help="1/f over white noise")
    parser.add_argument("--law", choices=list(LAWS), default="linear", help="contact law")
    args = parser.parse_args()
    rates, pinks = args.rate or (1e6, 2e6, 5e6), args.pink or (1.0, 0.3, 0.0)
    print(f"load average {os.getloadavg()[0]:.1f}, contact law {args.law}")
    if args.readers:
        print(f"impulse readers on noise alone, {args.readers} draws, % of the truth at 30 sigma")
        print("| rate | 1/f | line | predicted | free bound | line / bound | predicted / bound |")
        for pink in pinks:
            for rate in rates:
                started = time.perf_counter()
                spread, bound, impact, noise = readers(rate, pink, args.readers, name=args.law)
                scale = 100.0 / (30.0 * noise / impact.peak_sensor_force * impact.impulse)
                cells = [spread["line"] * scale, spread["predicted"] * scale, bound * scale]
                ratios = [spread["line"] / bound, spread["predicted"] / bound]
                print(
                    f"| {rate / 1e6:g} MHz | {pink:g} | "
                    + " | ".join(f"{c:.2f}" for c in cells + ratios)
                    + f" |  ({time.perf_counter() - started:.0f} s, load "
                    + f"{os.getloadavg()[0]:.1f})"
                )
        return
    print("standard deviation of the best linear unbiased estimator, % of the truth")
    print("| rate | 1/f | significance | " + " | ".join(f"{r}: {m}" for r, m in COLUMNS) + " |")
    needed = []
    for pink in pinks:
        for rate in rates:
            started = time.perf_counter()
            found = bounds(rate, pink, args.law)
            truth = found["truth"]
            at30 = {}
            for significance in (30.0, 100.0):
                scale = significance * found["noise"] / truth[0]  # amplitude of that significance
                cells = [
                    100.0 * found[m][k] / (scale * truth[k])
                    for k in (0, 1)
                    for m in ("law", "band", "free")
                ]
                cells += [
                    100.0 * found["law"][2] / (scale * truth[2]),
                    100.0 * found["force band"] / (scale * truth[2]),
                    100.0 * found["law"][3] / truth[3] / scale,
                ]
                if significance == 30.0:
                    at30 = dict(zip(COLUMNS, cells, strict=True))
                print(
                    f"| {rate / 1e6:g} MHz | {pink:g} | {significance:g} | "
                    + " | ".join(f"{c:.2f}" for c in cells)
                    + " |"
                )
            onset = [found["onset"] * truth[0] / (s * found["noise"]) for s in (30.0, 100.0)]
            print(
                "  first touch under the law's model, standard deviation at 30 / 100 sigma: "
                + f"{onset[0]:.2f} / {onset[1]:.2f} samples"
            )
            print(f"  ({time.perf_counter() - started:.1f} s, load {os.getloadavg()[0]:.1f})")
            needed.append((rate, pink, {**at30, ("onset", "law"): onset[0]}))
    print("significance from which the largest error of 17 impacts at the bound meets the target")
    names = [
        ("peak signal", "law"),
        ("peak signal", "band"),
        ("impulse", "law"),
        ("impulse", "free"),
        ("peak force", "law"),
        ("peak force", "force band"),
        ("contact time", "law"),
        ("onset", "law"),
    ]
    print("| rate | 1/f | " + " | ".join(f"{target}: {model}" for target, model in names) + " |")
    for rate, pink, at30 in needed:
        cells = [
            30.0 * LARGEST_OF_17 * at30[(target, model)] / TARGETS[target]
            for target, model in names
        ]
        print(f"| {rate / 1e6:g} MHz | {pink:g} | " + " | ".join(f"{c:.0f}" for c in cells) + " |")


if __name__ == "__main__":
    main()
