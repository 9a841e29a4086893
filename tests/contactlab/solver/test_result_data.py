"""``ImpactResult`` holds data (issue 25): its segments are arrays and numbers, evaluated
by :mod:`contactlab.kernels.segments` below the result, and a contact piece's force is the
law's branch formula; no object or closure of the solver is kept.

Every path of the solver is covered: the compiled loop (linear "exact", damped Hertz
"adaptive"), the Python pieces (a law with branches and history, exact and adaptive; a
Hertz-family law off the compiled exponent), the prescribed pulse, the Euler reference,
on the disc sensor and on a wall.
"""

import dataclasses
import inspect
import pickle
import types
import warnings

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import contactlab as cl
from contactlab.kernels.segments import DenseSteps
from contactlab.result import ImpactResult

GRAIN = cl.Grain(diameter=5e-3, density=765.0)
DISC = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
L = cl.laws
CASES = {
    "linear exact (compiled)": (DISC, L.LinearViscoelastic(1e5, 1.0), "auto"),
    "linear on a wall": (cl.Sensor.rigid(), L.LinearViscoelastic(1e5, 1.0), "auto"),
    "damped Hertz (compiled)": (DISC, L.HertzDamped(1.5e6, 0.05), "auto"),
    "Hunt-Crossley n 1.7 (Python DOP853)": (DISC, L.HuntCrossley(1.5e6, 1.7, 0.2), "auto"),
    "Thornton (branches, history)": (DISC, L.Thornton(1e8, 2.5e-3, 3e6), "auto"),
    "linear plastic exact (branches)": (DISC, L.LinearPlastic(1e5, 3.0), "exact"),
    "prescribed pulse": (DISC, L.PlasticTrapezoid(50e-6, 10e-6), "auto"),
    "Euler": (DISC, L.LinearViscoelastic(1e5, 1.0), "euler"),
}


def _solve(case):
    sensor, law, method = CASES[case]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Euler's coarse step: its audit warns, as documented
        return cl.simulate_impact(
            GRAIN, sensor, law, 2.0, method=method, time_step=1e-9, audit=False
        )


def _contents(obj):
    """Every object a segment holds, itself included (dataclass fields, attributes,
    tuples)."""
    yield obj
    if dataclasses.is_dataclass(obj):
        children = [getattr(obj, f.name) for f in dataclasses.fields(obj)]
    elif isinstance(obj, DenseSteps):
        children = list(vars(obj).values())
    elif isinstance(obj, (tuple, list)):
        children = list(obj)
    else:
        children = []
    for child in children:
        yield from _contents(child)


@pytest.mark.parametrize("case", CASES)
def test_segments_hold_no_function_and_nothing_of_the_solver(case):
    res = _solve(case)
    for held in _contents(res.segments):
        assert not isinstance(held, (types.FunctionType, types.MethodType)), (case, held)
        assert not type(held).__module__.startswith("contactlab.solver"), (case, held)


@pytest.mark.parametrize("case", CASES)
def test_a_result_rebuilt_from_pickled_segments_is_the_same_to_the_last_bit(case):
    """Plain data survives pickling (a closure does not); the copy gives every signal and
    headline number bit for bit."""
    res = _solve(case)
    kept = inspect.signature(ImpactResult).parameters.keys() - {"segments", "headline"}
    copy = ImpactResult(
        segments=pickle.loads(pickle.dumps(res.segments)),
        **{name: getattr(res, name) for name in kept},
    )
    reference = res.grid_reading()  # the same reading, from the original segments
    for name in ("contact_force", "sensor_force", "x1", "v1", "x2", "v2"):
        assert np.array_equal(getattr(copy, name), getattr(res, name)), (case, name)
    for name in ("peak_contact_force", "peak_sensor_force", "impulse", "rebound_velocity"):
        assert getattr(copy, name) == getattr(reference, name), (case, name)
    assert copy.energy_balance == res.energy_balance, case


FORMULA_CASES = [c for c in CASES if not CASES[c][1].prescribed and CASES[c][2] != "euler"]
"""The law's force (not the pulse's prescribed one, nor Euler's recorded step force)."""


@pytest.mark.parametrize("case", FORMULA_CASES)
def test_the_contact_force_is_the_laws_formula_on_the_states(case):
    """In contact, the force the result reports is the law's branch formula at the
    result's own states, clipped at zero (laws hold forces): read back through the law's
    vectorised force with the contact's largest overlap as its history."""
    res = _solve(case)
    start, end = res.contact_intervals[0]
    inside = (res.t > start) & (res.t < end)
    t, d, r = res.t[inside], (res.x2 - res.x1)[inside], (res.v2 - res.v1)[inside]
    # the largest overlap lies between two samples: located on the dense solution
    top = int(np.argmax(d))
    deepest = minimize_scalar(
        lambda s: -(lambda y: y[0, 2] - y[0, 0])(res._evaluate([s])[0]),
        bounds=(t[max(top - 1, 0)], t[min(top + 1, t.size - 1)]),
        method="bounded",
        options={"xatol": 1e-15},
    )
    history = np.where(t <= deepest.x, np.maximum.accumulate(d), -deepest.fun)
    law_force = np.maximum(res.law.force(d, r, history), 0.0)
    # the same formula on the same states: rounding, and for a history law the largest
    # overlap located to xatol 1e-15 s (its error is second order at the maximum)
    worst = np.max(np.abs(res.contact_force[inside] - law_force))
    assert worst <= 1e-12 * res.peak_contact_force, case
