"""Sensor response to a force pulse."""

import math

import numpy as np

from contactlab.errors import ParameterError
from contactlab.validation import (
    check_positive,
)

__all__ = ["half_sine_residual_amplitude"]


def half_sine_residual_amplitude(pulse_duration, period):
    """Residual vibration of an undamped oscillator after a half-sine force pulse.

    Parameters
    ----------
    pulse_duration : float
        Duration tau of the pulse F0 sin(pi t / tau), 0 <= t <= tau [s].
    period : float
        Natural period T of the oscillator [s].

    Returns
    -------
    float
        Amplitude of the free vibration after the pulse divided by the static deflection
        F0 / k under the peak force [-] (the residual shock response spectrum).

    Notes
    -----
    With r = tau / T, Duhamel's integral gives

    A_res / (F0/k) = 4 r |cos(pi r)| / |1 - 4 r^2| = 2 pi r / (1 + 2 r) |sinc((1 - 2r)/2)|,

    sinc(x) = sin(pi x) / (pi x); the second form is used (no 0/0 at r = 1/2, where the
    value is pi/2). Zeros at r = 3/2, 5/2, ...; for r -> 0 it tends to 4 r, the response
    to the impulse 2 F0 tau / pi.

    References
    ----------
    .. [1] A. G. Piersol, T. L. Paez (eds.), *Harris' Shock and Vibration Handbook*,
       6th ed., McGraw-Hill, 2010: transient response to pulse functions.
    """
    tau = check_positive("pulse_duration", pulse_duration, "s")
    t = check_positive("period", period, "s")
    r = tau / t
    if not math.isfinite(r):
        raise ParameterError(
            f"period = {t!r} s is too short for pulse_duration = {tau!r} s: their ratio "
            "overflows the float range"
        )
    return 2.0 * math.pi * r / (1.0 + 2.0 * r) * abs(float(np.sinc(0.5 - r)))
