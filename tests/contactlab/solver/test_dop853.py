"""The lean DOP853 stepper against scipy's DOP853 (same method) and a closed form."""

import numpy as np
import pytest
from scipy.integrate import DOP853

from contactlab.kernels.segments import DenseSteps
from contactlab.solver.dop853 import Stepper

OMEGA, ZETA = 2.5e5, 0.02  # the paper's 40 kHz sensor [rad/s], damping ratio [-]


def oscillator(y):
    return np.array([y[1], -(OMEGA**2) * y[0] - 2 * ZETA * OMEGA * y[1]])


def exact(t, x0=1e-6):
    """Free damped oscillator from rest at x0 [m]."""
    wd = OMEGA * np.sqrt(1 - ZETA**2)
    decay = np.exp(-ZETA * OMEGA * t)
    return x0 * decay * (np.cos(wd * t) + ZETA * OMEGA / wd * np.sin(wd * t))


def run(rtol, t_end=1e-4):
    atol = 1e-3 * rtol * np.array([1e-6, 0.25])
    ours = Stepper(oscillator, 0.0, [1e-6, 0.0], rtol, atol)
    steps = []
    while ours.t < t_end:
        assert ours.step(t_end)
        steps.append((ours.t_old, ours.t - ours.t_old, ours.y_old, ours.interpolant()))
    return ours, DenseSteps(*zip(*steps, strict=True))


def test_same_steps_as_scipy():
    ours, dense = run(1e-8)
    ref = DOP853(lambda t, y: oscillator(y), 0.0, [1e-6, 0.0], 1e-4, rtol=1e-8, atol=ours._atol)
    times = [0.0]
    while ref.status == "running":
        ref.step()
        times.append(ref.t)
    # identical method, tables and control: the same number of steps; the step sizes
    # follow the error norms continuously, so rounding in the norms (a dot product here, a
    # numpy norm there) moves them by ~1e-8 relative, and the end state with them
    assert len(dense.boundaries) == len(times)
    np.testing.assert_allclose(dense.boundaries, times, rtol=1e-7)
    np.testing.assert_allclose(ours.y, ref.y, rtol=1e-9, atol=1e-9 * np.abs(ref.y).max())


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_dense_output_follows_the_closed_form(rtol):
    _, dense = run(rtol)
    t = np.linspace(0.0, 1e-4, 5001)
    error = np.max(np.abs(dense(t)[:, 0] - exact(t))) / 1e-6
    # global error of an order-8 method at local tolerance rtol over ~4 periods: a few
    # hundred times rtol, and the 7th-order interpolant adds no more than that
    assert error < 300 * rtol
    # scalar and vector evaluation agree, and writing into a column-major buffer works
    np.testing.assert_allclose(dense.at(3.3e-5), dense(np.array([3.3e-5]))[0], rtol=1e-14)
    out = np.empty((2, t.size)).T
    np.testing.assert_array_equal(dense(t, out=out), dense(t))
