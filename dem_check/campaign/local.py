"""The local baseline of one impact, fitted on both sides of it, and its impulse: the
single-trace paths share it, so it lives in :mod:`contactlab.inverse.local_baseline`
(a line fitted on the quiet samples before the impact and, with the sensor's free
ringing, on the samples after its contact); handed on here for the campaign."""

from contactlab.inverse.local_baseline import (
    DEGREE,
    POST_PERIODS,
    PRE_PERIODS,
    LocalBaseline,
    local_baseline,
)

__all__ = ["DEGREE", "POST_PERIODS", "PRE_PERIODS", "LocalBaseline", "local_baseline"]
