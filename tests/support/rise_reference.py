"""``dem_check.campaign.step_ringing.rise`` as a loop over the samples, as it was before
its tests were taken on every sample at once (session 17): the reference that
``tests/dem_check/campaign/test_step_ringing_rise.py`` checks it against (imported by
name: ``tests/conftest.py`` puts this folder on the path)."""

import numpy as np

from dem_check.campaign.step_ringing import QUIET_FRACTION, RISE_SIGMAS, difference_sigma


def loop_rise(x, start, band, period):
    """Where the main lobe rises in ``x``, one sample after the other (the reference)."""
    quiet = max(2, round(QUIET_FRACTION * period))
    reach = RISE_SIGMAS * difference_sigma(x)

    def within(values):
        return values.min() >= band[0] - reach and values.max() <= band[1] + reach

    i = start + quiet
    while i < x.size:
        if not within(x[i : i + 1]) or abs(x[i] - np.median(x[i - quiet : i])) > 2.0 * reach:
            ahead = x[i + 1 : i + 1 + quiet]
            if ahead.size < quiet or np.ptp(ahead) > 2.0 * reach or not within(ahead):
                return max(start, i - quiet // 2)
            i += quiet  # a step: the level it settles at is the one to follow
        i += 1
    return max(start, x.size - quiet // 2)
