"""The noise window of a single-impact trace: baseline samples that hold none of the pulse.

An oscilloscope triggers when the signal crosses a level, so the first microseconds of the
pulse lie *before* ``t = 0``: a noise window "every sample before the trigger" holds the
start of the pulse, over-estimates the noise (2.2x on ``data/traces/keysight.csv``) and
makes every chi-squared computed with it too small (4.5x there). The window found here
ends before the pulse's detected onset by a guard as long as the pulse's rise, so the part
of the pulse below the detection threshold stays out of it as well.
"""

import numpy as np

from contactlab import signals
from contactlab.inverse._signal import BASELINE_MIN_SAMPLES, check_baseline_samples

__all__ = ["MAX_REFINEMENTS", "clean_noise_window"]

MAX_REFINEMENTS = 5
"""Most re-detections of the onset with the refined noise; each one moves the window end
to an earlier time, and on every trace tried it stops moving after two."""


def _pulse_start(t, y, window, k):
    """The earliest time the pulse may have started [s].

    The onset is the ``k``-sigma crossing of :func:`contactlab.signals.detect_onset`
    with the statistics of ``window``. Before it the pulse is below the threshold but not
    zero; a rise from zero to the peak that is a power of time, ``(t / T)**a`` with
    ``a <= 3``, crosses a threshold of 5 % of its peak after ``0.37 T`` at most, so going
    back from the onset by the whole onset-to-peak time ``T`` clears it.
    """
    mean = signals.baseline(t, y, window, name="baseline_window").mean
    onset = signals.detect_onset(t, y, window, k, name="baseline_window")
    after = t >= onset
    peak = t[after][int(np.argmax(np.abs(y[after] - mean)))]
    return onset - (peak - onset)


def clean_noise_window(t, y, k=5.0):
    """The record's start up to the pulse's start, with the pulse's rise as a guard.

    Starting from the samples before ``t = 0``, the onset is detected with the window's
    noise, the window is cut to end one onset-to-peak time before the onset, and the onset
    is detected again with the cleaner (smaller) noise, until the window's end stops
    moving.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times [s], strictly increasing, with samples before ``t = 0``.
    y : numpy.ndarray
        Signal on ``t`` (any unit) holding one pulse.
    k : float, default 5.0
        Onset threshold in noise standard deviations [-].

    Returns
    -------
    (float, float)
        The window ``[start, end)`` [s].

    Raises
    ------
    ParameterError
        When fewer than :data:`~contactlab.inverse._signal.BASELINE_MIN_SAMPLES` samples
        lie before the pulse (the message says how to give a window), or no pulse stands
        out of the noise.
    """
    window = (float(t[0]), 0.0)
    for _ in range(MAX_REFINEMENTS):
        count = int(signals.in_window(t, window).sum())
        if count < BASELINE_MIN_SAMPLES:
            break
        end = min(_pulse_start(t, y, window, k), window[1])
        moved = abs(end - window[1])
        window = (window[0], end)
        if moved < t[1] - t[0]:
            break
    check_baseline_samples(t, window, found=True)
    return window
