"""Batched impacts against simulate_impact in a loop (the batch issue's targets).

1. Impacts per second in one process: :func:`contactlab.batch.linear_impacts` on the
   paper study's impacts (5 mm grain, k2 = 1e5 N/m +-50 %, c2 = 1 N*s/m, v0 = 2 m/s, the
   paper's disc sensor at 10-300 kHz, log-spaced), against ``simulate_impact`` plus its
   headline numbers in a loop on a subset, timed in the same run; target >= 50 000/s.
   The largest relative deviation of each output over the subset is printed beside it.
   Then the same for :func:`contactlab.batch.hertz_impacts` (the grain's damped Hertz
   law from its material, e = 0.5, kH +-50 %; target >= 5 000/s at 1e-6 accuracy),
   against ``simulate_impact`` at its default rtol 1e-10.
2. The kernels' compile time in a fresh process with an empty cache, and their load time
   from the on-disk cache (what CI and a user pay once, and at every new process).
3. Dask: the same frames on a local cluster of 1 and of 2 worker processes.

Medians of repeated runs where cheap; the machine is shared, so expect noise.
"""

import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd

import contactlab as cl
from contactlab.batch import (
    RESULT_COLUMNS,
    dask_hertz_impacts,
    dask_linear_impacts,
    hertz_impacts,
    linear_impacts,
)
from contactlab.batch.rows import result_row

ROWS = 100_000
HERTZ_ROWS = 20_000
LOOP_ROWS = 400
GRAIN = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
TSUJI = cl.laws.HertzDamped.from_material(GRAIN.material(), 0.5, GRAIN.mass)


def _sensors(n):
    disc = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    k1 = disc.mass * (2 * np.pi * np.geomspace(10e3, 300e3, n)) ** 2
    return {"m1 [kg]": disc.mass, "k1 [N/m]": k1, "c1 [N*s/m]": 2 * 0.02 * np.sqrt(k1 * disc.mass)}


def study_frame(n, seed=0):
    rng = np.random.default_rng(seed)
    return pd.DataFrame(
        {
            **_sensors(n),
            "m2 [kg]": GRAIN.mass,
            "k2 [N/m]": 1e5 * rng.uniform(0.5, 1.5, n),
            "c2 [N*s/m]": 1.0,
            "v0 [m/s]": 2.0,
        }
    )


def hertz_frame(n, seed=0):
    rng = np.random.default_rng(seed)
    return pd.DataFrame(
        {
            **_sensors(n),
            "m2 [kg]": GRAIN.mass,
            "k_hertz [N/m**1.5]": TSUJI.k_hertz * rng.uniform(0.5, 1.5, n),
            "damping [N*s/m**1.25]": TSUJI.damping,
            "v0 [m/s]": 2.0,
        }
    )


def loop(frame, law):
    """simulate_impact and its six numbers on every row; ``law(k, c)`` builds the law."""
    out = []
    for m1, k1, c1, m2, k2, c2, v0 in frame.to_numpy():
        res = cl.simulate_impact(cl.Grain.from_mass(m2), cl.Sensor(m1, k1, c1), law(k2, c2), v0)
        out.append(result_row(res))
    return np.array(out)


def _rate(impacts, frame, threads):
    """Impacts per second of ``impacts`` on ``threads`` threads (median of 3)."""
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        got = impacts(frame, threads=threads)
        times.append(time.perf_counter() - t0)
    return len(frame) / statistics.median(times), got


def throughput(title, impacts, frame, law, target):
    impacts(frame.iloc[:2])  # load the compiled kernel
    rate, got = _rate(impacts, frame, 1)
    threaded, _ = _rate(impacts, frame, None)
    step = len(frame) // LOOP_ROWS
    subset = frame.iloc[::step]
    t0 = time.perf_counter()
    ref = loop(subset, law)
    loop_rate = len(subset) / (time.perf_counter() - t0)
    print(f"{title}: {len(frame)} impacts, sensor 10-300 kHz")
    print(f"   batch  {rate:9.0f} impacts/s   one thread")
    print(f"   batch  {threaded:9.0f} impacts/s   {os.cpu_count()} threads (target >= {target})")
    print(f"   loop   {loop_rate:9.0f} impacts/s   ratio {rate / loop_rate:6.1f}x (one thread)")
    mine = got.iloc[::step][list(RESULT_COLUMNS)].to_numpy()
    rel = np.abs(mine - ref) / np.abs(ref)
    for name, worst in zip(RESULT_COLUMNS, rel.max(axis=0), strict=True):
        print(f"   max relative deviation {name:24s} {worst:.1e}")


_COMPILE = "import time; t=time.perf_counter(); {body}; print(time.perf_counter()-t)"
_BODY = (
    "import pandas as pd, contactlab.batch as b; "
    "b.{impacts}(pd.DataFrame([[1e-3, 6e7, 1.0, 5e-5, 1e5, 1.0, 2.0]], "
    "columns=[c.name for c in b.{inputs}]))"
)


def compile_time():
    print("\n2. Compiled kernels (import contactlab.batch + first call, fresh process)")
    for impacts, inputs in (("linear_impacts", "LINEAR_INPUTS"), ("hertz_impacts", "HERTZ_INPUTS")):
        body = _BODY.format(impacts=impacts, inputs=inputs)
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            runs = [
                float(
                    subprocess.run(
                        [sys.executable, "-c", _COMPILE.format(body=body)],
                        env=env,
                        capture_output=True,
                        text=True,
                        check=True,
                    ).stdout
                )
                for _ in range(2)
            ]
        print(f"   {impacts}: empty cache (compile) {runs[0]:5.1f} s, cached {runs[1]:4.1f} s")


def dask_speedup(title, on_dask, frame):
    from dask.distributed import Client, LocalCluster

    rates = {}
    for workers in (1, 2):
        with (
            LocalCluster(
                n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            on_dask(frame.iloc[:8], client)  # workers load the kernel
            t0 = time.perf_counter()
            on_dask(frame, client)
            rates[workers] = len(frame) / (time.perf_counter() - t0)
    print(f"   {title}, {len(frame)} impacts")
    print(f"     1 worker   {rates[1]:9.0f} impacts/s")
    print(f"     2 workers  {rates[2]:9.0f} impacts/s   speed-up {rates[2] / rates[1]:.2f}x")


def main():
    linear, tsuji = cl.laws.LinearViscoelastic, cl.laws.HertzDamped
    throughput("1a. Linear", linear_impacts, study_frame(ROWS), linear, "50 000")
    throughput("1b. Damped Hertz", hertz_impacts, hertz_frame(HERTZ_ROWS), tsuji, "5 000")
    compile_time()
    print("\n3. Dask, local cluster of worker processes")
    dask_speedup("linear", dask_linear_impacts, study_frame(ROWS // 2, seed=1))
    dask_speedup("damped Hertz", dask_hertz_impacts, hertz_frame(HERTZ_ROWS // 2, seed=1))


if __name__ == "__main__":
    main()
