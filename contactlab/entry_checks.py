"""Entry checks of objects, names, switches and functions: each names the parameter.

The scalar and array checks are in :mod:`contactlab.validation`; these cover the other
arguments a public function takes: an object the library builds (by class, or by the
attributes the function reads), a user's function, a switch, one name or several.
"""

import numpy as np

from contactlab.errors import ParameterError
from contactlab.validation import check_choice

__all__ = ["check_callable", "check_flag", "check_instance", "check_names", "check_shaped"]


def check_instance(name, value, cls, source="", optional=False):
    """Return ``value`` after checking it is an instance of ``cls`` (or None when
    ``optional``); ``source`` says where such an object comes from, for the message
    (``"run_stream"``)."""
    if (optional and value is None) or isinstance(value, cls):
        return value
    origin = f" (from {source})" if source else ""
    none = " or None" if optional else ""
    raise ParameterError(f"{name} must be a {cls.__name__}{origin}{none}; got {value!r}")


def check_shaped(name, value, attributes, what):
    """Return ``value`` after checking it has every one of ``attributes`` (duck typing:
    a real object or one shaped like it, e.g. a test's stand-in); ``what`` names the
    expected object in the message (``"a StreamResult (from run_stream)"``)."""
    missing = [a for a in attributes if not hasattr(value, a)]
    if missing:
        raise ParameterError(f"{name} must be {what}; got {value!r} (no {', '.join(missing)})")
    return value


def check_callable(name, value, signature="", optional=True):
    """Return ``value`` after checking it can be called (or is None when ``optional``);
    ``signature`` shows the expected call in the message (``"detector(trace, sensor)"``)."""
    if (optional and value is None) or callable(value):
        return value
    expected = f" {signature}" if signature else ""
    raise ParameterError(f"{name} must be a function{expected}; got {value!r}")


def check_flag(name, value, optional=False):
    """Return ``value`` as a bool after checking it is ``True`` or ``False`` (or None,
    returned as such, when ``optional``: "decide for me", e.g. a progress bar only on a
    terminal).

    Only ``bool`` and numpy's ``bool_`` pass: a number, a text or an array is no switch
    (``bool("no")`` is True, and an array's truth is ambiguous).
    """
    if optional and value is None:
        return None
    if not isinstance(value, bool | np.bool_):
        none = " (or None)" if optional else ""
        raise ParameterError(f"{name} must be True or False{none}; got {value!r}")
    return bool(value)


def check_names(name, value, choices=None):
    """Return one name or a sequence of names as a tuple of distinct ``str``.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : str or iterable of str
        One name, or several (a repeated name is kept once, in its first place).
    choices : sequence of str, optional
        The valid names; each is checked with :func:`check_choice`.

    Raises
    ------
    ParameterError
        Naming ``name``: not text nor an iterable of text, no name at all, or a name
        outside ``choices``.
    """
    names = (value,) if isinstance(value, str) else value
    try:
        names = tuple(dict.fromkeys(names))
    except TypeError:  # not iterable, or unhashable items
        names = None
    if not names or not all(isinstance(n, str) for n in names):
        raise ParameterError(
            f"{name} must be a name or a sequence of at least one name (str); got {value!r}"
        )
    if choices is not None:
        for item in names:
            check_choice(name, item, choices)
    return names
