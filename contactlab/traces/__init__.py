"""Measured traces: read oscilloscope and DAQ exports, prepare them, write test layouts.

>>> from contactlab.traces import read_trace, remove_baseline
>>> trace = read_trace("impact.csv", channel="CH1", sensitivity=0.0225)  # doctest: +SKIP
>>> trace = remove_baseline(trace)                                      # doctest: +SKIP
>>> trace.metrics(threshold=0.05)                                       # doctest: +SKIP

Formats are recognised by content (see :data:`FORMATS`): generic CSV with units in the
header; Tektronix TDS and MSO/MDO/DPO, Rigol (both layouts), Keysight InfiniiVision,
PicoScope and LeCroy CSV; and, with ``pip install contactlab[traces]``, oscilloscope
binaries through RigolWFM, NI TDMS and HDF5. Malformed files raise
:class:`~contactlab.errors.TraceFormatError` naming the file and line; nothing is
dropped, clipped or guessed.
"""

from contactlab.errors import TraceFormatError
from contactlab.traces.api import read_trace, write_trace
from contactlab.traces.detect import detect_format
from contactlab.traces.formats import FORMATS
from contactlab.traces.prepare import (
    align,
    detect_onset,
    lowpass,
    noise_level,
    remove_baseline,
    to_force,
)
from contactlab.traces.trace import Trace

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
