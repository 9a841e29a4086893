"""Batched linear impacts against simulate_impact in a loop (the batch issue's targets).

1. Impacts per second in one process: :func:`contactlab.batch.linear_impacts` on the
   paper study's impacts (5 mm grain, k2 = 1e5 N/m +-50 %, c2 = 1 N*s/m, v0 = 2 m/s, the
   paper's disc sensor at 10-300 kHz, log-spaced), against ``simulate_impact`` plus its
   headline numbers in a loop on a subset, timed in the same run; target >= 50 000/s.
   The largest relative deviation of each output over the subset is printed beside it.
2. The kernel's compile time in a fresh process with an empty cache, and its load time
   from the on-disk cache (what CI and a user pay once, and at every new process).
3. Dask: the same frame on a local cluster of 1 and of 2 worker processes.

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
from contactlab.batch import RESULT_COLUMNS, dask_linear_impacts, linear_impacts

ROWS = 100_000
LOOP_ROWS = 400


def study_frame(n, seed=0):
    rng = np.random.default_rng(seed)
    disc = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    k1 = disc.mass * (2 * np.pi * np.geomspace(10e3, 300e3, n)) ** 2
    grain = cl.Grain(diameter=5e-3, density=765.0)
    return pd.DataFrame(
        {
            "m1 [kg]": disc.mass,
            "k1 [N/m]": k1,
            "c1 [N*s/m]": 2 * 0.02 * np.sqrt(k1 * disc.mass),
            "m2 [kg]": grain.mass,
            "k2 [N/m]": 1e5 * rng.uniform(0.5, 1.5, n),
            "c2 [N*s/m]": 1.0,
            "v0 [m/s]": 2.0,
        }
    )


def loop(frame):
    out = []
    for m1, k1, c1, m2, k2, c2, v0 in frame.to_numpy():
        res = cl.simulate_impact(
            cl.Grain.from_mass(m2), cl.Sensor(m1, k1, c1), cl.laws.LinearViscoelastic(k2, c2), v0
        )
        out.append(
            (
                res.contact_time,
                res.sensor_response_time,
                res.peak_contact_force,
                res.peak_sensor_force,
                res.restitution,
                len(res.contact_intervals),
            )
        )
    return np.array(out)


def _rate(frame, threads):
    """Impacts per second of ``linear_impacts`` on ``threads`` threads (median of 3)."""
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        got = linear_impacts(frame, threads=threads)
        times.append(time.perf_counter() - t0)
    return len(frame) / statistics.median(times), got


def throughput():
    frame = study_frame(ROWS)
    linear_impacts(frame.iloc[:2])  # load the compiled kernel
    rate, got = _rate(frame, 1)
    threaded, _ = _rate(frame, None)
    subset = frame.iloc[:: ROWS // LOOP_ROWS]
    t0 = time.perf_counter()
    ref = loop(subset)
    loop_rate = len(subset) / (time.perf_counter() - t0)
    print(f"1. {ROWS} paper-study impacts, sensor 10-300 kHz")
    print(f"   batch  {rate:9.0f} impacts/s   one thread")
    print(f"   batch  {threaded:9.0f} impacts/s   {os.cpu_count()} threads (target >= 50 000)")
    print(f"   loop   {loop_rate:9.0f} impacts/s   ratio {rate / loop_rate:6.1f}x")
    mine = got.iloc[:: ROWS // LOOP_ROWS][list(RESULT_COLUMNS)].to_numpy()
    rel = np.abs(mine - ref) / np.abs(ref)
    for name, worst in zip(RESULT_COLUMNS, rel.max(axis=0), strict=True):
        print(f"   max relative deviation {name:24s} {worst:.1e}")


_COMPILE = "import time; t=time.perf_counter(); {body}; print(time.perf_counter()-t)"
_BODY = (
    "import pandas as pd, contactlab.batch as b; "
    "b.linear_impacts(pd.DataFrame([[1e-3, 6e7, 1.0, 5e-5, 1e5, 1.0, 2.0]], "
    "columns=[c.name for c in b.LINEAR_INPUTS]))"
)


def compile_time():
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        runs = [
            float(
                subprocess.run(
                    [sys.executable, "-c", _COMPILE.format(body=_BODY)],
                    env=env,
                    capture_output=True,
                    text=True,
                    check=True,
                ).stdout
            )
            for _ in range(2)
        ]
    print("\n2. Compiled kernel (import contactlab.batch + first call, fresh process)")
    print(f"   empty cache (compile)  {runs[0]:6.1f} s")
    print(f"   from the disk cache    {runs[1]:6.1f} s")


def dask_speedup():
    from dask.distributed import Client, LocalCluster

    frame = study_frame(ROWS // 2, seed=1)
    rates = {}
    for workers in (1, 2):
        with (
            LocalCluster(
                n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            dask_linear_impacts(frame.iloc[:8], client)  # workers load the kernel
            t0 = time.perf_counter()
            dask_linear_impacts(frame, client)
            rates[workers] = len(frame) / (time.perf_counter() - t0)
    print(f"\n3. Dask, {len(frame)} impacts, local cluster of worker processes")
    print(f"   1 worker   {rates[1]:9.0f} impacts/s")
    print(f"   2 workers  {rates[2]:9.0f} impacts/s   speed-up {rates[2] / rates[1]:.2f}x")


def main():
    throughput()
    compile_time()
    dask_speedup()


if __name__ == "__main__":
    main()
