"""Exact propagation of linear pieces against scipy's matrix exponential."""

import numpy as np
import pytest
from scipy.linalg import expm

from contactlab.solver.propagators import LinearFlow, linear_flow

MATRICES = {
    # the paper's 40 kHz sensor alone, underdamped (zeta 0.02)
    "sensor": [[0.0, 1.0], [-6.3e10, -1.0e4]],
    # overdamped: two real modes
    "overdamped": [[0.0, 1.0], [-1.0e6, -1.0e4]],
    # critically damped: defective, the expm fallback
    "critical": [[0.0, 1.0], [-1.0e8, -2.0e4]],
    # grain and sensor coupled by a linear contact
    "coupled": [[0, 1, 0, 0], [-7e10, -12, 1e9, 10], [0, 0, 0, 1], [2e9, 20, -2e9, -20]],
}


@pytest.mark.parametrize("name", MATRICES)
@pytest.mark.parametrize("n", [5, 70, 20001])
def test_trajectory_and_grid_match_expm(name, n):
    matrix = np.array(MATRICES[name], dtype=float)
    z0 = np.arange(1.0, matrix.shape[0] + 1) * 1e-6
    trajectory = LinearFlow(matrix).trajectory(z0)
    tau = 1.234e-6 + 2.5e-8 * np.arange(n)
    pick = slice(None, None, max(1, n // 50))
    exact = np.array([expm(matrix * t) @ z0 for t in tau[pick]])
    scale = np.max(np.abs(exact), axis=0)
    # modal sums of a well-conditioned eigenbasis (cond < 1e8 by construction, here < 1e4):
    # 1e-11 of each component's range; the grid's tables add a few roundings more
    assert np.max(np.abs(trajectory(tau[pick]) - exact) / scale) < 1e-11
    out = np.empty((matrix.shape[0], n)).T  # column-contiguous, as the result stores it
    assert np.max(np.abs(trajectory.grid(tau[0], 2.5e-8, n, out=out)[pick] - exact) / scale) < 1e-11


def test_flows_are_shared_between_equal_matrices():
    assert linear_flow(MATRICES["sensor"]) is linear_flow(np.array(MATRICES["sensor"]))
    assert linear_flow(MATRICES["sensor"]) is not linear_flow(MATRICES["overdamped"])


def test_critical_damping_falls_back_to_expm():
    assert not LinearFlow(MATRICES["critical"]).modal
    assert LinearFlow(MATRICES["sensor"]).modal
