"""The local baseline of one impact and its impulse (dem_check.campaign.local) against the
forward model's exact numbers and closed forms (noise-free, so any error is the method's)."""

import math

import numpy as np
import pytest

from dem_check.campaign import realistic_record
from dem_check.campaign.local import local_baseline


def test_free_ringing_integral_in_closed_form(hard_setup):
    """A sensor ringing freely from ``t = 0``: the method's closed-form tail equals the
    integral of the ringing to the end of its decay (trapezoid on a fine grid)."""
    _, sensor, _ = hard_setup
    w, zeta = sensor.angular_frequency, sensor.damping_ratio
    a, b = zeta * w, w * math.sqrt(1.0 - zeta**2)
    dt = 1e-7
    t = (np.arange(22000) - 2000) * dt  # -0.2 to 2 ms (10 decay times 1 / (zeta w))
    s = np.maximum(t, 0.0)
    ringing = np.where(t >= 0.0, np.exp(-a * s) * (0.7 * np.cos(b * s) + 0.4 * np.sin(b * s)), 0.0)
    line = 0.3 - 20.0 * t  # a drifting baseline [N]
    # the ringing jumps at t = 0 (free from there on): nothing is integrated before it
    found = local_baseline(t, ringing + line, (-2e-4, -1e-5), 0.0, 0.0, t[-1], sensor)
    exact = (0.7 * a + 0.4 * b) / w**2  # integral of the ringing from 0 to infinity
    # measured 4e-16: least squares on exact data, only rounding
    assert found.impulse == pytest.approx(exact, rel=1e-12)
    np.testing.assert_allclose(found.values, line, atol=1e-9)


def test_impulse_of_an_impact_on_a_drifting_baseline(hard_setup):
    """An impact of the model with a linear drift of 40 N/s: the impulse to the contact's
    end plus the ringing's tail equals the model's contact impulse."""
    grain, sensor, law = hard_setup
    record = realistic_record(
        grain, sensor, law, [1.5], [1e-3], length=4e-3, sample_rate=2e6, noise=0.0
    )
    t, y = np.asarray(record.trace.t), np.asarray(record.trace.values)
    true = record.truth.iloc[0]
    drift = 0.05 + 40.0 * t
    onset, contact = true["onset [s]"], true["contact_time [s]"]
    base = (onset - 4e-4, onset - 1e-5)
    found = local_baseline(t, y + drift, base, base[1], onset + contact + 2.5e-5, t[-1], sensor)
    # noise-free: the line fits the drift exactly and the ringing after the contact is
    # the model's free ringing; measured 1.0e-5 relative, the trapezoid rule over the
    # 2 MHz samples of the contact (the model's impulse is integrated exactly)
    assert found.impulse == pytest.approx(true["impulse [N*s]"], rel=1e-4)
    np.testing.assert_allclose(found.values, drift, atol=1e-9)
