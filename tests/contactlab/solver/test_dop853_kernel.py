"""The compiled DOP853 kernel against the Python stepper it ports, one step at a time, and
its compiled dense evaluation against the per-time one."""

import numpy as np
import pytest
from scipy.integrate import DOP853

import contactlab as cl
from contactlab.kernels import dop853 as kernel
from contactlab.kernels.model_rhs import NORMAL
from contactlab.kernels.power import pack, rhs
from contactlab.laws import HertzDamped, HuntCrossley
from contactlab.solver import adaptive
from contactlab.solver.dop853 import Stepper
from contactlab.solver.system import System

EPS = np.finfo(float).eps
V0, RTOL = 2.0, 1e-6  # impact speed [m/s], relative tolerance
ATOL = 1e-3 * RTOL * np.array([V0 * 1e-6, V0, V0 * 1e-6, V0])  # as adaptive_contact sets it
SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
LAWS = [HertzDamped(1.5e6, 4.175), HuntCrossley(3e7, 2.2, 0.1)]
STATES = [
    [0.0, 0.0, 1e-9, V0],  # just after a touch
    [1e-7, 0.01, 3.1e-6, 1.5],  # loading
    [2e-7, -0.02, 3e-5, -0.5],  # unloading
]


def error_rounding(K, y, y_new):
    """Bound on the relative rounding of DOP853's error norm for stages ``K`` (13, n).

    The norm is built from ``E5 @ K`` and ``E3 @ K``, sums over 13 stages that cancel
    to ``(h/T)**8`` of their terms: each component's rounding is at most 14 eps of its
    terms' absolute sum, and the squared norm carries twice that, weighted by the
    component's share.
    """
    scale = ATOL + np.maximum(np.abs(y), np.abs(y_new)) * RTOL
    shares = []
    for table in (DOP853.E5, DOP853.E3):
        err = (table @ K) / scale
        terms = (np.abs(table)[:, None] * np.abs(K)).sum(axis=0) / scale
        shares.append(2.0 * np.sum(np.abs(err) * terms) / np.sum(err**2))
    return 14 * EPS * max(shares)


@pytest.mark.parametrize("y", STATES)
@pytest.mark.parametrize("law", LAWS, ids=repr)
def test_one_step_as_the_python_stepper(paper_grain, law, y):
    system, branch = System(paper_grain, SENSOR), law.branch("load")
    par = pack(branch.power, system.m1, system.k1, system.c1, system.m2, system.rigid)
    y = np.array(y)
    f = np.empty(4)
    rhs(y, par, False, f)
    python = Stepper(system.rhs(branch.force), 0.0, y, RTOL, ATOL)
    h_try = kernel.initial_step(y, f, RTOL, ATOL, par, False)
    # the same norms and one right-hand side: measured equal; 4 eps for sum order
    assert h_try == pytest.approx(python.initial_step(), rel=4 * EPS)
    python = Stepper(system.rhs(branch.force), 0.0, y, RTOL, ATOL, first_step=h_try)
    assert python.step(1.0)
    K, y_new, f_new = np.empty((kernel.WORK_ROWS, 4)), np.empty(4), np.empty(4)
    ok, _, h_next, h = kernel.step(
        0.0, y, f, h_try, 1.0, RTOL, ATOL, par, False, K, y_new, f_new, NORMAL
    )
    assert ok
    assert h == h_try == python.t  # accepted at once, by both: the step is the same number
    # a state is y plus 12 stage terms: rounding within 16 eps of y + h |f| per component
    scale = np.abs(y) + h * np.abs(K[: kernel.STAGES]).max(axis=0)
    assert np.all(np.abs(y_new - python.y) <= 16 * EPS * scale)
    # the next step: h * 0.9 * err**(-1/8), err rounded as error_rounding bounds it
    allowed = error_rounding(K[: kernel.STAGES + 1], y, y_new) / 8.0 + 4 * EPS
    assert h_next == pytest.approx(python._h, rel=allowed)
    F = np.empty((7, 4))
    kernel.interpolant(K, h, y, y_new, f_new, par, False, F, NORMAL)
    # rows 0-1 hold delta = y_new - y once: within 16 eps of the state's scale, as y_new;
    # row 2 holds 2 delta - h (f_new + f_old): twice that, plus 2 eps of the slopes'
    # term (measured 17.5 eps on one CPU); rows 3-6 sum 16 stages h D K, three of them
    # the right-hand side at stage
    # states rounded apart -- near the touch (d = 1e-9 m against h v = 3e-9 m, force
    # ~ d**2.2) that moves a stage by tens of eps: measured 57 eps of h |D| @ |K|
    rows = np.empty((7, 4))
    rows[:2] = 16 * EPS * scale
    rows[2] = 34 * EPS * scale
    rows[3:] = 128 * EPS * h * (np.abs(DOP853.D) @ np.abs(K[: kernel.STAGES + 4]))
    assert np.all(np.abs(F - python.interpolant()) <= rows)


def test_dense_states_equal_the_per_time_evaluation(paper_grain):
    system, branch = System(paper_grain, SENSOR), LAWS[0].branch("load")
    start, steps, _, _ = adaptive.compiled_piece(
        system, branch.power, 37e-6, np.array([0.0, 0.0, 0.0, V0]), 1e-3, RTOL, ATOL, True
    )
    rng = np.random.default_rng(20261125)
    for dense in (start, steps):
        bounds = dense.boundaries
        span = bounds[-1] - bounds[0]
        # times inside, outside (read on the nearest step, up to a fifth of the span
        # away), and every step boundary, in random order
        times = rng.permutation(
            np.concatenate(
                [rng.uniform(bounds[0] - 0.2 * span, bounds[-1] + 0.2 * span, 500), bounds]
            )
        )
        assert times.min() < bounds[0] and times.max() > bounds[-1]
        per_time = np.array([dense.at(t) for t in times])
        # the same step choice (bisect_right vs searchsorted 'right') and the same
        # operations in the same order: equal to the last bit
        np.testing.assert_array_equal(dense(times), per_time)
