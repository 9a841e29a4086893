"""Kernels compiled without reference counts (``njit(borrowed=True)``, issue 25) hand no
array back: a borrowed array returned to a counted caller would be released twice.

Every compiled signature of every borrowed function in :mod:`contactlab.kernels` is
checked after the solvers ran (single impacts and the batch, linear and damped Hertz),
so the check covers the signatures the solvers really use.
"""

import importlib
import pkgutil

import numpy as np
import pandas as pd
import pytest
from numba import types
from numba.core.registry import CPUDispatcher

import contactlab.kernels
from contactlab import Grain, Sensor, simulate_impact
from contactlab.batch import hertz_impacts, linear_impacts
from contactlab.laws import HertzDamped, LinearViscoelastic

ROW = {"m1 [kg]": 1.233e-3, "k1 [N/m]": 7.79e7, "c1 [N*s/m]": 12.4, "m2 [kg]": 5.0e-5}
"""A sensor and grain of the batch docstrings' example [SI]."""


def _borrowed_dispatchers():
    found = {}
    for info in pkgutil.iter_modules(contactlab.kernels.__path__):
        module = importlib.import_module(f"contactlab.kernels.{info.name}")
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.targetoptions.get("_nrt") is False:
                found[f"{value.py_func.__module__}.{value.py_func.__qualname__}"] = value
    return found


def _holds_array(typ):
    if isinstance(typ, types.Array):
        return True
    if isinstance(typ, types.BaseTuple):
        return any(_holds_array(t) for t in typ.types)
    return False


@pytest.fixture(scope="module")
def solved():
    """Run the solvers once, so every signature they use is compiled (or loaded)."""
    grain = Grain(diameter=5e-3, density=765.0)  # the README's grain, 50 mg
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    simulate_impact(grain, sensor, LinearViscoelastic(1e5, 1.0), velocity=2.0)
    simulate_impact(grain, sensor, HertzDamped(1e8, 2.0), velocity=2.0)
    frame = pd.DataFrame([ROW | {"v0 [m/s]": 2.0}])
    linear_impacts(frame.assign(**{"k2 [N/m]": 1e5, "c2 [N*s/m]": 1.0}))
    hertz_impacts(frame.assign(**{"k_hertz [N/m**1.5]": 1e8, "damping [N*s/m**1.25]": 2.0}))


def test_the_hot_helpers_are_borrowed():
    # the helpers measured hot in the linear and damped-Hertz batch (perf, issue 25)
    names = set(_borrowed_dispatchers())
    for expected in ("modal.state", "modal._read", "modal._root", "dop853.step", "power.rhs_row"):
        assert f"contactlab.kernels.{expected}" in names


def _signatures(dispatcher):
    """Every signature the solvers compiled: a callee compiled for a cached caller is in
    its own cache (numba's index, private API), not in this process's dispatcher."""
    for key in dispatcher._cache._cache_file._load_index():
        dispatcher.compile(key[0])  # loads the entry
    return dispatcher.nopython_signatures


def test_no_borrowed_kernel_returns_an_array(solved):
    compiled = 0
    for name, dispatcher in _borrowed_dispatchers().items():
        for signature in _signatures(dispatcher):
            compiled += 1
            assert not _holds_array(signature.return_type), (name, signature)
    assert compiled >= 5  # the solvers above compiled at least the five hot helpers


def test_a_borrowed_kernel_refuses_to_allocate():
    from contactlab.compiled import njit

    @njit(borrowed=True)
    def allocates(n):
        return np.zeros(n).sum()

    # numba without reference counts refuses a new array (np.zeros builds one and returns it)
    with pytest.raises(Exception, match="Only accept returning of array passed into the function"):
        allocates(3)
