"""Published DEM benchmarks, run against closed forms (and engines where available).

* :mod:`~contactlab.benchmarks.chung_ooi`: Chung & Ooi (2011), particle impact tests.
"""
