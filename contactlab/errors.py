"""Exception and warning family of contactlab.

All errors derive from standard bases so callers can catch them generically
(python-control's ``ControlDimension(ValueError)`` pattern).
"""

__all__ = [
    "AuditWarning",
    "CompiledCacheWarning",
    "ContactlabWarning",
    "ParameterError",
    "PlausibilityWarning",
    "ResolutionWarning",
    "RowFailedWarning",
    "TraceFormatError",
    "UnknownParameterError",
    "WindowWarning",
]


class ParameterError(ValueError):
    """A physical or numerical parameter is invalid.

    The message names the parameter, the value received and the allowed range.
    """


class UnknownParameterError(ParameterError, TypeError):
    """An unknown keyword argument, or a missing required one; the message lists valid names."""


class TraceFormatError(ValueError):
    """A trace file cannot be read as claimed; the message names the file and line."""


class ContactlabWarning(UserWarning):
    """Base class of the warnings this toolkit issues."""


class WindowWarning(ContactlabWarning):
    """The simulated time window is too short for what was asked; the message says how long."""


class ResolutionWarning(ContactlabWarning):
    """The output sample rate cannot resolve the signal; the message gives the minimum rate."""


class AuditWarning(ContactlabWarning):
    """A result breaks a physical invariant (one-sided normal force, Coulomb's limit, energy,
    momentum) beyond the solver's tolerance; the message names the check, its worst value,
    the tolerance and when (see :mod:`contactlab.audit`)."""


class PlausibilityWarning(ContactlabWarning):
    """A value is legal but outside what real grains, seeds and sensors span.

    The message names the likely unit slip; the ranges and their sources are in
    ``contactlab.plausibility.RANGES`` and ``docs/plausibility.md``.
    """


class RowFailedWarning(ContactlabWarning):
    """Rows of a batch could not be solved: NaN there, the reason in the ``error`` column."""


class CompiledCacheWarning(ContactlabWarning):
    """A compiled solver's numba cache file could not be read and is being rebuilt; the
    message names the cache folder (see :mod:`contactlab.compiled`)."""
