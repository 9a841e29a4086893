"""dem_check: cross-checks of contactlab against a rigid-body engine and measured traces.

Measured oscilloscope and DAQ exports are read with :func:`read_trace` (formats detected
by content; nothing lost, nothing guessed: bad files raise :class:`TraceFormatError`
naming the file and line).
"""

from dem_check.traces import Trace, TraceFormatError, read_trace, write_trace

__all__ = ["Trace", "TraceFormatError", "read_trace", "write_trace"]
