"""The Chung & Ooi (2011) benchmark: particle impacts from elastic normal to oblique with spin.

Chung Y.C., Ooi J.Y. (2011) Benchmark tests for verifying discrete element modelling codes
at particle impact level. Granular Matter 13, 643-656. DOI 10.1007/s10035-011-0277-0

* :mod:`~contactlab.benchmarks.chung_ooi.cases`: the tests, materials and their sources;
* :mod:`~contactlab.benchmarks.chung_ooi.runner`: runs, checks against theory, table,
  figures (:func:`run_chung_ooi`).
"""

from contactlab.benchmarks.chung_ooi.runner import run_chung_ooi

__all__ = ["run_chung_ooi"]
