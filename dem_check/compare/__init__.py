"""Impact comparisons, kept under their old name: they live in :mod:`contactlab.compare`.

Comparing two impacts quantity by quantity is contactlab's own business (its regression
tests compare against golden traces), so the comparison moved down into contactlab; this
package hands the same names on for code written against ``dem_check.compare``.
"""

from contactlab import compare as _home

__all__ = _home.__all__


def __getattr__(name):
    """Every public name of :mod:`contactlab.compare`, read there."""
    return getattr(_home, name)
