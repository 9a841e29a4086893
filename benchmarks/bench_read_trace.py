"""Benchmark: reading a 10-million-sample CSV with ``read_trace``.

Writes a generic CSV and a Rigol ``X,CH1,Start,Increment`` CSV of ``--samples`` samples
to a temporary directory, then reads each in a fresh process (so peak memory is that of
the read alone) with ``contactlab.traces.read_trace`` and with plain
``pandas.read_csv(engine="c")`` and ``numpy.loadtxt`` as references. Prints wall time,
samples per second, peak resident memory above the process's size before the read, as a
multiple of the final arrays' size (t and values, 16 bytes per sample), and the ratio of
each time to the pandas reference.

Run: ``.venv/bin/python benchmarks/bench_read_trace.py [--samples N] [--skip-loadtxt]``
"""

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

CHILD = """
import json, sys, time
import numpy as np, pandas as pd
from contactlab.traces import read_trace

def status_kib(key):
    with open("/proc/self/status") as fh:
        return next(int(line.split()[1]) for line in fh if line.startswith(key))

kind, path = sys.argv[1], sys.argv[2]
with open("/proc/self/clear_refs", "w") as fh:
    fh.write("5")  # reset the peak (VmHWM) to the current size: measure the read alone
before = status_kib("VmRSS:")
start = time.perf_counter()
if kind == "read_trace":
    trace = read_trace(path)
    arrays = (trace.t, trace.values)
elif kind == "pandas":
    frame = pd.read_csv(path, engine="c", skiprows={skip}, header=None, usecols=[0, 1])
    arrays = tuple(frame[c].to_numpy() for c in frame.columns)
else:
    data = np.loadtxt(path, delimiter=",", skiprows={skip}, usecols=(0, 1))
    arrays = (data[:, 0], data[:, 1])
seconds = time.perf_counter() - start
print(json.dumps({{"seconds": seconds, "peak_kib": status_kib("VmHWM:") - before,
                  "n": int(arrays[0].size), "array_bytes": sum(a.nbytes for a in arrays)}}))
"""


def write_files(directory, samples):
    """Write the two benchmark files; return {label: (path, header rows to skip)}."""
    from contactlab.traces import Trace, write_trace

    rng = np.random.default_rng(0)
    increment = 4e-9
    t = np.arange(samples) * increment
    t += -1e-3
    # 12-bit codes at 0.5 mV per code, written as a scope writes them (short decimals).
    values = np.round(np.round(rng.normal(0.0, 40.0, samples)) * 0.5e-3, 4)
    trace = Trace(t, values, "V", {"sample_interval": increment})
    files = {}
    for label, fmt, skip in (("generic", "generic", 1), ("rigol", "rigol-sequence", 2)):
        path = Path(directory) / f"bench_{label}.csv"
        started = time.perf_counter()
        write_trace(path, trace, fmt)
        size = path.stat().st_size / 1e6
        print(f"wrote {path.name}: {size:.0f} MB in {time.perf_counter() - started:.1f} s")
        files[label] = (path, skip)
    return files


def measure(kind, path, skip):
    """Run one read in a fresh interpreter; return its JSON report."""
    code = CHILD.format(skip=skip)
    out = subprocess.run(
        [sys.executable, "-c", code, kind, str(path)],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(out.stdout)


def main():
    """Write, read, report."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--skip-loadtxt", action="store_true", help="numpy.loadtxt is slow")
    args = parser.parse_args()
    kinds = ["read_trace", "pandas"] + ([] if args.skip_loadtxt else ["loadtxt"])
    with tempfile.TemporaryDirectory() as directory:
        files = write_files(directory, args.samples)
        print(
            f"\n{'file':8} {'reader':11} {'time [s]':>9} {'samples/s':>11} "
            f"{'peak/arrays':>12} {'vs pandas':>10}"
        )
        for label, (path, skip) in files.items():
            reports = {kind: measure(kind, path, skip) for kind in kinds}
            reference = reports["pandas"]["seconds"]
            for kind, r in reports.items():
                assert r["n"] == args.samples, (kind, r["n"])
                multiple = r["peak_kib"] * 1024 / r["array_bytes"]
                print(
                    f"{label:8} {kind:11} {r['seconds']:9.2f} {r['n'] / r['seconds']:11.3g} "
                    f"{multiple:12.2f} {r['seconds'] / reference:10.2f}"
                )
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(
        f"\n(peak/arrays: peak RSS of the read above the process before it, divided by the "
        f"final t and values arrays, {16 * args.samples / 1e6:.0f} MB; writer process peak "
        f"{rss:.0f} MiB)"
    )


if __name__ == "__main__":
    main()
