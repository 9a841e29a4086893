"""Measured traces, kept under their old name: they live in :mod:`contactlab.traces`.

Reading a measured sensor trace is contactlab's own business (force reconstruction and the
golden-trace tests read them), so the readers moved down into contactlab; this package
hands the same names on for code written against ``dem_check.traces``.
"""

from contactlab import traces as _home

__all__ = _home.__all__


def __getattr__(name):
    """Every public name of :mod:`contactlab.traces`, read there."""
    return getattr(_home, name)
