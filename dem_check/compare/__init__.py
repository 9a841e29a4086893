"""Impact comparisons, kept under their old name: they live in :mod:`contactlab.compare`.

Comparing two impacts quantity by quantity is contactlab's own business (its regression
tests compare against golden traces), so the comparison moved down into contactlab; this
package hands the same names on for code written against ``dem_check.compare``.
"""

from contactlab.compare import (
    ALIGNMENTS,
    DEFAULT_TOLERANCES,
    ONSET_LEVEL,
    QUANTITIES,
    Comparison,
    Quantity,
    compare,
    compare_trace,
    noise_tolerances,
)

__all__ = [
    "ALIGNMENTS",
    "DEFAULT_TOLERANCES",
    "ONSET_LEVEL",
    "QUANTITIES",
    "Comparison",
    "Quantity",
    "compare",
    "compare_trace",
    "noise_tolerances",
]
