"""The entry checks added for issue 24's public-API sweep: what each accepts, what it
refuses, and that the refusal names the parameter."""

import math

import numpy as np
import pytest

from contactlab.entry_checks import (
    check_callable,
    check_flag,
    check_instance,
    check_names,
    check_shaped,
)
from contactlab.errors import ParameterError
from contactlab.validation import check_interval, check_samples, check_values


def test_a_flag_is_true_or_false_only():
    assert check_flag("audit", True) is True and check_flag("audit", np.bool_(False)) is False
    assert check_flag("progress", None, optional=True) is None
    for value in ("no", 1, 0.0, [True], np.array([]), None):
        with pytest.raises(ParameterError, match="audit must be True or False"):
            check_flag("audit", value)


def test_names_are_one_or_several_texts_each_once():
    assert check_names("by", "resonance") == ("resonance",)
    assert check_names("laws", ["linear", "hertz", "linear"]) == ("linear", "hertz")
    with pytest.raises(ParameterError, match="Did you mean 'linear'"):
        check_names("laws", "lineer", ("linear", "hertz"))
    for value in ([], 3.0, [1.0], None, [["a"]]):
        with pytest.raises(ParameterError, match="by must be a name"):
            check_names("by", value)


def test_an_interval_has_a_finite_rate():
    assert check_interval("dt", 1e-6) == 1e-6
    assert math.isfinite(1.0 / check_interval("dt", 1e-300))  # tiny but its rate is finite
    for value in (0.0, -1e-6, 5e-324, math.nan, math.inf, "1e-6"):
        with pytest.raises(ParameterError, match="dt"):
            check_interval("dt", value)


def test_values_are_finite_and_above_the_bound():
    np.testing.assert_array_equal(check_values("rates", (1.0, 2)), [1.0, 2.0])
    np.testing.assert_array_equal(check_values("dampings", [0.0], low_open=False), [0.0])
    for value in ([], [0.0], [-1.0], [math.nan], 5.0, "1, 2", [[1.0]]):
        with pytest.raises(ParameterError, match="rates"):
            check_values("rates", value)


def test_objects_by_class_by_shape_and_functions():
    assert (
        check_instance("x", 3, int) == 3 and check_instance("x", None, int, optional=True) is None
    )
    with pytest.raises(ParameterError, match=r"result must be a StreamResult \(from run_stream\)"):
        check_instance("result", 1.0, type("StreamResult", (), {}), "run_stream")
    shaped = type("Shaped", (), {"steps": 1, "lead": 0.0})()
    assert check_shaped("result", shaped, ("steps", "lead"), "a result") is shaped
    with pytest.raises(ParameterError, match=r"result must be a result; .*\(no lead\)"):
        check_shaped("result", type("Half", (), {"steps": 1})(), ("steps", "lead"), "a result")
    assert check_callable("run", len) is len and check_callable("run", None) is None
    with pytest.raises(ParameterError, match=r"run must be a function run\(case\)"):
        check_callable("run", "run_stream", "run(case)")


def test_samples_are_copied_unless_asked_not_to():
    given = np.zeros(3)
    assert not np.shares_memory(check_samples("y", given), given)
    assert check_samples("y", given, copy=False) is given  # read-only callers, hot paths
    assert check_samples("y", [1, 2, 3], copy=False).dtype == float  # ints still converted
