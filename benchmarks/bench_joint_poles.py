"""Benchmark: the joint pencil's structure poles, before and after their refinement.

Windows built here in closed form, not by the record model: eight windows of ringing
after a hit, of the lengths found between the hits and bounces of
``bench_realistic.py --accuracy`` (1.3-3.8 ms), each holding the 40 kHz sensor's
ringing, an offset, the 730 Hz (damping ratio 0.01) and 1890 Hz (0.02) plate modes at
0.015-0.03 with their own amplitudes and phases, and noise: none, white (0.03), 1/f
(0.01; a sum of first-order processes with corners 10 Hz-100 kHz) or both, at 1 and
2 MHz. ``contactlab.inverse.crosstalk.joint_structure_modes`` with ``refine=False`` (the
pencil) and ``refine=True`` (variable projection); a mode counts as found when a
candidate within 30 % of it is significant after half of the windows. Prints, per
case, the largest and median relative frequency error of each mode and how often it was
missed (``docs/campaign.md``, "Crosstalk").

Run: ``.venv/bin/python benchmarks/bench_joint_poles.py [--seeds N]``
"""

import argparse
import math
import os
import time

import numpy as np
from scipy import signal

import contactlab as cl
from contactlab.inverse.crosstalk import joint_structure_modes

SENSOR = cl.Sensor.from_resonance(40e3, 0.01, damping_ratio=0.02)
PLATE = [(730.0, 0.01), (1890.0, 0.02)]
LENGTHS = [1.3e-3, 2.3e-3, 1.3e-3, 3.8e-3, 1.4e-3, 1.9e-3, 1.4e-3, 3.6e-3]  # [s]
NOISES = {"none": (0.0, 0.0), "white": (0.03, 0.0), "1/f": (0.0, 0.01), "both": (0.03, 0.01)}


def _damped(s, frequency, zeta):
    w = 2.0 * math.pi * frequency
    return np.where(s >= 0.0, np.exp(-zeta * w / math.sqrt(1 - zeta**2) * s) * np.sin(w * s), 0.0)


def _flicker(count, rng, dt):
    """1/f noise of unit standard deviation: first-order processes a decade apart."""
    noise = np.zeros(count)
    for corner in 10.0 ** np.arange(1, 6):
        decay = math.exp(-2.0 * math.pi * corner * dt)
        noise += signal.lfilter([1.0], [1.0, -decay], rng.normal(0, math.sqrt(1 - decay**2), count))
    return noise / noise.std()


def windows(seed, rate, white, flicker):
    rng = np.random.default_rng(seed)
    sizes = [round(length * rate) for length in LENGTHS]
    noise = white * rng.normal(size=sum(sizes)) + flicker * _flicker(sum(sizes), rng, 1 / rate)
    out, first = [], 0
    for size in sizes:
        t = np.arange(size) / rate
        y = 0.1 + 0.5 * _damped(t + 1e-4, SENSOR.resonance, SENSOR.damping_ratio)
        for frequency, zeta in PLATE:
            y += rng.uniform(0.015, 0.03) * _damped(t + rng.uniform(0.0, 2e-3), frequency, zeta)
        out.append((t, y + noise[first : first + size]))
        first += size
    return out


def _error(candidates, significant, frequency):
    errors = [
        abs(f / frequency - 1.0)
        for (f, _), hits in zip(candidates, significant.sum(axis=0), strict=True)
        if abs(f / frequency - 1.0) < 0.3 and hits >= significant.shape[0] / 2
    ]
    return min(errors, default=math.nan)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=12)
    seeds = parser.parse_args().seeds
    print(f"load average {os.getloadavg()[0]:.1f}; {seeds} seeds; errors in %: largest / median")
    for rate in (1e6, 2e6):
        for name, (white, flicker) in NOISES.items():
            errors = {False: [], True: []}
            seconds = {False: 0.0, True: 0.0}
            for seed in range(seeds):
                data = windows(seed, rate, white, flicker)
                for refine in errors:
                    started = time.perf_counter()
                    found = joint_structure_modes(data, SENSOR, refine=refine)
                    seconds[refine] += time.perf_counter() - started
                    errors[refine].append([_error(*found, f) for f, _ in PLATE])
            line = f"{rate / 1e6:.0f} MHz {name:6s}"
            for refine, label in ((False, "pencil"), (True, "refined")):
                e = 100 * np.array(errors[refine])
                parts = []
                for k, (frequency, _) in enumerate(PLATE):
                    column = e[:, k]
                    ok = column[np.isfinite(column)]
                    top = f"{ok.max():.1f} / {np.median(ok):.1f}" if ok.size else "-"
                    parts.append(f"{frequency:.0f} Hz {top} (missed {column.size - ok.size})")
                line += f" | {label}: " + ", ".join(parts) + f" [{seconds[refine]:.1f} s]"
            print(line, flush=True)


if __name__ == "__main__":
    main()
