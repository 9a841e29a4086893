"""dem_check: cross-checks of contactlab against a rigid-body engine and measured traces.

* :func:`drop_test` drops the grain on the sensor in an engine and reads the impact as
  :func:`contactlab.simulate_impact` does (:mod:`dem_check.engines`; pybullet by default);
* :func:`compare` sets two impacts (engine, model, measured trace) side by side,
  quantity by quantity, and says which agree within tolerance (:class:`Comparison`);
* measured oscilloscope and DAQ exports are read with :func:`read_trace` (formats detected
  by content; nothing lost, nothing guessed: bad files raise :class:`TraceFormatError`
  naming the file and line);
* :func:`run_campaign` analyses every impact of a measurement day's long records:
  per-impact results, the reconstructed force, statistics and an HTML report
  (:mod:`dem_check.campaign`).

Each engine is also an attribute named after it (``dem_check.lammps.drop_test``,
``dem_check.bullet.drop_test``): the module in :data:`dem_check.engines.ENGINES`, imported
when first used, so an engine whose library is an optional extra costs nothing until then.
"""

from dem_check.campaign import run_campaign
from dem_check.compare import Comparison, compare, compare_trace
from dem_check.engines import ENGINES, drop_test, engine_module
from dem_check.traces import Trace, TraceFormatError, read_trace, write_trace

__all__ = [
    "Comparison",
    "Trace",
    "TraceFormatError",
    "compare",
    "compare_trace",
    "drop_test",
    "read_trace",
    "run_campaign",
    "write_trace",
]


def __getattr__(name):
    if name in ENGINES:
        return engine_module(name)
    raise AttributeError(f"module 'dem_check' has no attribute {name!r}")
