"""Compare two impacts number by number: engine vs model, or a measured trace vs a model.

:func:`compare` takes any two of

* a simulated result (:class:`contactlab.ImpactResult`, :class:`dem_check.engines.EngineResult`),
  which has contact force, sensor signal and grain velocities;
* a measured :class:`~contactlab.traces.Trace` in newtons, which is a sensor signal only:
  the quantities it lacks (contact time, peak contact force, restitution) are reported as
  not available, never as failed;

and returns a :class:`Comparison`: a table of quantities with both values, their errors,
the tolerance and whether it holds.

Modules: :mod:`~contactlab.compare.quantities` (the quantities, their error bases and
default tolerances), :mod:`~contactlab.compare.waveform` (time alignment, waveform
errors), :mod:`~contactlab.compare.comparison` (:class:`Comparison`) and
:mod:`~contactlab.compare.impacts` (:func:`compare`, :func:`compare_trace`).
"""

from contactlab.compare.comparison import Comparison
from contactlab.compare.impacts import compare, compare_trace
from contactlab.compare.quantities import (
    DEFAULT_TOLERANCES,
    QUANTITIES,
    Quantity,
    noise_tolerances,
)
from contactlab.compare.waveform import ALIGNMENTS, ONSET_LEVEL

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
