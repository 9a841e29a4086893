"""Structural crosstalk of a single trace's one impact, its modes found on its own ringing.

The campaign reads a record's modes on many impacts (``dem_check.campaign.structure``);
a single trace has one, so its modes are sought on that impact's ringing after its
contact and kept when their response to its pulse is significant
(:mod:`contactlab.inverse.crosstalk`; ``docs/campaign.md``, "Single-trace paths").
"""

import numpy as np

from contactlab.errors import ParameterError
from contactlab.inverse.crosstalk import Crosstalk, fit_crosstalk, structure_modes

__all__ = ["SINGLE_IDENTIFICATION_SPAN", "SINGLE_SPAN", "single_impact_crosstalk"]

SINGLE_SPAN = 2e-3
"""Longest window a single trace's crosstalk is fitted on, on each side of its pulse [s]
(as the campaign's ``dem_check.campaign.structure.SPAN``): long against the modes'
periods, short against drift and 1/f noise (a quadratic follows them)."""

SINGLE_IDENTIFICATION_SPAN = 5e-3
"""Longest window after a single trace's contact its modes are identified on [s] (as the
campaign's): a mode is sought from one period in it."""


def single_impact_crosstalk(t, y, sensor, onset, pre_end, contact_end):
    """The crosstalk of the one impact of a single trace, its modes found on its own ringing.

    With one record there is one impact: the modes are those :func:`structure_modes`
    finds on the ringing after its contact (from ``contact_end`` to the record's end, at
    most :data:`SINGLE_IDENTIFICATION_SPAN`), kept by :func:`fit_crosstalk` when their
    response to this pulse is significant. The campaign instead keeps the modes found
    after half of a record's impacts, which a single trace cannot do; a candidate must
    instead also be significant under the noise of the pre-trigger (``noise=`` of
    :func:`structure_modes`), which drops the poles the pencil fits to 1/f noise.

    Parameters
    ----------
    t, y : numpy.ndarray
        The record: uniform times [s] and the signal [N].
    sensor : Sensor
    onset : float
        The pulse's onset [s].
    pre_end : float or None
        End of the baseline window before the pulse [s] (its samples before it, at most
        :data:`SINGLE_SPAN`, are fitted), or None when the record starts at the pulse.
    contact_end : float
        A time after the contact has ended [s].

    Returns
    -------
    Crosstalk or None
        On every sample of the record (zero outside the fitted stretch); None when the
        ringing after the contact is too short to identify modes on.
    """
    after = (t >= contact_end) & (t <= contact_end + SINGLE_IDENTIFICATION_SPAN)
    noise = None
    if pre_end is not None:
        quiet = (t < min(pre_end, onset)) & (t >= pre_end - SINGLE_IDENTIFICATION_SPAN)
        noise = (t[quiet], y[quiet]) if quiet.sum() >= 16 else None
    try:
        modes = structure_modes(t[after], y[after], sensor, noise=noise, refine=True)
    except ParameterError:  # too short a window after the contact
        return None
    values = np.zeros(t.size)
    if not modes:
        return Crosstalk((), values)
    post_start = contact_end + sensor.period
    start = onset if pre_end is None else pre_end
    first = onset - SINGLE_SPAN if pre_end is not None else start
    stretch = (t >= first) & (t <= post_start + SINGLE_SPAN)
    tt, yy = t[stretch], y[stretch]
    fitted = ((tt < start) & (pre_end is not None)) | (tt >= post_start)
    pulse = (tt >= start) & (tt < contact_end)
    found = fit_crosstalk(tt, yy, sensor, onset, pulse, fitted, post_start, modes)
    values[stretch] = found.values
    return Crosstalk(found.modes, values)
