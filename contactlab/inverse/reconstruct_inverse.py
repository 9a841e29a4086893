"""The band-limited exact inverse of the sensor (``method="inverse"`` of
:func:`contactlab.inverse.reconstruct_force`).

``S2 = S1 + m1 x1''`` with ``x1 = S1 / (c1 s + k1)``, after a zero-phase Butterworth
low-pass of the signal: ``S2 = S1 + u'' / w1**2`` with ``u = S1 / (1 + 2 zeta1 s /
w1)``, ``u''`` by the 3-point stencil, accurate to ``(w dt)**2 / 12`` below the cutoff.

References
----------
Eichstaedt S., Elster C., Esward T.J., Hessling J.P. (2010) Deconvolution filters for
the analysis of dynamic measurement processes: a tutorial. Metrologia 47, 522-533.
DOI 10.1088/0026-1394/47/5/003
"""

import numpy as np

from contactlab import signals

__all__ = ["DEFAULT_CUTOFF_FACTOR", "band_limited_inverse"]

DEFAULT_CUTOFF_FACTOR = 2.0
"""Default cutoff of the inverse filter in units of the resonance. The inverse's gain
grows as ``(f / f1)**2`` above resonance, so at ``2 f1`` white noise is amplified about
four times; a contact long enough to be resolved has little content above it."""


def band_limited_inverse(t, y, dt, sensor, noise, window, options):
    """The ``"inverse"`` method of :func:`contactlab.inverse.reconstruct_force`: the
    force [N] on ``t``, its parameters and ``None`` (no spread: a stationary filter's is
    read on the baseline). ``noise`` and ``window`` are not used (the methods share one
    signature); ``options["cutoff"]`` [Hz] or :data:`DEFAULT_CUTOFF_FACTOR` resonances."""
    from scipy.signal import cont2discrete, lfilter

    cutoff = options["cutoff"]
    if cutoff is None:
        cutoff = DEFAULT_CUTOFF_FACTOR * sensor.resonance
    smooth = signals.lowpass(y, dt, cutoff)
    lag_time = 2.0 * sensor.damping_ratio / sensor.angular_frequency
    if lag_time > 0.0:
        # x1 = S1 / (c1 s + k1), up to the factor 1/k1: a first-order lag, exact for
        # piecewise-linear input (first-order hold). It starts on the lag's steady
        # response to the signal's initial ramp, u = S1 - tau S1': a cold start leaves a
        # transient whose curvature the inverse amplifies by 1 / (4 zeta**2).
        num, den, _ = cont2discrete(([1.0], [lag_time, 1.0]), dt, method="foh")
        num = np.ravel(num)
        ramp_output = smooth[0] - lag_time * (smooth[1] - smooth[0]) / dt
        start = [ramp_output - num[0] * smooth[0]]
        lagged = lfilter(num, den, smooth, zi=start)[0]
    else:
        lagged = smooth
    curvature = np.empty_like(lagged)
    curvature[1:-1] = (lagged[2:] - 2.0 * lagged[1:-1] + lagged[:-2]) / dt**2
    # the 3-point stencil needs both neighbours: the end samples take their neighbour's
    curvature[0], curvature[-1] = curvature[1], curvature[-2]
    force = smooth + curvature / sensor.angular_frequency**2
    params = {"cutoff [Hz]": float(cutoff), "filter": "Butterworth order 4, zero-phase"}
    return force, params, None  # a stationary filter: its spread is read on the baseline
