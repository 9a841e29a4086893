"""Any value in any parameter of a cheap public callable: a result or ParameterError (issue 24).

hypothesis draws, for every public callable whose valid call is cheap
(``conftest.costly`` is false), one parameter and one value from the whole space a user
can type: any float (NaN, infinities, 5e-324, 1e308), integers up to 1e30, short text,
``None``, booleans, complex numbers, lists, empty, NaN, ragged and 2-D arrays, and every
must-refuse value of every kind, while the other parameters keep their valid values. The
call may succeed (the value may be legal) or raise :class:`ParameterError` /
:class:`TraceFormatError` (a path to no file may raise ``FileNotFoundError``, as
``open`` does, and a golden reference not on disk ``GoldenMissingError``, the testing
package's documented answer); ``TypeError``, ``OverflowError``, ``ZeroDivisionError``,
``IndexError``, ``LinAlgError``, a numpy ``RuntimeWarning`` (an overflow or invalid value
let through) or a hang are failures. The budget is fixed (:data:`SETTINGS`); the refusal
of values that must be refused is test_api_refusals.py's.
"""

import math

import numpy as np
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from contactlab.errors import ParameterError, TraceFormatError
from contactlab.testing import GoldenMissingError

SETTINGS = settings(
    max_examples=12, deadline=None, derandomize=True, phases=[Phase.explicit, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.differing_executors],
)  # fmt: skip  # fixed budget: 12 draws per callable (about 2 000 calls), no shrinking


def _all_refusals(api):
    return [value for values in api.MUST_REFUSE.values() for _, value in values]


ARRAYS = st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=70).map(np.array)


def hostile(api):
    return st.one_of(
        st.floats(allow_nan=True, allow_infinity=True),
        st.sampled_from([0.0, -0.0, 5e-324, 1e-320, 1e308, -1e308, math.nan, -1.0]),
        st.integers(min_value=-(10**30), max_value=10**30),
        st.text(max_size=5),
        st.sampled_from([None, True, False, 1j, [], (), {}, np.ones((3, 3)), [[1.0], [2.0, 3.0]]]),
        st.sampled_from(_all_refusals(api)),
        ARRAYS,
    )


def test_any_value_gives_a_result_or_parameter_error(api, cheap_name):
    function, valid, kinds = api.baseline(cheap_name)
    if cheap_name in api.KNOWN_HOSTILE_DEFECTS:  # a strict xfail: the value found, exactly
        parameter, value, _ = api.KNOWN_HOSTILE_DEFECTS[cheap_name]
        try:
            api.call(function, {**valid, parameter: value})
        except (ParameterError, TraceFormatError):
            pass
        return

    @SETTINGS
    @given(parameter=st.sampled_from(sorted(kinds)), value=hostile(api))
    def check(parameter, value):
        try:
            api.call(function, {**valid, parameter: value})
        except (ParameterError, TraceFormatError, GoldenMissingError):
            pass
        except FileNotFoundError:
            if kinds[parameter][0] != "path":
                raise

    check()
