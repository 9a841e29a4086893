"""The Chung & Ooi (2011) benchmark: particle impacts from elastic normal to oblique with spin.

Chung Y.C., Ooi J.Y. (2011) Benchmark tests for verifying discrete element modelling codes
at particle impact level. Granular Matter 13, 643-656. DOI 10.1007/s10035-011-0277-0

The nine tests (the paper's eight and the ninth of Kratos' nightly suite):

* :mod:`~contactlab.benchmarks.chung_ooi.cases`: the tests, materials and their sources,
  and where the sources disagree;
* :mod:`~contactlab.benchmarks.chung_ooi.normal`: tests 1, 2, 3, 9 (normal impacts);
* :mod:`~contactlab.benchmarks.chung_ooi.oblique`: tests 4, 5, 6 (a sphere on a plane);
* :mod:`~contactlab.benchmarks.chung_ooi.pairs`: tests 7, 8 (two spheres, exact reduction);
* :mod:`~contactlab.benchmarks.chung_ooi.grading`: graded rows and their tolerances;
* :mod:`~contactlab.benchmarks.chung_ooi.figures`: one figure per test;
* :mod:`~contactlab.benchmarks.chung_ooi.runner`: :func:`run_chung_ooi` (optionally with
  LAMMPS beside) and the table.
"""

from contactlab.benchmarks.chung_ooi.runner import EngineRunner, run_chung_ooi

__all__ = ["EngineRunner", "run_chung_ooi"]
