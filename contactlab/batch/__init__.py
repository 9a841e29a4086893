"""Batched impact solvers: one row of a DataFrame per impact.

* :func:`linear_impacts`: exact linear (Kelvin-Voigt) impacts with the single-impact
  solver's numbers, tens of thousands per second in one process
  (:mod:`contactlab.batch.linear`, compiled kernel :mod:`contactlab.kernels.linear_impact`);
* :func:`hertz_impacts`: damped-Hertz (Tsuji) impacts on the single solver's compiled
  contact pieces, thousands per second (:mod:`contactlab.batch.hertz`, kernel
  :mod:`contactlab.kernels.hertz_impact`);
* :func:`oblique_impacts`: oblique Hertz-Mindlin impacts (sweeps over angle, spin, speed)
  on the compiled phase loop of :func:`contactlab.simulate_oblique`
  (:mod:`contactlab.batch.oblique`);
* :func:`dask_linear_impacts`, :func:`dask_hertz_impacts`: the same on a Dask cluster,
  partitioned by rows (:mod:`contactlab.batch.dask`).
"""

from contactlab.batch.dask import dask_hertz_impacts, dask_linear_impacts
from contactlab.batch.hertz import HERTZ_INPUTS, hertz_impacts
from contactlab.batch.linear import LINEAR_INPUTS, linear_impacts
from contactlab.batch.oblique import OBLIQUE_INPUTS, OBLIQUE_RESULTS, oblique_impacts
from contactlab.batch.rows import RESULT_COLUMNS

__all__ = [
    "HERTZ_INPUTS",
    "LINEAR_INPUTS",
    "OBLIQUE_INPUTS",
    "OBLIQUE_RESULTS",
    "RESULT_COLUMNS",
    "dask_hertz_impacts",
    "dask_linear_impacts",
    "hertz_impacts",
    "linear_impacts",
    "oblique_impacts",
]
