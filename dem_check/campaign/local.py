"""The local baseline of one impact, fitted on both sides of it, and its impulse: the
single-trace paths share it, so it lives in :mod:`contactlab.inverse.local_baseline`
(a line fitted on the quiet samples before the impact and, with the sensor's free
ringing, on the samples after its contact); handed on here for the campaign, with the
record's white and 1/f noise (:func:`record_noise`) that predicts the noise under each
pulse from both sides of it (:mod:`contactlab.inverse.noise_prediction`)."""

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.local_baseline import (
    DEGREE,
    POST_PERIODS,
    PRE_PERIODS,
    LocalBaseline,
    local_baseline,
)
from contactlab.inverse.noise_prediction import estimate_coloured_noise

__all__ = [
    "DEGREE",
    "POST_PERIODS",
    "PRE_PERIODS",
    "LocalBaseline",
    "local_baseline",
    "record_noise",
]


def record_noise(detection, sensor):
    """The record's white and 1/f noise, estimated on its quiet samples.

    Quiet: finite samples outside every impact (a sensor period before its onset to
    its decayed ringing) and offset step found.

    Parameters
    ----------
    detection : Detection
    sensor : Sensor

    Returns
    -------
    ColouredNoise or None
        ``None`` when the quiet samples are too few for the estimate (the local
        baselines are then ordinary least squares).
    """
    t = np.asarray(detection.record.t)
    y = np.asarray(detection.record.values, dtype=float)
    quiet = np.isfinite(y)
    for window in (*detection.impacts, *detection.steps):
        quiet &= (t < window.onset - sensor.period) | (t > window.end)
    dt = float(t[1] - t[0])
    y = np.where(quiet, y, 0.0)
    try:
        return estimate_coloured_noise(y, quiet, dt, t.size * dt, sensor.period)
    except ParameterError:
        return None
