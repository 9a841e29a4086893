"""The first lobe of one impact's smoothed signal on its segment, and the level it ends at.

:func:`segment_lobe` reads the lobe with :func:`contactlab.metrics.first_lobe` at the
onset level (:data:`dem_check.campaign.detection.ONSET_SIGMAS` standard deviations of the
smoothed signal on the detection's baseline window) with the same hysteresis, so that
only a return to zero ends it. Zero is the baseline window's mean; where the signal
does not come back to it inside the segment (measured: a 0.57 N Hertz impact on a 2 MHz
record with 2 % crosstalk and 1/f noise as large as the white noise, its free ringing's
level 0.02-0.06 N above a window mean 0.3-0.5 ms before, the onset level 0.155 N, so that
no dip of the smoothed noise reached zero in the 0.65 ms after the touch;
``docs/campaign.md``, "No whole first lobe, traced"), zero is the line through that
mean and the mean of the segment's decayed ringing after the impact's end (the samples
of other impacts held out): the slow part of the record (1/f noise, drift, a structure
mode's slow ringing) that moved between the two sides is then not read as a lobe that
never ends. The first reading is kept wherever it finds the lobe, so the rows it read
are unchanged.
"""

import math

import numpy as np

from contactlab.metrics import first_lobe
from dem_check.campaign.detection import ONSET_SIGMAS

__all__ = ["NoLobe", "main_lobe_start", "segment_lobe"]

MIN_AFTER = 16
"""Fewest quiet samples after the impact's decayed ringing for the line's second side
[-] (as many as a baseline needs, ``dem_check.campaign.detection``)."""


class NoLobe(Exception):
    """The segment holds no whole first lobe to read the signal's numbers on (the
    message says why)."""


def main_lobe_start(y, level):
    """Index from which the first lobe is read: the last sample under ``level`` before
    the signal first reaches half its largest value. Wiggles before the impact that
    cross the onset level (an acquisition filter's pre-echo, a trigger glitch) then do
    not pass for its first lobe."""
    half = int(np.argmax(y >= 0.5 * np.nanmax(y)))
    under = np.flatnonzero(y[:half] < level)
    return int(under[-1]) if under.size else 0


def _both_sides(t, smooth, window, held, in_base):
    """The line through the baseline window's mean (at its middle) and the mean of the
    segment's samples after the impact's end (at their middle) [N], or ``None`` where
    the baseline window lies after the impact (a short pre-trigger) or fewer than
    :data:`MIN_AFTER` quiet samples follow the impact."""
    after = (t > window.end) & ~held
    if window.baseline_window[0] > window.onset or np.count_nonzero(after) < MIN_AFTER:
        return None
    t0, t1 = float(np.mean(t[in_base])), float(np.mean(t[after]))
    y0, y1 = float(np.mean(smooth[in_base])), float(np.mean(smooth[after]))
    return y0 + (y1 - y0) * (t - t0) / (t1 - t0)


def segment_lobe(t, smooth, window, held):
    """The first lobe of the smoothed signal on an impact's segment (module docstring).

    Parameters
    ----------
    t : numpy.ndarray
        The segment's time [s].
    smooth : numpy.ndarray
        The smoothed signal on it [N].
    window : ImpactWindow
        The impact (its ``baseline_window``, ``onset`` and ``end`` [s]).
    held : numpy.ndarray of bool
        The segment's samples that hold another impact.

    Returns
    -------
    tuple of float
        The lobe's start and end [s].

    Raises
    ------
    NoLobe
        Where the signal does not rise above, or does not return to, the onset level
        inside the segment against either zero.
    """
    base = window.baseline_window
    in_base = (t >= base[0]) & (t < base[1])
    level = ONSET_SIGMAS * float(np.std(smooth[in_base], ddof=1))
    zeros = [
        np.full(t.size, np.mean(smooth[in_base])),
        _both_sides(t, smooth, window, held, in_base),
    ]
    for zero in (z for z in zeros if z is not None):
        above = smooth - zero
        first = main_lobe_start(above, level)
        lobe = first_lobe(t[first:], above[first:], level, hysteresis=level)
        if math.isfinite(lobe[0]) and math.isfinite(lobe[1]):
            return lobe
    edge = "return to" if math.isfinite(lobe[0]) else "rise above"
    raise NoLobe(
        f"the smoothed signal less its baseline window's mean (or the line from it to the "
        f"decayed ringing's mean) does not {edge} {ONSET_SIGMAS:g} sigma of that window's "
        f"noise ({level:.3g} N) between {t[first]:.6g} and {t[-1]:.6g} s: no first lobe "
        "to read the peak signal, the impulse and the contact on"
    )
