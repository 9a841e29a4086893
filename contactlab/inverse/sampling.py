"""The sampling-rate rule for a force reconstruction: a record too coarse to reconstruct.

One rule serves the single-trace reconstruction
(:func:`contactlab.inverse.reconstruct.reconstruct_force`) and the campaign
(:mod:`dem_check.campaign.analysis`): the signal's first lobe must span at least
:data:`MIN_SAMPLES_PER_CONTACT` samples.
"""

import numpy as np

from contactlab import metrics
from contactlab.errors import ParameterError

__all__ = ["HIT_PEAK_FRACTION", "MIN_SAMPLES_PER_CONTACT", "check_samples_per_lobe"]

MIN_SAMPLES_PER_CONTACT = 20
"""Fewest samples per contact time for a reconstruction [-]. Below it the Tikhonov
reconstruction has fewer force values than a pulse's shape needs; the record is too
coarse, and a reconstructed peak and contact time are not given."""

HIT_PEAK_FRACTION = 0.5
"""Least peak of the lobe read as the hit, as a fraction of the signal's largest value
[-]. A sensor's first lobe under a contact is its largest excursion (the ringing after it
decays), so the hit's lobe reaches it; an acquisition filter's pre-echo or a noise
excursion before the hit (0.3-0.5 N before 69-89 N hits on the real hammer records,
docs/campaign.md "Real records") stays far under half of it."""


def check_samples_per_lobe(t, y, level):
    """Raise when the signal's first lobe spans fewer than :data:`MIN_SAMPLES_PER_CONTACT`
    samples.

    Parameters
    ----------
    t : numpy.ndarray
        Uniform time axis [s].
    y : numpy.ndarray
        The signal less its baseline [N].
    level : float
        Lobe threshold [N] (a few noise sigmas); the lobe ends at its last crossing before
        the signal is back at the baseline (hysteresis equal to the level), and lobes under
        :data:`HIT_PEAK_FRACTION` of the largest value before the hit are passed over.

    Raises
    ------
    ParameterError
        Naming the samples per first lobe and the :data:`MIN_SAMPLES_PER_CONTACT` needed.
    """
    dt = float(t[1] - t[0])
    start, end = metrics.first_lobe(t, y, level, level, HIT_PEAK_FRACTION)
    span = (end - start) / dt
    if np.isnan(span) or span >= MIN_SAMPLES_PER_CONTACT:
        return  # no lobe, or one running off the record: the reconstruction says so itself
    raise ParameterError(
        f"the record is too coarse to reconstruct: the signal's first lobe lasts {span:.3g} "
        f"samples of {dt:.4g} s (need {MIN_SAMPLES_PER_CONTACT}); sample at least "
        f"{MIN_SAMPLES_PER_CONTACT / span:.3g} times faster, or read its peak and impulse "
        "with dem-check compare"
    )
