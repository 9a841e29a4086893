"""Placing an offset step found across an impact: before it, or in its ringing with the
sensor's free ringing fitted and taken off (issue 22).

:func:`dem_check.campaign.steps.find_steps` reads the level change across an impact that
the first pass masked (the level after its ringing less the level before it); where the
step lies is then found on the record around it. A least-absolute-deviation split there
is drawn to the impact's onset: the flanks of the main lobe lie nearer the higher level,
and the ringing, larger than the step, counts for both levels at random. So:

1. **Main lobe.** Samples whose one-period mean lies far from both levels (further than
   the step's height and :data:`~dem_check.campaign.steps.FAR_SIGMAS` of the period
   means' noise; where none does, a lobe less than twice the step's height high, outside
   the band between the levels by that noise), in the stretch around the largest
   excursion, one period either side, are left out: no step can be placed on them. The
   lobe's start is then moved to where the samples rise (:func:`rise`): before its
   impact the sensor is at rest.
2. **Fit.** The samples left are the level, the step, and from the lobe's end the
   sensor's free ringing (``exp(-a s) cos(b s)``, ``exp(-a s) sin(b s)``, ``s`` from the
   lobe's peak, the sensor's resonance and damping): least squares, for every place of
   the step at once (the step column's part that the other columns do not explain, by
   cumulative sums: the reduction of the residual sum of squares is
   ``(r . u)**2 / (u . u - u' M (M' M)^-1 M' u)`` for the step column ``u`` and the
   residual ``r`` without it).
3. **Height.** The period means' height is read on the medians of windows that drift,
   hum and 1/f noise bend (seed 3 of a 0.614 N step 19 us before an onset read 0.449 N:
   its new level then lay outside the band between the two levels and the step was taken
   for the lobe's rise). The height is read again on the samples of the window, by the
   fit of the level, the free ringing and the step at its best place, and the lobe found
   again with it, until it stays (:func:`height_across`); that height places the step
   and is the step's.
4. **Inside the lobe.** A step at the lobe's end, the first sample after it, stands for
   a step anywhere inside the lobe. When it fits not worse than the best place by more
   than :data:`SEPARABLE_SIGMAS` (of the residual's noise), the step cannot be told from
   the impact: it is placed at the lobe's middle (at most half the lobe off) and
   flagged (the row's reason says so).
"""

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy.ndimage import label, maximum_filter1d, uniform_filter1d

from contactlab.inverse.local_baseline import _ringing
from contactlab.signals import MAD_TO_SIGMA

__all__ = [
    "SEPARABLE_SIGMAS",
    "difference_sigma",
    "height_across",
    "place_across",
    "read_across",
    "rise",
    "second_across",
]

SEPARABLE_SIGMAS = 4.0
"""A step fits better where it is placed than anywhere inside the main lobe when the
residual sum of squares is less by more than this many noise sigmas squared [-] (a
chi-squared change of one degree of freedom, at 4 sigma)."""


def difference_sigma(x):
    """Noise standard deviation of the samples ``x`` [N] read on their first differences:
    :data:`~contactlab.signals.MAD_TO_SIGMA` times the median absolute difference over
    ``sqrt(2)`` (a difference holds two samples' noise; drift and steps move few of
    them)."""
    return MAD_TO_SIGMA * np.median(np.abs(np.diff(x))) / np.sqrt(2.0)


QUIET_FRACTION = 0.25
"""The samples before a main lobe that a rise is told on, a quarter of a sensor period
[-] (:func:`rise`)."""

RISE_SIGMAS = 4.0
"""A rise leaves the band between the two levels by this many sample-noise sigmas [-]
(:func:`rise`)."""


def _lobe(x, level, height, period, far_noise):
    """``(start, stop)`` indices of the main lobe in ``x`` (module step 1), or None."""
    averaged = uniform_filter1d(x, period, mode="nearest")
    low, high = sorted((level, level + height))
    # outside the band between the two levels: a step moves the record within it, a
    # lobe beyond it (a lobe of the step's sign less than twice the step's height high
    # lies within the step's height of the new level: seed 83 of bench_steps)
    outside = np.maximum(averaged - high, low - averaged)
    # further than the step's height from both levels where a lobe is (the band's edges
    # move with 1/f noise, hum and drift: a lobe so taken can reach into the ringing),
    # else outside the band
    distance = np.minimum(np.abs(averaged - level), np.abs(averaged - level - height))
    far = distance > abs(height) + far_noise
    far = far if far.any() else outside > far_noise
    if not far.any():
        return None
    # the far stretch around the largest excursion, gaps shorter than a period bridged
    # (slow noise far from the levels elsewhere in the window is no lobe)
    stretches = label(maximum_filter1d(far.astype(np.int8), period + 1, mode="constant"))[0]
    peak = int(np.argmax(np.where(far, outside, -np.inf)))
    inside = np.flatnonzero(far & (stretches == stretches[peak]))
    start = max(0, int(inside[0]) - period)
    return rise(x[:peak], start, (low, high), period), min(x.size, int(inside[-1]) + period + 1)


def rise(x, start, band, period):
    """Where the main lobe rises in ``x`` (the record up to the lobe's largest
    excursion), searched from ``start`` (the period means' conservative start): the
    first sample that leaves the ``band`` ``(low, high)`` between the two levels [N] by
    more than :data:`RISE_SIGMAS` sample-noise sigmas or the median of the
    :data:`QUIET_FRACTION` of a period before it by twice that, unless the samples after
    it settle as a step does (as many, within the band and spread over no more than
    twice that), less half that stretch as a margin. Before its impact the sensor is at
    rest, so the samples there place a step a period or more nearer the onset than the
    period means do (a step 19 us before an onset at 1 MHz: seed 14 of the hard mix).
    The samples after the one that leaves are judged, not it: a lobe's rise goes on, a
    single sample out with the next ones back in the band is the noise's tail (1/f noise
    and hum move the level under white noise, and one sample 0.144 N off the head's
    level, 4.4 of these sigmas, 0.1 ms before the lobe, ended the head of seed 4 of a weak
    impact between two steps at 96 of the 100 samples it needs)."""
    quiet = max(2, round(QUIET_FRACTION * period))
    reach = RISE_SIGMAS * difference_sigma(x)

    def within(values):
        return values.min() >= band[0] - reach and values.max() <= band[1] + reach

    first = start + quiet
    if first < x.size:  # every sample's test at once: the medians of the quarter periods
        before = np.median(sliding_window_view(x[start : x.size - 1], quiet), axis=1)
        tail = x[first:]
        leaves = ~((tail >= band[0] - reach) & (tail <= band[1] + reach))  # NaN leaves
        leaves |= np.abs(tail - before) > 2.0 * reach
        for i in first + np.flatnonzero(leaves):
            if i < first:  # inside a step's settled stretch, passed over
                continue
            ahead = x[i + 1 : i + 1 + quiet]
            if ahead.size < quiet or np.ptp(ahead) > 2.0 * reach or not within(ahead):
                return max(start, i - quiet // 2)
            first = i + quiet + 1  # a step: the level it settles at is the one to follow
    return max(start, x.size - quiet // 2)


def _fit(x, kept, stop, peak, ring, fixed=()):
    """The least-squares fit of the level and the free ringing from the lobe's end (and
    steps at the ``fixed`` indices of ``kept``) on ``x[kept]``: its columns and
    residual, and for a step at every place of ``kept`` the residual sum of squares it
    takes off and the part of its column the other columns do not explain (module step
    2)."""
    sensor, dt = ring
    columns = _ringing(np.clip(kept - peak, 0, None) * dt, sensor)[0]
    columns[kept < stop] = 0.0  # the ringing is free from the lobe's end
    steps = [(np.arange(kept.size) >= j).astype(float) for j in fixed]
    m = np.column_stack([np.ones(kept.size), columns, *steps])
    y = x[kept]
    coefficients = np.linalg.lstsq(m, y, rcond=None)[0]
    residual = y - m @ coefficients
    # step column u_j: 1 from kept sample j on; its sums with the columns and the residual
    tails = np.cumsum(m[::-1], axis=0)[::-1]
    r_u = np.cumsum(residual[::-1])[::-1]
    gram = np.linalg.pinv(m.T @ m)
    u_u = (kept.size - np.arange(kept.size)) - np.einsum("ij,jk,ik->i", tails, gram, tails)
    gain = np.zeros(kept.size)
    valid = u_u > 1e-9 * kept.size
    valid[0] = False  # u_0 is the constant column itself
    gain[valid] = r_u[valid] ** 2 / u_u[valid]
    return {
        "coefficients": coefficients,
        "residual": residual,
        "gain": gain,
        "r_u": r_u,
        "valid": valid,
    }


def _kept(x, lobe):
    start, stop = lobe
    return np.r_[np.arange(start), np.arange(stop, x.size)]


HEIGHT_PASSES = 4
"""Most readings of the height across an impact, each with the lobe found with the one
before [-] (:func:`height_across`; on the near-step cases it stays after two)."""


def height_across(x, level, height, period, far_noise, ring):
    """The height [N] of a step found across an impact, read on the window's samples
    (module step 3): the least-squares fit of the level, the sensor's free ringing from
    the main lobe's end and a step at its best place (a sample outside the lobe, or the
    first after it for one inside), on the samples outside the lobe, the lobe found again
    with the height fitted, until it stays (at most :data:`HEIGHT_PASSES`).

    Parameters
    ----------
    x, level, height, period, far_noise, ring
        As for :func:`place_across`; ``height`` is the period means' reading [N].

    Returns
    -------
    float
        The height fitted, or ``height`` when the window holds no lobe with samples on
        both sides of it, or the fit gives the other sign.
    """
    lobe = _lobe(x, level, height, period, far_noise)
    fitted = height
    for _ in range(HEIGHT_PASSES):
        if lobe is None:
            break
        start, stop = lobe
        kept = _kept(x, lobe)
        if start == 0 or stop >= x.size:
            break
        peak = start + int(np.argmax(np.abs(x[start:stop] - level)))
        fit = _fit(x, kept, stop, peak, ring)
        valid = fit["valid"] & (np.sign(fit["r_u"]) == np.sign(height))
        if not valid.any():
            return height
        j = int(np.argmax(np.where(valid, fit["gain"], 0.0)))  # the step's best place
        fitted = float(_fit(x, kept, stop, peak, ring, fixed=(j,))["coefficients"][-1])
        if np.sign(fitted) != np.sign(height):
            return height
        again = _lobe(x, level, fitted, period, far_noise)
        if again == lobe:
            break
        lobe = again
    return fitted


def place_across(x, level, height, period, far_noise, ring):
    """Where a step lies in a window that holds an impact (module docstring).

    Parameters
    ----------
    x : numpy.ndarray
        The record in the window [N], the drift's slope taken off.
    level, height : float
        The level before the step and the step's height [N].
    period : int
        The sensor's period [samples].
    far_noise : float
        How far beyond the step's height a period mean must lie from both levels to be
        an impact's main lobe [N].
    ring : tuple
        ``(sensor, dt)``: the :class:`~contactlab.bodies.Sensor` whose free ringing is
        fitted and the sampling interval [s].

    Returns
    -------
    tuple or None
        ``(index, lobe)``: the first sample at the new level (index in ``x``) and, when
        it may lie anywhere inside the main lobe, the lobe's ``(start, stop)``, else
        None. None altogether when the window holds no lobe or too few samples.
    """
    lobe = _lobe(x, level, height, period, far_noise)
    if lobe is None:
        return None
    start, stop = lobe
    kept = _kept(x, lobe)
    if kept.size < 8:
        return None
    peak = start + int(np.argmax(np.abs(x[start:stop] - level)))
    fit = _fit(x, kept, stop, peak, ring)
    gain, residual = fit["gain"], fit["residual"]
    # a change of the other sign is no such step
    valid = fit["valid"] & (np.sign(fit["r_u"]) == np.sign(height))
    if not valid.any():
        return None
    gain[~valid] = 0.0
    j = int(np.argmax(gain))
    at_end = int(np.searchsorted(kept, stop))  # a step anywhere in the lobe
    if start > 0 and at_end < kept.size and valid[at_end]:
        rss = max(float(residual @ residual) - gain[j], 0.0)
        variance = rss / max(kept.size - fit["coefficients"].size - 1, 1)
        if j == at_end or gain[j] - gain[at_end] <= SEPARABLE_SIGMAS**2 * variance:
            return (start + stop) // 2, lobe
    return int(kept[j]), None


def read_across(x, level, height, period, far_noise, ring):
    """A step found across an impact read on the window's samples: its height
    (:func:`height_across`), its place (:func:`place_across`) with that height and, when
    placed outside the lobe, a second step on the lobe's other side
    (:func:`second_across`). Its parameters are :func:`height_across`'s.

    Returns
    -------
    height : float
        The height read again [N].
    placed : tuple or None
        :func:`place_across`'s result.
    other : tuple or None
        :func:`second_across`'s result (None when the step is not placed, or flagged
        inside the lobe).
    """
    height = height_across(x, level, height, period, far_noise, ring)
    placed = place_across(x, level, height, period, far_noise, ring)
    if placed is None or placed[1] is not None:
        return height, placed, None
    return height, placed, second_across(x, level, height, period, far_noise, ring, placed[0])


def second_across(x, level, height, period, far_noise, ring, index):
    """A second step on the other side of the impact's main lobe from the step placed at
    ``index`` (:func:`place_across`): two steps, one before an impact and one in its
    ringing, make one level change across it (their sum), which places one of them.

    Parameters
    ----------
    x, level, height, period, far_noise, ring
        As for :func:`place_across`.
    index : int
        The first step's place in ``x`` (outside the main lobe).

    Returns
    -------
    tuple or None
        ``(index, heights, sides)``: the second step's first sample at the new level
        (index in ``x``), the two steps' heights [N] fitted together (the first's,
        then the second's) and, for each, how many samples of ``x`` outside the lobe lie
        on either side of it within its stretch (before the lobe: from the window's
        start to the lobe; after it: from the lobe's end to the window's end) [-]; None when
        it would not be told from the impact (a place inside the lobe fits as well, by
        :data:`SEPARABLE_SIGMAS`) or there is no room.
    """
    lobe = _lobe(x, level, height, period, far_noise)
    if lobe is None:
        return None
    start, stop = lobe
    kept = _kept(x, lobe)
    at_end = int(np.searchsorted(kept, stop))
    first = int(np.searchsorted(kept, index))
    if start == 0 or at_end >= kept.size or first in (0, at_end):
        return None
    peak = start + int(np.argmax(np.abs(x[start:stop] - level)))
    fit = _fit(x, kept, stop, peak, ring, fixed=(first,))
    before = first >= at_end  # the first step lies after the lobe: look before it
    side = np.arange(kept.size) < at_end if before else np.arange(kept.size) >= at_end
    candidates = fit["valid"] & side
    candidates[at_end] = False
    if not candidates.any():
        return None
    gain = np.where(candidates, fit["gain"], 0.0)
    j = int(np.argmax(gain))
    rss = max(float(fit["residual"] @ fit["residual"]) - gain[j], 0.0)
    variance = rss / max(kept.size - fit["coefficients"].size - 1, 1)
    if fit["valid"][at_end] and gain[j] - fit["gain"][at_end] <= SEPARABLE_SIGMAS**2 * variance:
        return None
    both = _fit(x, kept, stop, peak, ring, fixed=(first, j))["coefficients"][-2:]
    sides = [(i, at_end - i) if i < at_end else (i - at_end, kept.size - i) for i in (first, j)]
    return int(kept[j]), (float(both[0]), float(both[1])), sides
