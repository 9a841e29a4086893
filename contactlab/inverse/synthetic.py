"""Synthetic sensor traces with a known truth, for tests, demos and benchmarks."""

import numpy as np

from contactlab.solver import simulate_impact
from contactlab.validation import check_count, check_number

__all__ = ["synthetic_trace"]


def synthetic_trace(
    grain,
    sensor,
    law,
    velocity,
    *,
    duration=400e-6,
    sample_rate=5e6,
    pre_trigger=100e-6,
    noise=0.01,
    seed=0,
):
    """A simulated sensor signal with a pre-trigger baseline and white noise.

    Parameters
    ----------
    grain, sensor, law, velocity
        As for :func:`contactlab.simulate_impact` (velocity [m/s]).
    duration : float, default 400e-6
        Record length after first touch [s].
    sample_rate : float, default 5e6
        Sample rate [Hz].
    pre_trigger : float, default 100e-6
        Baseline recorded before first touch [s] (time is negative there, as an
        oscilloscope writes it relative to the trigger).
    noise : float, default 0.01
        Standard deviation of the Gaussian white noise as a fraction of the peak sensor
        signal [-].
    seed : int, default 0
        Seed of ``numpy.random.default_rng`` (>= 0).

    Returns
    -------
    t : numpy.ndarray
        Time [s], first touch at 0.
    signal : numpy.ndarray
        Sensor signal with noise [N].
    truth : ImpactResult
        The noiseless simulation (``truth.contact_force`` is S2 on ``truth.t``).
    """
    sample_rate = check_number("sample_rate", sample_rate, low=0.0, unit="Hz")
    pre_trigger = check_number("pre_trigger", pre_trigger, low=0.0, low_open=False, unit="s")
    noise = check_number("noise", noise, low=0.0, low_open=False)
    seed = check_count("seed", seed, low=0)
    truth = simulate_impact(
        grain, sensor, law, velocity, duration=duration, sample_rate=sample_rate
    )
    before = round(pre_trigger * sample_rate)
    t = np.concatenate([np.arange(-before, 0) / sample_rate, truth.t])
    clean = np.concatenate([np.zeros(before), truth.sensor_force])
    rng = np.random.default_rng(seed)
    return t, clean + rng.normal(0.0, noise * truth.peak_sensor_force, t.size), truth
