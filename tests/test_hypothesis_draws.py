"""The derandomized property tests draw the same examples wherever they run."""

import importlib
import os

import pytest
from hypothesis.internal.conjecture import providers


@pytest.mark.skipif(
    bool(os.environ.get("CONTACTLAB_RANDOM_SWEEPS")),
    reason="the random profile keeps the source constants",
)
def test_no_source_constant_enters_the_draws_after_an_import():
    # a module full of literal constants (thresholds, unit factors), imported here if not yet
    importlib.import_module("dem_check.campaign.steps")
    pool = providers._get_local_constants()
    assert not (pool.integers or pool.floats or pool.strings or pool.bytes)
