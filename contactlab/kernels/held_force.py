"""A force shape pushed through the sensor on a fine grid, compiled: the contact
families' unit signal of :class:`contactlab.inverse.lobe_model.LobeModel`.

The onset and family fits of every detected impact evaluate it a few hundred times
each (one Nelder-Mead step, one call); in numpy it was ``numpy.interp`` and
``scipy.signal.lfilter`` with their Python overheads, 30 % of ``find_impacts`` on the
realistic records of the tests. This loop does the same arithmetic in the same order
(``numpy.interp``'s slope and offset, ``lfilter``'s transposed direct form II), so its
values are those functions' to the last bit (``tests/contactlab/inverse/test_held_force.py``).
The signal sampled at the window's times, which every step evaluates as well
(:meth:`~contactlab.inverse.lobe_model.LobeModel.response`), was ``numpy.interp``;
:func:`sampled_signal` is its loop, equal to the last bit too.
"""

import numpy as np

from contactlab.compiled import njit

__all__ = ["held_signal", "sampled_signal"]


@njit(cache=True, error_model="numpy")
def held_signal(step, count, tau, u, h, b, a):
    """The force ``h((s - step / 2) / tau)`` (zero outside ``u``'s span) filtered by
    ``b / a`` on the grid ``s = k step``, ``k = -1, 0, ..., count - 1``.

    Parameters
    ----------
    step : float
        Grid step [s].
    count : int
        Grid points after the first, ``k = -1`` [-].
    tau : float
        The contact's duration [s], > 0.
    u, h : numpy.ndarray
        The unit force shape: time over the duration [-] (increasing) and force over its
        peak [-] (:func:`contactlab.inverse.lobe_model.force_shape`).
    b, a : numpy.ndarray
        The sensor's discrete filter on ``step``, of one length, ``a[0] = 1``
        (``scipy.signal.cont2discrete``).

    Returns
    -------
    times : numpy.ndarray
        ``s - step / 2`` [s], the time since the force's start.
    values : numpy.ndarray
        The filtered force [-] (the signal of a unit-peak force).
    """
    times = np.empty(count + 1)
    values = np.empty(count + 1)
    order = b.size
    state = np.zeros(order - 1)
    last = u.size - 1
    j = 0
    for i in range(count + 1):
        s = float(i - 1) * step
        x = (s - 0.5 * step) / tau
        times[i] = s - 0.5 * step
        if x != x:  # a duration of zero or NaN: numpy.interp gives NaN
            force = np.nan
        elif x < u[0] or x > u[last]:
            force = 0.0
        elif x == u[last]:
            force = h[last]
        else:  # numpy.interp's formula on the interval that holds x
            while u[j + 1] <= x:
                j += 1
            slope = (h[j + 1] - h[j]) / (u[j + 1] - u[j])
            force = slope * (x - u[j]) + h[j]
        value = state[0] + b[0] * force  # lfilter's order of operations
        for n in range(order - 2):
            state[n] = state[n + 1] + force * b[n + 1] - value * a[n + 1]
        state[order - 2] = force * b[order - 1] - value * a[order - 1]
        values[i] = value
    return times, values


@njit(cache=True, error_model="numpy")
def sampled_signal(t, t0, s, r):
    """``numpy.interp(t - t0, s, r, left=0.0)``: the unit signal ``r`` on its grid ``s``
    sampled at the window's times since the force's start, with numpy's arithmetic
    (its index, its slope and offset, its fall-backs at NaN), so to the last bit.

    Parameters
    ----------
    t : numpy.ndarray
        The window's sample times [s].
    t0 : float
        The force's start [s].
    s, r : numpy.ndarray
        The grid [s] (strictly increasing) and the signal on it [-] (:func:`held_signal`).

    Returns
    -------
    numpy.ndarray
        The signal at ``t`` [-]: 0 before the grid, its last value after it.
    """
    last = s.size - 1
    values = np.empty(t.size)
    j = -1  # no interval found yet
    for i in range(t.size):
        x = t[i] - t0
        if x != x:
            values[i] = x
            continue
        if x < s[0]:
            values[i] = 0.0
            continue
        if x > s[last]:
            values[i] = r[last]
            continue
        if j < 0 or x < s[j]:  # the first sample, or the times went back: bisect
            j = np.searchsorted(s, x, side="right") - 1
        while j < last and s[j + 1] <= x:
            j += 1
        if j == last or s[j] == x:
            values[i] = r[j]
            continue
        slope = (r[j + 1] - r[j]) / (s[j + 1] - s[j])
        value = slope * (x - s[j]) + r[j]
        if value != value:  # numpy's second try, from the interval's other end
            value = slope * (x - s[j + 1]) + r[j + 1]
            if value != value and r[j] == r[j + 1]:
                value = r[j]
        values[i] = value
    return values
