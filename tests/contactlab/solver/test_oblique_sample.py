"""The compiled sampler of a solved oblique contact (:mod:`contactlab.kernels.oblique_sample`)
against a sample-by-sample reading of the same arrays: the step found by a search, its
interpolant through :func:`contactlab.kernels.dop853.interpolate` (issue 25)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.kernels.dop853 import interpolate

GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
HERTZ = cl.laws.Hertz.from_material(GRAIN.material())
SENSOR = cl.Sensor(mass=1e-3, stiffness=1e7, damping=2.0)
MINDLIN = cl.laws.Mindlin.from_material(cl.analytic.Material(3.8e11, 0.23, GRAIN.radius), 0.092)


def _impact(sensor):
    """Stick, slide and stick again at 5 deg: five phases, warped and timed steps."""
    return cl.simulate_oblique(GRAIN, sensor, HERTZ, MINDLIN, 3.9, math.radians(5.0))


RESULTS = {"flat": _impact(cl.Sensor.rigid()), "sensor": _impact(SENSOR)}


def _one_by_one(contact, t):
    """The state (7,) at ``t`` [s]: the last phase and step starting at or before it,
    found by ``numpy.searchsorted``, read with the DOP853 interpolant."""
    table, (_, w_t, w_h, w_y, w_F), (_, s_t, s_h, s_y, s_F) = (
        contact._table,
        contact._warp,
        contact._steps,
    )
    k = max(int(np.searchsorted(table[:, 0], t, side="right")) - 1, 0)
    t0, _, _, switch, w0, w1, s0, s1 = table[k]
    w0, w1, s0, s1 = int(w0), int(w1), int(s0), int(s1)
    out = np.empty(8)
    if w1 > w0 and (s1 == s0 or t - t0 < switch):
        s = math.sqrt(math.sqrt(max(t - t0, 0.0)))
        j = min(max(w0 + int(np.searchsorted(w_t[w0:w1], s, side="right")) - 1, w0), w1 - 1)
        interpolate(w_F[j], w_y[j], (s - w_t[j]) / w_h[j], out)
    else:
        j = min(max(s0 + int(np.searchsorted(s_t[s0:s1], t, side="right")) - 1, s0), s1 - 1)
        interpolate(s_F[j], s_y[j], (t - s_t[j]) / s_h[j], out[:7])
    return out[:7]


@pytest.mark.parametrize("kind", ["flat", "sensor"])
@given(fractions=st.lists(st.floats(0.0, 1.0), min_size=1, max_size=40))
def test_step_by_step_sampling_reads_the_steps_a_search_finds(kind, fractions):
    res = RESULTS[kind]
    contact = res._contact
    # the first microsecond holds the warped steps: half the times there
    times = np.sort([f * (1e-9 if i % 2 else contact.end) for i, f in enumerate(fractions)])
    states = contact(times)[0]
    expected = np.array([_one_by_one(contact, t) for t in times])
    if res.sensor.is_rigid:
        expected[:, :2] = 0.0  # a wall does not move: x1 = v1 = 0, not interpolated
    # the same operations in the same order on the same numbers: equal bits
    np.testing.assert_array_equal(states, expected)


@pytest.mark.parametrize("kind", ["flat", "sensor"])
def test_output_grid_is_the_sampled_contact(kind):
    res = RESULTS[kind]
    inside = res.t < res.contact_time
    states, raw, normal, tangential, slip = res._contact(res.t[inside])
    grid = np.column_stack(
        [
            res.x1,
            res.v1,
            res.x2,
            res.v2,
            res.tangential_velocity_signal,
            res.angular_velocity_signal,
        ]
    )
    # one sampler, called on the grid in one piece or again here: equal bits
    np.testing.assert_array_equal(grid[inside], states[:, :6])
    np.testing.assert_array_equal(res.normal_force[inside], normal)
    np.testing.assert_array_equal(res.tangential_force[inside], tangential)
    np.testing.assert_array_equal(res.slip[inside], slip)
    np.testing.assert_array_equal(raw.clip(0.0), normal)


def test_peaks_are_the_largest_forces_on_the_phase_nodes():
    res = RESULTS["sensor"]
    times = np.concatenate(
        [np.linspace(t0, t1, 513, endpoint=False) for t0, t1, _ in res._contact.phases()]
    )
    _, _, normal, tangential, _ = res._contact(times)
    # the same nodes (numpy's linspace written out) and forces: equal bits
    assert res._contact.peaks(513) == (normal.max(), np.abs(tangential).max())
    assert res.peak_normal_force == max(normal.max(), res.normal_force.max())


def test_decreasing_times_and_short_outputs_are_refused():
    contact = RESULTS["flat"]._contact
    with pytest.raises(ParameterError, match="times"):
        contact(np.array([2e-6, 1e-6]))
    short = (np.empty((7, 1)), *np.empty((4, 1)))
    with pytest.raises(ParameterError, match="out"):
        contact(np.array([1e-6, 2e-6]), short)


def test_grid_after_the_contact_is_free_flight():
    """After the separation no force acts: the grain keeps its end velocities, on a wall it
    flies at ``x2(t1) + v2(t1) (t - t1)`` and the plate rests; a sensor's plate rings as
    the free flight's exact states (:func:`contactlab.solver.exact.free_flight`)."""
    from contactlab.solver.exact import free_flight
    from contactlab.solver.system import System

    for kind, res in RESULTS.items():
        after = res.t >= res.contact_time
        end, final = res.contact_time, res._final
        assert after.sum() > 1000  # the window holds free flight (ringing or the wall's 1.5x)
        # the grid's times are arange(n) / sample_rate, as they were written in numpy
        np.testing.assert_array_equal(res.t, np.arange(res.t.size) / res.sample_rate)
        for signal in (res.normal_force, res.tangential_force, res._raw):
            assert not signal[after].any()
        # the end values themselves, copied: equal bits
        assert (res.tangential_velocity_signal[after] == final[4]).all()
        assert (res.angular_velocity_signal[after] == final[5]).all()
        assert (res.slip[after] == final[4] - GRAIN.radius * final[5]).all()
        if kind == "flat":
            # the same operations as the closed form written here: equal bits
            x2 = (res.t[after] - end) * final[3] + final[2]
            np.testing.assert_array_equal(res.x2[after], x2)
            assert (res.v2[after] == final[3]).all() and not res.x1[after].any()
        else:
            system = System(GRAIN, res.sensor)
            free = free_flight(system, HERTZ, 0.0, end, final[:4], res.duration - end)[0]
            states = free.states(res.t[after] - end)
            # the plate's rows are these exact states, written by the same numpy code
            np.testing.assert_array_equal(np.column_stack([res.x1, res.v1])[after], states[:, :2])
            np.testing.assert_array_equal(res.x2[after], states[:, 2])
