"""Checks at the public entry points: each names the culprit and the allowed range.

Every public constructor and function calls these before doing any work, so that a
bad value fails where it enters, with a message such as::

    ParameterError: stiffness must be a finite number > 0 [N/m]; got -3.0
"""

import difflib
import functools
import inspect
import math
import numbers
import os
import re
from collections.abc import Hashable
from pathlib import Path

import numpy as np

from contactlab.errors import ParameterError, UnknownParameterError

__all__ = [
    "KeywordChecked",
    "check_choice",
    "check_count",
    "check_inertia_factor",
    "check_interval",
    "check_non_negative",
    "check_number",
    "check_path",
    "check_poisson_ratio",
    "check_positive",
    "check_probability",
    "check_samples",
    "check_text",
    "check_values",
    "keyword_checked",
    "make_folder",
    "numbers_checked",
    "unknown_keywords",
    "with_suggestion",
]


def _describe(low, high, low_open, high_open):
    parts = []
    if low is not None:
        parts.append(f"{'>' if low_open else '>='} {low:g}")
    if high is not None:
        parts.append(f"{'<' if high_open else '<='} {high:g}")
    return " and ".join(parts)


def check_number(
    name,
    value,
    *,
    low=None,
    high=None,
    low_open=True,
    high_open=False,
    unit="",
    allow_inf=False,
):
    """Return ``value`` as a float after checking it is a real number within a range.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : object
        The value to check. ``bool`` is rejected (it is an ``int`` subclass but never a
        physical quantity).
    low, high : float or None
        Bounds of the allowed range; ``None`` means unbounded.
    low_open, high_open : bool
        Whether the bounds are excluded (default: ``value > low`` and ``value <= high``).
    unit : str
        Unit shown in the message, e.g. ``"N/m"``.
    allow_inf : bool
        Accept ``+inf`` (e.g. an immovable wall's mass).

    Returns
    -------
    float
        ``value`` converted (an ``int`` or numpy scalar becomes a float).

    Raises
    ------
    ParameterError
        If the value is not a real number, is NaN, infinite (unless allowed), or out of range.
    """
    bounds = (low, high, low_open, high_open)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        got = f"{value!r} of type {type(value).__name__}"
        raise _out_of_range(name, "a real number", bounds, unit, got)
    x = float(value)
    if math.isnan(x) or (math.isinf(x) and not (allow_inf and x > 0)):
        raise _out_of_range(name, "a finite number", bounds, unit, repr(x))
    bad_low = low is not None and (x <= low if low_open else x < low)
    bad_high = high is not None and (x >= high if high_open else x > high)
    if bad_low or bad_high:
        raise _out_of_range(name, "a finite number", bounds, unit, repr(x))
    return x


def _out_of_range(name, kind, bounds, unit, got):
    """The :class:`ParameterError` of :func:`check_number`, its message built only when a
    check fails (a passing check, a dozen per solver call, builds no text)."""
    rng = _describe(*bounds)
    rng = f" {rng}" if rng else ""
    unit_text = f" [{unit}]" if unit else ""
    return ParameterError(f"{name} must be {kind}{rng}{unit_text}; got {got}")


def check_samples(name, value, *, ndim=1, min_size=0, unit="", finite=True, copy=True):
    """Return ``value`` as a float array after checking it holds finite real numbers.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : array_like
        Numbers (a scalar, a sequence, an array). Text, ``None``, booleans, complex
        numbers and objects are refused: ``numpy.asarray`` would read ``"1e5"`` as a
        number and ``None`` as NaN.
    ndim : int or None, default 1
        Required number of dimensions; None accepts any (a scalar or an array that
        broadcasts).
    min_size : int, default 0
        Fewest values.
    unit : str
        Unit shown in the message.
    finite : bool, default True
        Refuse NaN and infinite values; False lets them through (a recorder's overrange
        samples, which the caller reports itself).
    copy : bool, default True
        False returns a float64 array given as such without copying it (for a caller
        that only reads it, on a hot path); the default always returns a new array.

    Returns
    -------
    numpy.ndarray of float

    Raises
    ------
    ParameterError
        Naming ``name``: not numbers, wrong dimensions, too few, NaN or infinite values.
    """
    unit_text = f" [{unit}]" if unit else ""
    if isinstance(value, str | bytes) or value is None:
        raise ParameterError(f"{name} must be numbers{unit_text}; got {value!r}")
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as exc:  # ragged nesting
        raise ParameterError(f"{name} must be an array of numbers{unit_text}; {exc}") from None
    if array.dtype.kind not in "iuf":
        raise ParameterError(f"{name} must hold real numbers{unit_text}; got {array.dtype} values")
    array = array.astype(float, copy=copy)
    if ndim is not None and array.ndim != ndim:
        raise ParameterError(f"{name} must be a {ndim}-D array; got shape {array.shape}")
    if array.size < min_size:
        raise ParameterError(f"{name} needs at least {min_size} values; got {array.size}")
    if finite and not np.isfinite(array).all():
        raise ParameterError(f"{name} must be finite{unit_text} (no NaN or inf values)")
    return array


def check_values(name, value, *, low=0.0, low_open=True, unit="", min_size=1):
    """Return ``value`` as a 1-D float array of at least ``min_size`` finite numbers, each
    above ``low`` (a list of diameters, resonances, dampings...).

    Parameters are those of :func:`check_samples` and :func:`check_number`; ``low=None``
    leaves the values unbounded.

    Raises
    ------
    ParameterError
        Naming ``name``: as :func:`check_samples`, or a value at or below ``low`` (below
        it with ``low_open=False``).
    """
    values = check_samples(name, value, min_size=min_size, unit=unit)
    if low is not None and values.size:
        smallest = values.min()
        if smallest < low or (low_open and smallest == low):
            rng = _describe(low, None, low_open, False)
            unit_text = f" [{unit}]" if unit else ""
            raise ParameterError(f"{name} must be numbers {rng}{unit_text}; got {smallest!r}")
    return values


def check_path(name, value):
    """Return ``value`` after checking it is a file path (``str`` or ``os.PathLike``).

    Raises
    ------
    ParameterError
        Naming ``name``, for anything else (a number, ``None``, a list) and for an empty
        text.
    """
    if not isinstance(value, str | os.PathLike) or not os.fspath(value):
        raise ParameterError(f"{name} must be a file path (str or pathlib.Path); got {value!r}")
    return value


def make_folder(name, value):
    """Check ``value`` is a path (:func:`check_path`), create that folder and its parents
    where missing, and return it as a :class:`pathlib.Path`."""
    folder = Path(check_path(name, value))
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def check_positive(name, value, unit=""):
    """Check a finite number ``> 0`` in ``unit``; return it as float."""
    return check_number(name, value, low=0.0, unit=unit)


def check_non_negative(name, value, unit=""):
    """Check a finite number ``>= 0`` in ``unit``; return it as float."""
    return check_number(name, value, low=0.0, low_open=False, unit=unit)


def check_poisson_ratio(name, value):
    """Check a Poisson ratio in (-1, 0.5] [-]; return it as float."""
    return check_number(name, value, low=-1.0, high=0.5, unit="-")


INERTIA_FACTOR_RANGE = (1e-3, 2.0 / 3.0)
"""Allowed ``I / (m r**2)`` of a spherical grain [-]: at most 2/3 (all the mass on the
surface, a thin shell: no sphere of non-negative density has more); at least 1e-3 (a
core 30 times denser than its shell gives 0.1; below 1e-3 the spin is a mode so fast that
the oblique solver's run time grows without bound: 1e-12 hung)."""


def check_inertia_factor(name, value):
    """Check a sphere's inertia factor ``I / (m r**2)`` in :data:`INERTIA_FACTOR_RANGE`."""
    low, high = INERTIA_FACTOR_RANGE
    return check_number(name, value, low=low, high=high, low_open=False, unit="-")


def check_interval(name, value):
    """Check a sample interval [s]: a finite number > 0 whose rate ``1 / value`` is finite
    too (a subnormal interval such as 5e-324 s has an infinite rate); return it as float."""
    interval = check_number(name, value, low=0.0, unit="s")
    if not math.isfinite(1.0 / interval):
        raise ParameterError(
            f"{name} must be a sample interval [s] whose rate 1/{name} is finite; got {interval!r}"
        )
    return interval


def check_count(name, value, low=1):
    """Return ``value`` as an int after checking it is an integer >= ``low``.

    ``bool`` and floats (even integral ones such as ``2.0``) are rejected: a count is never
    rounded or truncated silently.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < low:
        raise ParameterError(f"{name} must be an integer >= {low}; got {value!r}")
    return int(value)


def check_probability(name, value, *, low_open=False, high_open=False):
    """Check a dimensionless fraction in [0, 1] (open ends as requested); return it as float."""
    return check_number(name, value, low=0.0, high=1.0, low_open=low_open, high_open=high_open)


def check_choice(name, value, choices):
    """Check that ``value`` is one of ``choices``; the message lists the valid ones.

    Near matches are suggested (PyBaMM habit) through :mod:`difflib`.
    """
    if isinstance(value, Hashable) and value in choices:  # an array or list is no choice
        return value
    close = difflib.get_close_matches(str(value), [str(c) for c in choices], n=1)
    hint = f" Did you mean {close[0]!r}?" if close else ""
    valid = ", ".join(repr(c) for c in choices)
    raise ParameterError(f"{name} must be one of {valid}; got {value!r}.{hint}")


TEXT_MAX_LENGTH = 1000
"""Longest free text (a label, a file path) accepted into a written file [characters]."""

_PYTHON_CODING = re.compile(r"coding[:=]")
"""PEP 263 declaration: on a script's first two lines it changes how Python decodes it."""


def check_text(name, value, max_length=TEXT_MAX_LENGTH):
    """Return ``value`` after checking it is safe text for a comment in any input deck.

    The text must be a ``str`` of printable characters (no line ends of any kind, no
    control characters, see :meth:`str.isprintable`), at most ``max_length`` long, must not
    end in a line continuation (``\\`` in C/C++, ``&`` in LAMMPS, which would pull the
    next line into the comment) and must not hold a Python encoding declaration
    (``coding:``). Text that fails is refused, never repaired.

    Raises
    ------
    ParameterError
        Naming ``name`` and the offending character.
    """
    if not isinstance(value, str):
        raise ParameterError(f"{name} must be text (str); got {type(value).__name__}")
    if len(value) > max_length:
        raise ParameterError(f"{name} must be at most {max_length} characters; got {len(value)}")
    for position, char in enumerate(value):
        if not char.isprintable():
            raise ParameterError(
                f"{name} must be printable text on one line; character {position} is "
                f"{char!r}: refused"
            )
    if value.rstrip().endswith(("\\", "&")):
        raise ParameterError(
            f"{name} must not end in {value.rstrip()[-1]!r} (a line continuation); got {value!r}"
        )
    if _PYTHON_CODING.search(value):
        raise ParameterError(
            f"{name} must not hold an encoding declaration 'coding:'; got {value!r}"
        )
    return value


def with_suggestion(name, valid):
    """``'name'``, followed by ``(did you mean 'nearest'?)`` when a valid name is close
    (:func:`difflib.get_close_matches`, cutoff 0.6)."""
    close = difflib.get_close_matches(str(name), [str(v) for v in valid], n=1, cutoff=0.6)
    return f"{name!r} (did you mean {close[0]!r}?)" if close else repr(name)


@functools.cache
def _signature(function):
    return inspect.signature(function)


def unknown_keywords(owner, function, args, kwargs, noun="parameter", skip=0, names=None):
    """Bind ``args, kwargs`` to ``function``'s signature; a bad call raises, naming the
    unknown names with the nearest valid one (:mod:`difflib`).

    Parameters
    ----------
    owner : str
        Who is called, for the message (``"Grain"``, ``"[sensor]"``).
    function : callable
        Its signature is the reference.
    args : tuple
        Positional arguments (``self`` included for a method).
    kwargs : dict
        Keyword arguments (or a TOML table's keys).
    noun : str, default "parameter"
        What the names are called in the message (``"key"`` for TOML tables).
    skip : int, default 0
        Leading signature parameters not listed as valid (``self``).
    names : sequence of str, optional
        The valid names as the caller's callers spell them, where they are not the
        signature's (a TOML table's keys that the caller gathers into one argument);
        default the signature's parameters after ``skip``.

    Raises
    ------
    UnknownParameterError
        An unknown name (with a suggestion), a missing required one, or too many
        positional arguments; the message lists the valid names.
    """
    signature = _signature(function)
    try:
        signature.bind(*args, **kwargs)
    except TypeError as exc:
        parameters = list(signature.parameters)[skip:]
        valid = parameters if names is None else list(names)
        unknown = [k for k in kwargs if k not in parameters]
        if unknown:
            problem = f"unknown {noun}(s) {', '.join(with_suggestion(k, valid) for k in unknown)}"
            given = len(args) - skip
            missing = [
                name
                for i, name in enumerate(parameters)
                if i >= given
                and name not in kwargs
                and signature.parameters[name].default is inspect.Parameter.empty
                and signature.parameters[name].kind
                not in (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)
            ]
            if missing:
                problem += f"; missing required {noun}(s) {', '.join(map(repr, missing))}"
        else:
            problem = str(exc)
        raise UnknownParameterError(
            f"{owner}: {problem}; valid {noun}s are {', '.join(valid)}"
        ) from None


def keyword_checked(function):
    """Decorator: a misspelt or missing argument of ``function`` raises
    :class:`UnknownParameterError` naming it, with a suggestion, instead of a bare
    ``TypeError``."""

    @functools.wraps(function)
    def checked(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError:  # a bad call, or a TypeError from inside: binding tells which
            unknown_keywords(function.__name__, function, args, kwargs)
            raise

    return checked


def numbers_checked(*optional):
    """Decorator of a vectorised function: every argument must be finite real numbers.

    Each argument (a scalar or an array that broadcasts) goes through
    :func:`check_samples` with any number of dimensions before the call, so text,
    ``None``, complex numbers and NaN are refused naming the argument instead of turning
    into NaN or a ``TypeError`` deep in numpy. Arguments named in ``optional`` may also be
    ``None``. A misspelt or missing argument raises :class:`UnknownParameterError`.
    """

    def decorate(function):
        signature = inspect.signature(function)

        @functools.wraps(function)
        def checked(*args, **kwargs):
            unknown_keywords(function.__name__, function, args, kwargs)
            bound = signature.bind(*args, **kwargs)
            for name, value in bound.arguments.items():
                if not (value is None and name in optional):
                    array = check_samples(name, value, ndim=None)
                    bound.arguments[name] = float(array) if array.ndim == 0 else array
            return function(*bound.args, **bound.kwargs)

        return checked

    return decorate


class KeywordChecked:
    """Mixin: unknown or missing constructor arguments raise :class:`UnknownParameterError`.

    The error is both a :class:`~contactlab.errors.ParameterError` (a ``ValueError``, as the
    project's contract asks) and a ``TypeError`` (what Python raises for a bad keyword and
    what python-control's ``kwargs_test`` expects); it names an unknown keyword with the
    nearest valid one (``Grain(diam=...)``: did you mean 'diameter'?) and lists the valid
    names.
    """

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        init = cls.__dict__.get("__init__")
        if init is None or getattr(init, "_keyword_checked", False):
            return

        @functools.wraps(init)
        def checked_init(self, *args, **kw):
            unknown_keywords(cls.__name__, init, (self, *args), kw, skip=1)
            init(self, *args, **kw)

        checked_init._keyword_checked = True
        cls.__init__ = checked_init
