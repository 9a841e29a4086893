"""Later impacts in an impact's ringing: where the ringing envelope grows, by a force
(step 5 of :mod:`dem_check.campaign.detection`, issue 22).

Free ringing only decays. The largest value per sensor period after the first lobe
must grow by :data:`GROWTH_FACTOR` plus the noise floor and reach the detection
threshold, and the growth must be a force's: the ringing about its running mean over a
period grows so too (a new contact rings the sensor), or that mean, the level, stands at
the detection threshold on the first lobe's side (a slow contact's lobe rings the sensor
little). A level the running baseline left under the ringing moves the largest value
without either: a plate mode's slow swing (the record model's crosstalk is the plate's
response to the force, which swings the level by 0.1-0.15 N within 0.1-0.3 ms after a
2-3.6 N impact), or a block level chosen for a stretch (seeds 60 and 82 of
``benchmarks/bench_steps.py``: 'overlap' rows invented 0.17-0.29 ms after an impact).
A weak contact's lobe rises over about two periods, by less than the factor in each, and
fills the period it starts in only in part: the growth is counted against the least of
the :data:`RISE_PERIODS` periods before, and the level may reach the threshold in the
growth's period or the next (``benchmarks/bench_weak_impacts.py``: 10-15 sigma impacts
0.3-1.5 ms after a strong one: 24 of 400 missed before, 2 of them in a clipped impact's
ringing, which was not checked then; 1 after). A lobe under about half the ringing
cannot grow the envelope by the factor: :mod:`dem_check.campaign.ringing_lobes` takes
the sensor's free ringing off and looks at the level left (seed 98).
"""

import numpy as np
from scipy.ndimage import uniform_filter1d

__all__ = ["GROWTH_FACTOR", "RISE_PERIODS", "later_impacts"]

GROWTH_FACTOR = 1.5
"""Largest growth of the ringing envelope from one sensor period to the next that is
not a new impact: free ringing shrinks by ``exp(-2 pi zeta)`` per period."""

RISE_PERIODS = 2
"""Sensor periods over which the envelope's growth is counted [-]: each period's largest
value is weighed against the least of the periods before, up to this many back. A weak
contact's lobe rises over about half its contact (two periods of the 40 kHz sensor for a
100 us contact), by less than the factor in each period."""


def later_impacts(z, ratio, first_lobe_end, last, period, levels):
    """Where the ringing envelope grows to the detection threshold by a force: later
    impacts (module docstring).

    Parameters
    ----------
    z : numpy.ndarray
        The smoothed residual of the record [N].
    ratio : numpy.ndarray
        ``|z|`` over the local noise [local sigmas].
    first_lobe_end, last : int
        The first lobe's last sample and the run's last (indices).
    period : int
        The sensor's period [samples].
    levels : tuple
        ``(floor [N], sigmas [-])``: the noise floor and the detection threshold.

    Returns
    -------
    list of int
        Where each later impact's growth starts (indices).
    """
    start = first_lobe_end + period  # the free ringing is under way one period later
    windows = (last + 1 - start) // period
    if windows < 2:
        return []
    stop = start + windows * period
    periods = z[start:stop].reshape(windows, period)
    # a period's mean holds none of the sensor's free ringing (a jump of the level under
    # it leaves at most half the jump about the running mean)
    lo = max(0, start - period)
    mean = uniform_filter1d(z[lo : stop + period], period, mode="nearest")[start - lo : stop - lo]
    centred = np.abs(periods - mean.reshape(windows, period)).max(axis=1)
    envelope = np.abs(periods).max(axis=1)
    sigmas = ratio[start:stop].reshape(windows, period)
    reached = sigmas.max(axis=1)
    level = np.mean(np.sign(periods) * sigmas, axis=1)  # the period's mean [local sigmas]

    def grown(values):
        # against the least of the RISE_PERIODS periods before: a contact's lobe can
        # rise over two, neither growing by the factor from the one before
        reference = values[:-1].copy()
        for back in range(2, RISE_PERIODS + 1):
            reference[back - 1 :] = np.minimum(reference[back - 1 :], values[:-back])
        return values[1:] > GROWTH_FACTOR * reference + levels[0], reference

    # the level at the threshold in the period of the growth or the next: the lobe
    # fills the period where it started only in part
    rising = np.maximum(level[1:], np.append(level[2:], -np.inf))
    force = grown(centred)[0] | (rising >= levels[1])
    larger, reference = grown(envelope)
    grows = (reached[1:] >= levels[1]) & larger & force
    runs = np.flatnonzero(grows & ~np.concatenate([[False], grows[:-1]])) + 1
    found = []
    for k in runs:
        threshold = GROWTH_FACTOR * reference[k - 1] + levels[0]
        first = max(0, k - RISE_PERIODS + 1)  # where a growth over two periods started
        samples = np.abs(periods[first : k + 1].ravel())
        found.append(start + first * period + int(np.argmax(samples > threshold)))
    return found
