"""Argument checks shared by the testing helpers (the rest use contactlab.validation)."""

import numbers

from contactlab.errors import ParameterError


def check_count(name, value, minimum):
    """Return ``value`` after checking it is an integer >= ``minimum`` (a sample count)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ParameterError(f"{name} must be an integer >= {minimum}; got {value!r}")
    return int(value)
