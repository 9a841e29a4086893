"""A force shape pushed through the sensor on a fine grid, compiled: the contact
families' unit signal of :class:`contactlab.inverse.lobe_model.LobeModel`.

The onset and family fits of every detected impact evaluate it a few hundred times
each (one Nelder-Mead step, one call); in numpy it was ``numpy.interp`` and
``scipy.signal.lfilter`` with their Python overheads, 30 % of ``find_impacts`` on the
realistic records of the tests. This loop does the same arithmetic in the same order
(``numpy.interp``'s slope and offset, ``lfilter``'s transposed direct form II), so its
values are those functions' to the last bit (``tests/contactlab/inverse/test_lobe_model.py``).
"""

import numpy as np

from contactlab.compiled import njit

__all__ = ["held_signal"]


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
