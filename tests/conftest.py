"""Shared test settings.

The paper's grains and sensors (``paper_grain``, ``paper_grain_small``, ``paper_sensor``,
``rigid_sensor``) and the ``golden`` fixture come from contactlab's pytest plugin
(:mod:`contactlab.testing.plugin`), loaded through its entry point.
"""

import os
import sys
from pathlib import Path

import matplotlib
import pytest
from hypothesis import settings
from hypothesis.internal.conjecture import providers
from threadpoolctl import threadpool_limits

matplotlib.use("Agg")

# One BLAS thread per test process: ``make test`` runs one pytest worker per core, and
# OpenBLAS' own threads (one per core in each worker) then wait for cores the other
# workers hold. Measured on the 2-core machine with other work running
# (test_fit_quality.py, 17 tests): 107 s of CPU with OpenBLAS' default threads, 26 s with
# one. The environment variable reaches the command-line tests' subprocesses.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
threadpool_limits(limits=1, user_api="blas")

# Property tests draw the same examples on every run (seeded from each test's source and
# hypothesis' pinned version), so CI runs exactly what passed here; a failure found once is
# pinned as an explicit case. CONTACTLAB_RANDOM_SWEEPS=1 draws fresh examples to hunt for
# new failures locally.
settings.register_profile("derandomized", derandomize=True)
settings.register_profile("random", derandomize=False)
RANDOM_SWEEPS = bool(os.environ.get("CONTACTLAB_RANDOM_SWEEPS"))
settings.load_profile("random" if RANDOM_SWEEPS else "derandomized")

# Hypothesis also draws, now and then, a literal constant found in the source of every
# non-test module loaded so far. That pool grows with each import, so the same test drew
# other examples alone than in the whole suite, in another order, on another xdist worker,
# or after any constant changed anywhere in the package. The derandomized profile draws
# from hypothesis' own constants only; the random profile keeps the source constants.
if not RANDOM_SWEEPS:
    NO_SOURCE_CONSTANTS = providers.Constants()
    assert hasattr(providers, "_get_local_constants"), "hypothesis renamed its constant pool"
    providers._get_local_constants = lambda: NO_SOURCE_CONSTANTS

# helper modules of the tests themselves (tests/support/) import by name: importlib mode puts
# no test folder on the path (and tests/ itself would shadow the packages with its folders)
sys.path.insert(0, str(Path(__file__).parent / "support"))

pytest_plugins = ["pytester"]  # the plugin's own tests run pytest in temporary folders

PAPER_MASS = 765.0 * 3.141592653589793 * (5e-3) ** 3 / 6.0
"""The paper's 5 mm grain at 765 kg/m^3 [kg]."""


@pytest.fixture(autouse=True)
def _close_figures():
    """Close the figures a test left open: pyplot keeps them, and the 21st open figure
    raises matplotlib's RuntimeWarning (an error here) in whichever test draws next."""
    yield
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        pyplot.close("all")
