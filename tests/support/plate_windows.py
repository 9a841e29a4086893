"""Windows of ringing after a hit, built in closed form (not by the record model): the
40 kHz sensor's ringing, the plate's 730 Hz and 1890 Hz modes and white and 1/f noise.
``tests/contactlab/inverse/test_crosstalk.py`` checks the joint pencil on them and
``benchmarks/bench_joint_poles.py`` measures it on more seeds and rates (imported by
name: ``tests/conftest.py`` and the benchmark put this folder on the path)."""

import math

import numpy as np
from scipy import signal

import contactlab as cl

SENSOR = cl.Sensor.from_resonance(40e3, 0.01, damping_ratio=0.02)
"""The 40 kHz sensor (10 g, damping ratio 0.02) that rings in every window."""

PLATE = [(730.0, 0.01), (1890.0, 0.02)]
"""The plate's modes: ``(frequency [Hz], damping ratio [-])``."""

LENGTHS = [1.3e-3, 2.3e-3, 1.3e-3, 3.8e-3, 1.4e-3, 1.9e-3, 1.4e-3, 3.6e-3]
"""Window lengths [s], as between the realistic benchmark's hits and bounces at 1 MHz
(docs/campaign.md)."""

SENSOR_RINGING = 0.5
"""Amplitude of the sensor's ringing in each window [N]."""


def damped(s, frequency, zeta):
    """A unit damped sinusoid ``exp(-zeta w / sqrt(1 - zeta**2) s) sin(w s)`` starting at
    ``s = 0`` (zero before), ``w = 2 pi frequency`` [rad/s], ``s`` [s]."""
    w = 2.0 * math.pi * frequency
    return np.where(s >= 0.0, np.exp(-zeta * w / math.sqrt(1 - zeta**2) * s) * np.sin(w * s), 0.0)


def flicker(count, rng, dt):
    """1/f noise of unit standard deviation: a sum of first-order (Ornstein-Uhlenbeck)
    processes of equal variance with corners a decade apart, 10 Hz to 100 kHz (their sum's
    spectrum falls as 1/f between the corners; Keshner 1982), not the record model's
    spectral shaping; ``dt`` [s] is the sample interval."""
    noise = np.zeros(count)
    for corner in 10.0 ** np.arange(1, 6):
        decay = math.exp(-2.0 * math.pi * corner * dt)
        drive = rng.normal(0.0, math.sqrt(1.0 - decay**2), count)
        noise += signal.lfilter([1.0], [1.0, -decay], drive)
    return noise / noise.std()


def plate_windows(seed, rate=1e6, white=0.03, flicker_sigma=0.01):
    """Windows of ringing after eight hits, ``[(t [s], y [N]), ...]``: the sensor's
    ringing, the :data:`PLATE` modes (0.015-0.03 each, ringing from 0-2 ms before the
    window) and white (``white`` [N]) and 1/f (``flicker_sigma`` [N]) noise cut from one
    continuous record sampled at ``rate`` [Hz] (the 1/f noise is slower than a window)."""
    rng = np.random.default_rng(seed)
    sizes = [round(length * rate) for length in LENGTHS]
    noise = white * rng.normal(size=sum(sizes))
    noise = noise + flicker_sigma * flicker(sum(sizes), rng, 1 / rate)
    windows, first = [], 0
    for size in sizes:
        t = np.arange(size) / rate
        y = 0.1 + SENSOR_RINGING * damped(t + 1e-4, SENSOR.resonance, SENSOR.damping_ratio)
        for frequency, zeta in PLATE:
            lag = rng.uniform(0.0, 2e-3)
            y += rng.uniform(0.015, 0.03) * damped(t + lag, frequency, zeta)
        windows.append((t, y + noise[first : first + size]))
        first += size
    return windows


def mode_error(candidates, significant, frequency):
    """Relative error of the candidate nearest ``frequency`` [Hz] significant after half
    of the windows (nan when there is none within 30 %)."""
    errors = [
        abs(f / frequency - 1.0)
        for (f, _), hits in zip(candidates, significant.sum(axis=0), strict=True)
        if abs(f / frequency - 1.0) < 0.3 and hits >= significant.shape[0] / 2
    ]
    return min(errors, default=math.nan)
