"""Accuracy and time of the inverse methods on synthetic traces with known truth.

The paper's hard grain (preset fig6: 5 mm, 765 kg/m^3, k = 1e5 N/m, c = 1 N*s/m,
2 m/s) on the 40 kHz disc sensor (damping ratio 0.02), 5 MHz, 1 % noise, over
``--seeds`` noise seeds: identification errors, reconstruction errors against the raw
signal's, and fit recovery with the fraction of truths inside the 95 % intervals. Times
are medians (the machine is shared). The numbers in ``docs/inverse.md`` come from here.

Run: ``.venv/bin/python benchmarks/bench_inverse.py [--seeds N]``
"""

import argparse
import statistics
import time
import warnings

import numpy as np

import contactlab as cl
from contactlab.config import load_preset
from contactlab.inverse import (
    IdentifiabilityWarning,
    fit_contact,
    identify_sensor,
    reconstruct_force,
    synthetic_trace,
)


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _row(name, errors, times):
    errors = np.abs(np.asarray(errors)) * 100.0
    return (
        f"{name:34s} max {errors.max():6.2f} %  mean {errors.mean():6.2f} %  "
        f"time {statistics.median(times) * 1e3:7.1f} ms"
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=8)
    seeds = range(parser.parse_args().seeds)
    case = load_preset("fig6")
    grain, law, v0 = case.grain, case.law, case.simulation["velocity"]
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    traces = [synthetic_trace(grain, sensor, law, v0, seed=s) for s in seeds]
    truth = traces[0][2]
    print(f"hard case, 40 kHz sensor, {len(traces)} seeds, 1 % noise, 5 MHz")

    long = cl.simulate_impact(grain, sensor, law, v0, duration=1e-3, sample_rate=2e6)
    f_err, z_err, times = [], [], []
    for s in seeds:
        noise = np.random.default_rng(s).normal(0, 0.01 * long.peak_sensor_force, long.t.size)
        ident, dt = timed(lambda n=noise: identify_sensor(long.t, long.sensor_force + n))
        f_err.append(ident.resonance / 40e3 - 1.0)
        z_err.append(ident.damping_ratio / 0.02 - 1.0)
        times.append(dt)
    print(_row("identify: resonance", f_err, times))
    print(_row("identify: damping ratio", z_err, times))

    raw_peak = truth.peak_sensor_force / truth.peak_contact_force - 1.0
    raw_time = truth.sensor_response_time / truth.contact_time - 1.0
    print(f"{'raw signal: peak / contact time':34s} {raw_peak:+.1%} / {raw_time:+.1%}")
    for method in ("tikhonov", "inverse"):
        peaks, durations, times = [], [], []
        for t, y, _ in traces:
            rec, dt = timed(lambda t=t, y=y, m=method: reconstruct_force(t, y, sensor, m))
            peaks.append(rec.metrics.peak / truth.peak_contact_force - 1.0)
            durations.append(rec.metrics.duration / truth.contact_time - 1.0)
            times.append(dt)
        print(_row(f"reconstruct {method}: peak", peaks, times))
        print(_row(f"reconstruct {method}: contact time", durations, times))

    truths = {"stiffness": 1e5, "damping": 1.0, "velocity": v0}
    errors = {k: [] for k in truths}
    covered = {k: 0 for k in truths}
    times = []
    for t, y, _ in traces:
        with warnings.catch_warnings():
            warnings.simplefilter("error", IdentifiabilityWarning)
            fit, dt = timed(lambda t=t, y=y: fit_contact(t, y, grain, sensor, "linear"))
        times.append(dt)
        for name, value in truths.items():
            p = fit.parameters[name]
            errors[name].append(p.value / value - 1.0)
            covered[name] += p.ci95[0] <= value <= p.ci95[1]
    for name in truths:
        print(_row(f"fit linear: {name}", errors[name], times) + f"  in 95 % CI "
              f"{covered[name]}/{len(traces)}")  # fmt: skip


if __name__ == "__main__":
    main()
