"""Compare two impacts number by number: engine vs model, or a measured trace vs a model.

:func:`compare` takes any two of

* a simulated result (:class:`contactlab.ImpactResult`, :class:`dem_check.engines.EngineResult`),
  which has contact force, sensor signal and grain velocities;
* a measured :class:`~dem_check.traces.Trace` in newtons, which is a sensor signal only:
  the quantities it lacks (contact time, peak contact force, restitution) are reported as
  not available, never as failed;

and returns a :class:`Comparison`: a table of quantities with both values, their errors,
the tolerance and whether it holds.

Modules: :mod:`~dem_check.compare.quantities` (the quantities, their error bases and
default tolerances), :mod:`~dem_check.compare.waveform` (time alignment, waveform
errors), :mod:`~dem_check.compare.comparison` (:class:`Comparison`) and
:mod:`~dem_check.compare.impacts` (:func:`compare`, :func:`compare_trace`).
"""

from dem_check.compare.comparison import Comparison
from dem_check.compare.impacts import compare, compare_trace
from dem_check.compare.quantities import (
    DEFAULT_TOLERANCES,
    QUANTITIES,
    Quantity,
    noise_tolerances,
)
from dem_check.compare.waveform import ALIGNMENTS, ONSET_LEVEL

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
