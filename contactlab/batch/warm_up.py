"""The numba-compiled solvers, compiled once and cached: check the cache, warm it.

The Hertz-family contact pieces of :func:`contactlab.simulate_impact`, the oblique solver
(:func:`contactlab.simulate_oblique`) and the batch kernels are compiled with numba on
first use (20-50 s on a free 2-core machine, 156 s measured on a busy one, and the oblique
kernels about 50 s of CPU time more) and cached as ``*.nbi``/``*.nbc`` files in the ``__pycache__``
folders beside their sources; a new process then loads them in about 0.1 s. ``make demo``
and ``make test`` pay the compile through :func:`warm_up` (``contactlab warm-up``), so no
timed command hides it. On an empty cache it compiles in two processes, one per group of
solvers (the cache files are locked, :mod:`contactlab.compiled`), then loads them all in
its own process, which checks that nothing was lost (:func:`cache_misses`).
"""

import importlib
import multiprocessing
import os
import time
import warnings
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from contactlab.errors import CompiledCacheWarning

__all__ = ["COMPILED_MODULES", "cache_is_warm", "cache_misses", "warm_up"]

COMPILED_MODULES = (
    "contactlab.kernels.brent",
    "contactlab.kernels.rules",
    "contactlab.kernels.power",
    "contactlab.kernels.dop853",
    "contactlab.kernels.power_piece",
    "contactlab.kernels.modal",
    "contactlab.kernels.linear_impact",
    "contactlab.kernels.hertz_impact",
    "contactlab.kernels.impact_loop",
    "contactlab.kernels.oblique_rhs",
    "contactlab.kernels.oblique_events",
    "contactlab.kernels.oblique_kernel",
    "contactlab.kernels.gauss",
    "contactlab.kernels.held_force",
    "contactlab.kernels.lobe_cost",
    "contactlab.kernels.levels",
    "contactlab.kernels.oblique_sample",
    "contactlab.batch.oblique_kernel",
)
"""Modules with ``numba.njit(cache=True)`` functions compiled on their own (and so cached
beside their source). ``contactlab.kernels.model_rhs`` is not one: its two functions are
inlined into their callers (``inline="always"``) and cached with them."""


_ONE_POLE = (np.array([0.5, 0.0]), np.array([1.0, -0.5]))
"""A discrete filter ``b, a`` for the warm-up's call of the held force's signal."""


def cache_is_warm():
    """Whether every compiled module has cache index files beside its source.

    Returns
    -------
    bool
        False when some module has none yet (its first use compiles it) or when
        ``NUMBA_CACHE_DIR`` moves the cache elsewhere (not looked for there).
    """
    if os.environ.get("NUMBA_CACHE_DIR"):
        return False
    for name in COMPILED_MODULES:
        source = Path(importlib.util.find_spec(name).origin)
        if not any((source.parent / "__pycache__").glob(f"{source.stem}.*.nbi")):
            return False
    return True


def _one_row_frame(**law_columns):
    """A one-impact batch frame: the paper's 40 kHz sensor and 50 mg grain at 2 m/s."""
    mass = 1.233e-3
    stiffness = mass * (2.0 * np.pi * 40e3) ** 2
    return pd.DataFrame(
        {
            "m1 [kg]": [mass],
            "k1 [N/m]": [stiffness],
            "c1 [N*s/m]": [2.0 * 0.02 * np.sqrt(stiffness * mass)],
            "m2 [kg]": [5.0e-5],
            **{name: [value] for name, value in law_columns.items()},
            "v0 [m/s]": [2.0],
        }
    )


def _compile_impacts():
    """The normal-impact solvers: the Hertz-family pieces, the linear and Hertz batches."""
    from contactlab.batch.hertz import hertz_impacts
    from contactlab.batch.linear import linear_impacts
    from contactlab.bodies import Grain, Sensor
    from contactlab.laws import HertzDamped
    from contactlab.solver import simulate_impact

    grain = Grain(diameter=5e-3, density=765.0)
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    simulate_impact(grain, sensor, HertzDamped(3.0e6, 2.0), 2.0)
    linear_impacts(_one_row_frame(**{"k2 [N/m]": 1e5, "c2 [N*s/m]": 1.0}))
    hertz_impacts(_one_row_frame(**{"k_hertz [N/m**1.5]": 3.0e6, "damping [N*s/m**1.25]": 2.0}))


def _compile_readers():
    """The record readers' loops: the held force, the lobe fits' residual and
    Nelder-Mead, the running baseline's residual; and the Gauss-Legendre rule as
    :mod:`contactlab.quadrature` calls it (a compiled caller loaded from the cache does not
    compile it: without this call its cache stayed empty after a parallel warm-up)."""
    from contactlab.kernels.held_force import held_signal, sampled_signal
    from contactlab.kernels.levels import nearest_residual
    from contactlab.kernels.lobe_cost import fitted_rss, scanned_rss, simplex_fit, white_signal
    from contactlab.quadrature import gauss_rule

    gauss_rule(0.0, 1.0e-4, 2.5e-5, graded=True, graded_end=True)
    shape = np.linspace(0.0, 1.0, 5)  # a triangle through a one-pole filter
    times, values = held_signal(1e-6, 10, 5e-6, shape, 1.0 - np.abs(2.0 * shape - 1.0), *_ONE_POLE)
    window = np.arange(4) * 2e-6
    sampled_signal(window, 1e-6, times, values)
    ar, basis = np.array([0.5]), np.linalg.qr(np.column_stack([np.ones(3), np.arange(3.0)]))[0]
    fitted = (np.ascontiguousarray(basis), np.zeros(3), 1.0)  # a lobe fit's line and record
    scanned_rss(window, window, times, white_signal(values, ar, 2), 1, *fitted)
    nearest_residual(shape, shape, np.array([0, 0, 1, 1, 1]), np.zeros(2), 0.0, 0.0, 2)
    problem = (window, 1e-6, 10, shape, shape, *_ONE_POLE, ar, 2, *fitted)
    fitted_rss(1e-6, 5e-6, *problem)
    simplex_fit(np.array([[1e-6, 5e-6], [2e-6, 5e-6], [1e-6, 6e-6]]), 1e-9, 1e-9, 400, problem)


def _compile_oblique():
    """The oblique solver (its two tangential loops), the oblique batch and the record
    readers' loops (:func:`_compile_readers`: with these, the two groups' compile times
    are about equal)."""
    from contactlab.batch.oblique import oblique_impacts
    from contactlab.bodies import Grain, Sensor
    from contactlab.laws import HertzDamped, Mindlin
    from contactlab.solver import simulate_oblique

    grain = Grain(diameter=5e-3, density=765.0)
    sensor = Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    law = HertzDamped(3.0e6, 2.0)
    simulate_oblique(grain, sensor, law, Mindlin(1e6, 0.3, "incremental"), 2.0, 0.5, spin=10.0)
    kratos = Mindlin(1e6, 0.3, "incremental", "tied", "elastic")  # Kratos' cap: its own loop
    simulate_oblique(grain, sensor, law, kratos, 2.0, 0.5, spin=10.0)
    oblique = _one_row_frame(
        **{
            "k_hertz [N/m**1.5]": 3.0e6,
            "damping [N*s/m**1.25]": 2.0,
            "k_mindlin [N/m**1.5]": 1e6,
            "friction [-]": 0.3,
        }
    )
    oblique_impacts(
        oblique.assign(**{"radius [m]": 2.5e-3, "angle [rad]": 0.5, "spin [rad/s]": 0.0})
    )
    _compile_readers()


_GROUPS = (_compile_impacts, _compile_oblique)
"""The warm-up's calls in two groups of about equal compile time (CPU on an empty cache,
docs/testing.md); run in one process each when two cores are free."""


def _run_group(index):
    _GROUPS[index]()


def cache_misses():
    """The cached compiled functions this process compiled instead of loading.

    Returns
    -------
    list of str
        ``module.function`` of every numba function of :data:`COMPILED_MODULES` with a
        signature compiled in this process because the cache had no readable entry for it.
    """
    from numba.core.dispatcher import Dispatcher

    from contactlab.compiled import _RebuildingCache

    names = set()
    for name in COMPILED_MODULES:
        for value in vars(importlib.import_module(name)).values():
            if (
                isinstance(value, Dispatcher)
                and isinstance(value._cache, _RebuildingCache)
                and value.stats.cache_misses
            ):
                names.add(value._cache.function_name)
    return sorted(names)


def warm_up(processes=None):
    """Compile (or load from the cache) every numba solver by running one small case each.

    Parameters
    ----------
    processes : int, optional
        Processes that compile at once: each runs one group of the calls (at most two
        groups), then this process runs them all again, loading every function from the
        cache. Default: two when the machine has two cores or more and the cache files can
        be locked (:data:`contactlab.compiled.CAN_LOCK`), else one (everything compiled here).

    Returns
    -------
    float
        Seconds taken: 20 s to a few minutes into an empty cache, a fraction of a second from a
        warm one.

    Warns
    -----
    CompiledCacheWarning
        When, after the parallel compile, this process still had to compile a function
        (a cache entry lost or unreadable): it is compiled and cached here, and named.
    """
    from contactlab.compiled import CAN_LOCK

    if processes is None:
        processes = 2 if CAN_LOCK and (os.cpu_count() or 1) >= 2 else 1
    start = time.perf_counter()
    parallel = processes > 1 and not cache_is_warm()
    if parallel:
        context = multiprocessing.get_context("spawn")  # a fresh interpreter: nothing compiled
        with ProcessPoolExecutor(min(processes, len(_GROUPS)), mp_context=context) as pool:
            list(pool.map(_run_group, range(len(_GROUPS))))
    for group in _GROUPS:
        group()
    missed = cache_misses() if parallel else []
    if missed:
        warnings.warn(
            "compiled again after the parallel warm-up, now cached: " + ", ".join(missed),
            CompiledCacheWarning,
            stacklevel=2,
        )
    return time.perf_counter() - start
