"""Names that moved down into contactlab still read under their dem_check names."""

import importlib

import pytest

import contactlab.compare
import contactlab.traces
import dem_check


@pytest.mark.parametrize("package", ["traces", "compare"])
def test_every_public_name_is_the_moved_object(package):
    # the module, not the attribute: dem_check.compare is the function compare
    old = importlib.import_module(f"dem_check.{package}")
    new = importlib.import_module(f"contactlab.{package}")
    assert old.__all__ == new.__all__
    for name in new.__all__:
        assert getattr(old, name) is getattr(new, name), name


def test_package_level_names():
    from dem_check.compare import QUANTITIES, compare
    from dem_check.traces import Trace, read_trace

    assert (compare, QUANTITIES) == (contactlab.compare.compare, contactlab.compare.QUANTITIES)
    assert (Trace, read_trace) == (contactlab.traces.Trace, contactlab.traces.read_trace)
    assert dem_check.read_trace is read_trace and dem_check.compare is compare


def test_a_missing_name_is_an_import_error():
    with pytest.raises(ImportError, match="nothing"):
        from dem_check.traces import nothing  # noqa: F401
