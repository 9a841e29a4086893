"""Realistic records drawn from a seed, as the benchmarks count them and the regression
tests of their failing records rebuild them (issue 22): a record is named by its seed
alone.

:func:`accuracy_record`: the records of ``benchmarks/bench_realistic.py --accuracy``.
:func:`hard_mix`: the hard mix of ``benchmarks/bench_steps.py`` (100 records;
``tests/dem_check/campaign/test_hard_mix_records.py``). The hard mix's record: 1-4
impacts of 0.2-2.5 m/s at 1, 2 or 5 MHz, with bounces (1.5-3 ms later), every effect of
:meth:`~dem_check.campaign.Effects.everything` (1/f noise as large as the white noise,
hum of 1.5 sigma, crosstalk of 2 % as the plate's response to the force, a 16-bit ADC
clipping at 1.2 times the largest peak plus the drift and the steps), drift of 20-50
noise sigmas (10 when the record starts at its impact) and two offset steps of 3-30 noise
sigmas, up or down, each at a random place of one of :data:`STEP_KINDS`.
:func:`weak_in_ringing`: a weak impact in a strong one's ringing, as
``benchmarks/bench_weak_impacts.py`` counts them
(``tests/dem_check/campaign/test_weak_impact_in_ringing.py``).
"""

import math

import numpy as np
import pandas as pd

from dem_check.campaign.records import Effects, realistic_record, ringing_at_onsets

__all__ = ["NOISE", "STEP_KINDS", "accuracy_record", "hard_mix", "weak_in_ringing"]

NOISE = 0.03
"""White noise of the records [N]: 1 % of the hard grain's 3 N peak at 2 m/s."""

STEP_KINDS = ("anywhere", "start", "end", "before impact", "after impact")
"""Where an offset step is drawn: anywhere, within 0.2 ms of the record's start or end, up
to 0.3 ms before an impact, or up to 0.3 ms after one (in its ringing)."""


def _step_time(rng, kind, onsets, length):
    """A step's time [s] of one of :data:`STEP_KINDS`."""
    if kind == "start" or (kind.endswith("impact") and not onsets.size):
        return rng.uniform(0.0, 0.2e-3)
    if kind == "end":
        return length - rng.uniform(0.0, 0.2e-3)
    if kind == "before impact":
        return max(0.0, rng.choice(onsets) - rng.uniform(0.0, 0.3e-3))
    if kind == "after impact":
        return rng.choice(onsets) + rng.uniform(0.0, 0.3e-3)
    return rng.uniform(0.0, length)


def hard_mix(seed, grain, sensor, law):
    """One record of the hard mix (module docstring) and its effects.

    Parameters
    ----------
    seed : int
        The record's number: it draws the record's parameters and its noise.
    grain, sensor, law
        As for :func:`~dem_check.campaign.realistic_record`; the benchmark's are the hard
        test grain (``data/traces/model_hard.toml``, linear contact k2 = 4e4 N/m, c2 =
        0.5 N*s/m: peak signal 1.5 N per m/s).

    Returns
    -------
    (RealisticRecord, Effects)
    """
    rng = np.random.default_rng(seed)
    rate = float(rng.choice([1e6, 2e6, 5e6]))
    count = int(rng.integers(1, 5))
    delay = rng.uniform(1.5e-3, 3e-3)
    first = float(rng.choice([0.0, 2.0 / rate, 1e-3]))
    gaps = rng.uniform(delay + 1.5e-3, 8e-3, count - 1)
    onsets = first + np.concatenate([[0.0], np.cumsum(gaps)])
    velocities = rng.uniform(0.2, 2.5, count)
    length = float(onsets[-1] + 6e-3)
    offsets = tuple(
        (
            _step_time(rng, str(rng.choice(STEP_KINDS)), onsets, length),
            rng.choice((-1.0, 1.0)) * rng.uniform(3.0, 30.0) * NOISE,
        )
        for _ in range(2)
    )
    largest = 3.0 * velocities.max() / 2.0  # the hard grain's peak signal [N]
    drift = rng.uniform(20.0, 50.0) * NOISE if first >= 1e-3 else 10.0 * NOISE
    # the ADC clips the largest impact, not the drift and steps (a record held at a
    # rail is not analysable)
    rails = 1.2 * largest + drift + sum(abs(h) for _, h in offsets)
    effects = Effects.everything(
        NOISE,
        largest,
        drift=drift,
        full_scale=rails,
        steps=0,
        offsets=offsets,
        bounce_delay=delay,
    )
    sampling = {"length": length, "sample_rate": rate, "noise": NOISE}
    record = realistic_record(
        grain, sensor, law, velocities, onsets, **sampling, effects=effects, seed=seed
    )
    return record, effects


def weak_in_ringing(seed, grain, sensor, law, *, alone=False):
    """A strong impact and a weak one 0.3-1.5 ms later, in its ringing, every effect on.

    The strong impact (1-2.5 m/s) is at 1 ms; the weak one's peak signal is 10-15 times
    the noise the realistic sweep counts (white, 1/f and quantisation noise with the
    structure's ringing at its onset, as
    :func:`~dem_check.campaign.records.ringing_at_onsets`), from the hard grain's 1.5 N
    of peak signal per m/s. At 1, 2 or 5 MHz, the effects at random levels over the
    realistic sweep's ranges (``tests/dem_check/campaign/test_realistic_detection.py``:
    1/f noise up to 2 noise sigmas, drift up to 50, hum up to 2, crosstalk up to 3 % as
    the plate's response, a 12-24 bit ADC clipping at 0.8-3 times a 2.5 m/s impact's
    peak); no offset steps. 6 ms.

    Parameters
    ----------
    seed : int
        The record's number: it draws the record's parameters and its noise.
    grain, sensor, law
        As for :func:`~dem_check.campaign.realistic_record` (the hard test grain's).
    alone : bool, default False
        Leave the weak impact out (the same record otherwise): nothing may be found in
        the ringing then.

    Returns
    -------
    (RealisticRecord, Effects)
    """
    rng = np.random.default_rng(seed)
    rate = float(rng.choice([1e6, 2e6, 5e6]))
    strong, delay, sigmas = rng.uniform(1.0, 2.5), rng.uniform(0.3e-3, 1.5e-3), rng.uniform(10, 15)
    largest = 1.5 * 2.5  # the hard grain's peak signal at 2.5 m/s [N]
    effects = Effects(
        pink=rng.uniform(0.0, 2.0) * NOISE,
        drift=rng.uniform(0.0, 50.0) * NOISE,
        hum=rng.uniform(0.0, 2.0) * NOISE,
        mains=float(rng.choice([50.0, 60.0])),
        crosstalk=rng.uniform(0.0, 0.03),
        full_scale=rng.uniform(0.8, 3.0) * largest,
        bits=int(rng.choice([12, 16, 24])),
    )
    onsets = np.array([1e-3, 1e-3 + delay])
    truth = pd.DataFrame({"onset [s]": onsets, "peak_sensor_force [N]": [1.5 * strong, 0.0]})
    structure = ringing_at_onsets(truth, effects)[1]
    lsb = 2.0 * effects.full_scale / 2**effects.bits
    random_noise = math.sqrt(NOISE**2 + effects.pink**2 + lsb**2 / 12.0)
    weak = sigmas * math.hypot(random_noise, structure / math.sqrt(2.0)) / 1.5
    velocities, onsets = ([strong], onsets[:1]) if alone else ([strong, weak], onsets)
    sampling = {"length": 6e-3, "sample_rate": rate, "noise": NOISE}
    record = realistic_record(
        grain, sensor, law, velocities, onsets, **sampling, effects=effects, seed=seed
    )
    return record, effects


def accuracy_record(seed, grain, sensor, law, sample_rate, noise=NOISE, **changes):
    """One record of the accuracy benchmark (``benchmarks/bench_realistic.py``).

    Four impacts of 0.5-2.5 m/s, 4-7 ms apart, the first at 1 ms, with every effect of
    :meth:`~dem_check.campaign.Effects.everything` for a 3 N peak; clipping and offset
    steps off unless ``changes`` (keywords of ``Effects.everything``) turn them on.

    Parameters
    ----------
    seed : int
        Draws the velocities and onsets and the record's noise.
    grain, sensor, law
        As for :func:`~dem_check.campaign.realistic_record`.
    sample_rate : float
        [Hz].
    noise : float, default :data:`NOISE`
        White noise [N].

    Returns
    -------
    RealisticRecord
    """
    rng = np.random.default_rng(seed)
    onsets = 1e-3 + np.cumsum(rng.uniform(4e-3, 7e-3, 4)) - 4e-3
    effects = Effects.everything(noise, 3.0, **{"full_scale": None, "steps": 0, **changes})
    return realistic_record(
        grain,
        sensor,
        law,
        rng.uniform(0.5, 2.5, 4),
        onsets,
        length=onsets[-1] + 6e-3,
        sample_rate=sample_rate,
        noise=noise,
        effects=effects,
        seed=seed,
    )
