"""Batched impact solvers: one row of a DataFrame per impact.

* :func:`linear_impacts`: exact linear (Kelvin-Voigt) impacts with the single-impact
  solver's numbers, tens of thousands per second in one process
  (:mod:`contactlab.batch.linear`, compiled kernel :mod:`contactlab.batch.linear_kernel`);
* :func:`dask_linear_impacts`: the same on a Dask cluster, partitioned by rows
  (:mod:`contactlab.batch.dask`).
"""

from contactlab.batch.dask import dask_linear_impacts
from contactlab.batch.linear import LINEAR_INPUTS, RESULT_COLUMNS, linear_impacts

__all__ = ["LINEAR_INPUTS", "RESULT_COLUMNS", "dask_linear_impacts", "linear_impacts"]
