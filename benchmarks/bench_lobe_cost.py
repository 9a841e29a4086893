"""Benchmark: the lobe fits' residual and Nelder-Mead compiled (session 17), against the
numpy and scipy code they replaced, timed in the same run.

On ``bench_realistic.py --speed``'s record (1.5 million samples at 5 MHz, every effect):
:func:`contactlab.inverse.lobe_onset.lobe_family` on its 4 most significant impacts, as
``bench_family_read.py`` calls it (112 lobe fits), with
:class:`~contactlab.inverse.lobe_model.LobeModel`'s ``rss``, ``scan`` and ``fit`` as they
are (:mod:`contactlab.kernels.lobe_cost`) and replaced by the reference: the residual of
:meth:`~contactlab.inverse.lobe_model.LobeModel.solve` (numpy), the onsets scanned one by
one and ``scipy.optimize.minimize(method="Nelder-Mead")``. Alternated, best of three;
prints the CPU times, their ratio and both readings (the same family and damping).

Run: ``.venv/bin/python benchmarks/bench_lobe_cost.py``
"""

import os
import time

import bench_family_read  # beside this script: the speed record's strongest lobes
import numpy as np
from scipy import optimize

from contactlab.inverse import lobe_onset
from contactlab.inverse.lobe_model import LobeModel

COMPILED = {name: getattr(LobeModel, name) for name in ("rss", "scan", "fit")}


def _rss(model, t0, tau):
    return model.solve(t0, tau, coefficients=False)[1]


def _scan(model, onsets, tau):
    unit = model.white_unit(tau)
    return np.array([model.solve(t0, tau, unit, coefficients=False)[1] for t0 in onsets])


def _fit(model, simplex, xatol, fatol):
    best = optimize.minimize(
        lambda x: model.solve(x[0], x[1], coefficients=False)[1],
        simplex[0],
        method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": xatol, "fatol": fatol},
    )
    return float(best.x[0]), float(best.x[1])


REFERENCE = {"rss": _rss, "scan": _scan, "fit": _fit}


def timed(methods, lobes, sensor):
    """CPU time [s] of the family read with ``methods`` on LobeModel, and its reading."""
    for name, method in methods.items():
        setattr(LobeModel, name, method)
    try:
        started = time.process_time()
        read = lobe_onset.lobe_family(lobes, sensor)
        return time.process_time() - started, read
    finally:
        for name, method in COMPILED.items():
            setattr(LobeModel, name, method)


def main():
    sensor, lobes = bench_family_read.strongest_lobes()
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    best, reads = {"compiled": np.inf, "numpy": np.inf}, {}
    for _ in range(3):
        for name, methods in (("compiled", COMPILED), ("numpy", REFERENCE)):
            seconds, reads[name] = timed(methods, lobes, sensor)
            best[name] = min(best[name], seconds)
    for name in best:
        print(f"{name}: {reads[name][0]} {reads[name][1]} in {best[name]:.2f} s of CPU")
    print(f"ratio (numpy over compiled): {best['numpy'] / best['compiled']:.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
