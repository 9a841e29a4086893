"""Synthetic long records with many impacts and a known truth (tests, demos, benchmarks).

No public record of a seed stream or drop series on a piezoelectric force sensor is
known, so campaigns are tested on records built with the forward model: each impact is
:func:`contactlab.simulate_impact` of the grain on the sensor, placed at its first touch
in a long record, plus white noise (and, optionally, a sensitivity and a DC offset to
give volts as an oscilloscope records them).
"""

import math

import numpy as np
import pandas as pd

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from contactlab.quantities import columns
from contactlab.solver import simulate_impact
from contactlab.traces import Trace
from contactlab.validation import check_count, check_number, check_samples

__all__ = ["OVERSAMPLING", "RINGING_LEFT", "synthetic_record"]

OVERSAMPLING = 8
"""Simulation points per record sample interval [-]: first touches fall on this grid,
so they sit at any eighth of a sample interval, not on the record's samples."""

RINGING_LEFT = 1e-4
"""Each impact is simulated until its sensor ringing has decayed to this fraction of
its peak signal [-]; the rest of the record holds no signal from it (a truncation far
below any usable noise level)."""

TRUTH_COLUMNS = columns(
    "onset",
    "velocity",
    "peak_sensor_force",
    "sensor_response_time",
    "impulse",
    "peak_contact_force",
    "contact_time",
    "restitution",
)
"""Columns of the truth table, named as in :attr:`CampaignResult.impacts`."""


def _impact_window(sensor):
    """Simulated span after first touch [s]: ringing down to :data:`RINGING_LEFT`."""
    decay = math.log(1.0 / RINGING_LEFT) / (sensor.damping_ratio * sensor.angular_frequency)
    return decay + 10.0 * sensor.period  # plus room for the contact itself


def synthetic_record(
    grain,
    sensor,
    law,
    velocities,
    onsets,
    *,
    length,
    sample_rate=5e6,
    noise=0.02,
    sensitivity=None,
    offset=0.0,
    seed=0,
):
    """A long record of several impacts of one grain type, with its truth table.

    Parameters
    ----------
    grain, sensor, law
        As for :func:`contactlab.simulate_impact` (a moving sensor: its ringing sets how
        long each impact is simulated).
    velocities : sequence of float
        Impact velocity of each impact [m/s].
    onsets : sequence of float
        First touch of each impact [s], from the record's first sample (t = 0); rounded
        to the simulation grid (1 / (8 sample_rate)). Impacts closer than their ringing
        are superposed: exact for the sensor's signal only if the sensor was at rest at
        the second touch, so use close pairs to test the flagging of overlaps, not the
        physics.
    length : float
        Record length [s].
    sample_rate : float, default 5e6
        Sample rate [Hz].
    noise : float, default 0.02
        Standard deviation of the white Gaussian noise [N] (before the sensitivity).
    sensitivity : float, optional
        Sensor sensitivity [V/N]: the record is then in volts, as a laboratory records it.
    offset : float, default 0.0
        DC offset added to the record, in its unit (N, or V with ``sensitivity``).
    seed : int, default 0
        Seed of ``numpy.random.default_rng`` (>= 0).

    Returns
    -------
    trace : Trace
        The record (``metadata["format"] == "synthetic"``, no trigger time).
    truth : pandas.DataFrame
        One row per impact, columns :data:`TRUTH_COLUMNS`: the exact onset and the
        model's headline numbers (``peak_sensor_force [N]`` is the sensor's
        ``peak_sensor_force``, ``sensor_response_time [s]`` its ``sensor_response_time``).

    Raises
    ------
    ParameterError
        Bad arguments, an onset outside the record, or a rigid sensor.
    """
    if not isinstance(sensor, Sensor) or sensor.is_rigid:
        raise ParameterError("sensor must be a moving contactlab.Sensor (its ringing is simulated)")
    length = check_number("length", length, low=0.0, unit="s")
    sample_rate = check_number("sample_rate", sample_rate, low=0.0, unit="Hz")
    noise = check_number("noise", noise, low=0.0, low_open=False, unit="N")
    offset = check_number("offset", offset)
    seed = check_count("seed", seed, low=0)
    if sensitivity is not None:
        sensitivity = check_number("sensitivity", sensitivity, low=0.0, unit="V/N")
    velocities = np.atleast_1d(check_samples("velocities", velocities, ndim=None))
    onsets = np.atleast_1d(check_samples("onsets", onsets, ndim=None))
    if velocities.shape != onsets.shape or velocities.ndim != 1:
        raise ParameterError(
            f"velocities and onsets must be 1-D of equal length; got {velocities.shape} "
            f"and {onsets.shape}"
        )
    count = round(length * sample_rate)
    step = 1.0 / (OVERSAMPLING * sample_rate)  # simulation grid [s]
    clean = np.zeros(count)
    rows = []
    for velocity, onset in zip(velocities, onsets, strict=True):
        onset = check_number(
            "onset", onset, low=0.0, low_open=False, high=length, high_open=True, unit="s"
        )
        touch = round(onset / step)  # first touch on the simulation grid
        result = simulate_impact(
            grain,
            sensor,
            law,
            velocity,
            duration=_impact_window(sensor),
            sample_rate=OVERSAMPLING * sample_rate,
        )
        first = -(-touch // OVERSAMPLING)  # first record sample at or after the touch
        grid = np.arange(first * OVERSAMPLING - touch, result.t.size, OVERSAMPLING)
        stop = min(first + grid.size, count)
        clean[first:stop] += result.sensor_force[grid[: stop - first]]
        rows.append(
            (
                touch * step,
                float(velocity),
                result.peak_sensor_force,
                result.sensor_response_time,
                result.impulse,
                result.peak_contact_force,
                result.contact_time,
                result.restitution,
            )
        )
    rng = np.random.default_rng(seed)
    values = clean + rng.normal(0.0, noise, count) if noise > 0.0 else clean
    unit = "N"
    if sensitivity is not None:
        values, unit = values * sensitivity, "V"
    metadata = {
        "format": "synthetic",
        "source": None,
        "instrument": "synthetic two-mass model (dem_check.campaign.synthetic_record)",
        "sample_interval": 1.0 / sample_rate,
        "trigger_time": None,
    }
    trace = Trace(np.arange(count) / sample_rate, values + offset, unit, metadata)
    return trace, pd.DataFrame(rows, columns=list(TRUTH_COLUMNS))
