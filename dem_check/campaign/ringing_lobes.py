"""A weak impact's lobe under a strong one's free ringing: the ringing fitted and taken
off (step 5 of :mod:`dem_check.campaign.detection`, issue 22).

The growth rule (:mod:`dem_check.campaign.growths`) sees a later impact where the
ringing envelope grows by :data:`~dem_check.campaign.growths.GROWTH_FACTOR`; a lobe
under about half the ringing where it lands cannot raise the envelope so
(``benchmarks/bench_weak_impacts.py``, seed 98: a 0.39 N lobe, 13 noise sigmas, on 0.19 N
of a 3.69 N impact's ringing 0.39 ms later raises the envelope to 0.30 N, under 1.5 times
0.19 N plus the floor). The sensor's free ringing is known in form: a damped sinusoid at
the sensor's damped frequency and decay, which the detection's linear smoothing keeps
one. Where the growth rule found nothing:

1. **Prediction.** For each sensor period of the run after the first lobe's ringing is
   under way, the free ringing (its two amplitudes) and a level are fitted by least
   squares on the :data:`FIT_PERIODS` periods before it and extrapolated over it; the
   residual's mean over the period, over the local noise, is its excess level.
2. **Candidate.** The first period whose excess level reaches the detection threshold
   (in local sigmas) on the positive side (a compressive contact), if its lobe falls
   back (:data:`RETURN_FRACTION`: an offset step in the ringing stays); the
   later impact is placed where the residual first passes the noise floor in the period
   before it or in it (the lobe fills the period it starts in only in part).
3. **Not the plate's.** A level the running baseline left under the ringing, or a plate
   mode's swing, also leaves a level no sensor ringing explains (the 4100 Hz mode moves
   by its amplitude within two sensor periods): the candidate stands only if the
   structure's free ringing after the first impact, fitted without the candidate's
   samples (:func:`dem_check.campaign.plate_swings.explained`: the plate's modes, a
   quadratic and the sensor's ringing), does not bring it under the detection threshold.
"""

import numpy as np

from contactlab.inverse.local_baseline import free_ringing
from dem_check.campaign.noise import FLOOR_SIGMAS
from dem_check.campaign.plate_swings import LOBE_PERIODS, explained

__all__ = [
    "FIT_PERIODS",
    "LEFT_OUT_PERIODS",
    "RETURN_FRACTION",
    "excess_levels",
    "lobe_under_ringing",
]

FIT_PERIODS = 3
"""Sensor periods the free ringing is fitted on before each period it predicts [-]:
several periods average the noise in the two amplitudes and the level, and a short
window lets the level follow the running baseline's and the plate's slow moves (one
level for the whole ringing left 9.3 local sigmas 0.1 ms into seed 98's record without
its weak impact; three periods, at most 2.4). Not tuned further."""

LEFT_OUT_PERIODS = 4
"""Sensor periods left out of the plate's fit from the candidate on [-]: a 100 us
contact (the hard grain's) spans four periods of the 40 kHz sensor; a longer contact's
tail left in the fit is followed by the plate's model in part, which lowers the
candidate's residual (a miss, not an invented impact)."""

RETURN_FRACTION = 0.5
"""A lobe falls back: within :data:`~dem_check.campaign.plate_swings.LOBE_PERIODS` of the
first period over the threshold, a period's excess level must fall to minus this
fraction of the largest [-]. A contact's lobe falls as it rose (seed 98: +25.4 then
-19.1 local sigmas); an offset step in the ringing stays (seeds 32 and 54 of
``benchmarks/bench_steps.py``: +12.2 and +19.7, then -0.4 and -0.2 at the lowest)."""


def excess_levels(z, local, start, windows, period, t, sensor):
    """The residual of each period's prediction (module step 1) [N], one row a period
    from period :data:`FIT_PERIODS` on, and its mean over the local noise [-]."""
    unit = [
        free_ringing(t[start : start + windows * period], t[start], u, sensor)
        for u in ((1, 0), (0, 1))
    ]
    design = np.column_stack([*unit, np.ones(windows * period)])
    residuals, excess = [], []
    span = FIT_PERIODS * period
    for k in range(FIT_PERIODS, windows):
        lo, hi = (k - FIT_PERIODS) * period, k * period
        coefficients, *_ = np.linalg.lstsq(design[lo:hi], z[start + lo : start + hi], rcond=None)
        rest = z[start + lo : start + hi + period] - design[lo : hi + period] @ coefficients
        residuals.append(rest[span - period :])
        excess.append(rest[span:].mean() / local[start + hi : start + hi + period].mean())
    return residuals, np.array(excess)


def lobe_under_ringing(record, stage, sensor, first_lobe, run, following):
    """A later impact's lobe under the first one's free ringing (module docstring).

    Parameters
    ----------
    record : Trace
        The record [N] (its offset steps taken off).
    stage : dict
        The detection's ``floor`` (NoiseFloor), ``smoothed`` (Trace), ``local`` (local
        noise [N] at every sample) and ``scales`` (``period`` [samples]).
    sensor : Sensor
    first_lobe : (float, int)
        The first impact's onset [s] and its first lobe's last sample.
    run : (int, int)
        First and last sample of the run.
    following : int
        First sample after the run's segment (the next run's, or the record's length).

    Returns
    -------
    list of int
        Where the later impact starts (one index), or none.
    """
    z = np.asarray(stage["smoothed"].values, dtype=float)
    t = np.asarray(stage["smoothed"].t)
    local, period, floor = stage["local"], stage["scales"]["period"], stage["floor"]
    start = first_lobe[1] + period  # the free ringing is under way one period later
    windows = (run[1] + 1 - start) // period
    if windows <= FIT_PERIODS:
        return []
    residuals, excess = excess_levels(z, local, start, windows, period, t, sensor)
    over = np.flatnonzero(excess >= floor.sigmas)
    if not over.size:
        return []
    k = int(over[0])  # the first period over the threshold, counted from FIT_PERIODS
    rise = excess[k : k + int(LOBE_PERIODS)]
    if -rise.min() < RETURN_FRACTION * rise.max():
        return []  # it does not fall back: a level that stays (an offset step)
    rising = np.flatnonzero(residuals[k] > FLOOR_SIGMAS * floor.smoothed_noise)
    at = start + (k + FIT_PERIODS - 1) * period + (int(rising[0]) if rising.size else period)
    end = min(at + LEFT_OUT_PERIODS * period, run[1])
    arrays = (floor.kernel, z, local)
    after = float(t[following]) if following < t.size else np.inf
    if explained(record, arrays, floor.sigmas, (at, end), first_lobe, after, sensor):
        return []  # the plate's ringing and the sensor's bring it under the threshold
    return [at]
