"""Measured traces, kept under their old name: they live in :mod:`contactlab.traces`.

Reading a measured sensor trace is contactlab's own business (force reconstruction and the
golden-trace tests read them), so the readers moved down into contactlab; this package
hands the same names on for code written against ``dem_check.traces``.
"""

from contactlab.traces import (
    FORMATS,
    Trace,
    TraceFormatError,
    align,
    detect_format,
    detect_onset,
    lowpass,
    noise_level,
    read_trace,
    remove_baseline,
    to_force,
    write_trace,
)

__all__ = [
    "FORMATS",
    "Trace",
    "TraceFormatError",
    "align",
    "detect_format",
    "detect_onset",
    "lowpass",
    "noise_level",
    "read_trace",
    "remove_baseline",
    "to_force",
    "write_trace",
]
