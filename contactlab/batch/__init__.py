"""Batched impact solvers: one row of a DataFrame per impact.

* :func:`linear_impacts`: exact linear (Kelvin-Voigt) impacts, the single solver's
  numbers at tens of thousands of impacts per second;
* :func:`dask_impacts`: the same on a Dask cluster, partitioned by rows.
"""

from contactlab.batch.linear import LINEAR_INPUTS, RESULT_COLUMNS, linear_impacts

__all__ = ["LINEAR_INPUTS", "RESULT_COLUMNS", "linear_impacts"]
