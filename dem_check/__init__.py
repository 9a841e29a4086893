"""dem_check: cross-checks of contactlab against a rigid-body engine and measured traces.

* :func:`drop_test` drops the grain on the sensor in an engine and reads the impact as
  :func:`contactlab.simulate_impact` does (:mod:`dem_check.engines`; pybullet by default);
* :func:`compare` sets two impacts (engine, model, measured trace) side by side,
  quantity by quantity, and says which agree within tolerance (:class:`Comparison`);
* measured oscilloscope and DAQ exports are read with :func:`read_trace` (formats detected
  by content; nothing lost, nothing guessed: bad files raise :class:`TraceFormatError`
  naming the file and line).
"""

from dem_check.compare import Comparison, compare, compare_trace
from dem_check.engines import drop_test
from dem_check.traces import Trace, TraceFormatError, read_trace, write_trace

__all__ = [
    "Comparison",
    "Trace",
    "TraceFormatError",
    "compare",
    "compare_trace",
    "drop_test",
    "read_trace",
    "write_trace",
]
