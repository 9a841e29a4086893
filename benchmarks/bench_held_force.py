"""Benchmark: the compiled unit signal of the lobe model (``contactlab.kernels.held_force``)
in the contact family read of a record's first touches (issue 22).

On ``bench_realistic.py --speed``'s record (1.5 million samples at 5 MHz, every effect),
:func:`contactlab.inverse.lobe_onset.lobe_family` on the record's 4 most significant
impacts, as ``dem_check.campaign.onsets`` calls it: with the compiled unit signal, and
with the reference of the same run, ``numpy.interp`` and ``scipy.signal.lfilter`` as
before (``tests/support/held_reference.py``). Prints the family and damping each read
(the same: the kernel is equal to the reference to the last bit), their CPU times and
the ratio.

Run: ``.venv/bin/python benchmarks/bench_held_force.py``
"""

import os
import sys
import time
from pathlib import Path

import bench_family_read  # beside this script: the speed record's strongest lobes

from contactlab.inverse import lobe_model, lobe_onset

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
from held_reference import numpy_unit


def _reference_unit(model, tau, shape=None):
    """``LobeModel.unit`` through the numpy reference."""
    u, h = (model.u, model.h) if shape is None else shape
    count = model.fine * (model.t.size + 2)
    return numpy_unit(model.dt / model.fine, count, tau, u, h, *model.filter)


def main():
    sensor, lobes = bench_family_read.strongest_lobes()
    compiled_unit = lobe_model.LobeModel.unit
    lobe_onset.lobe_family(lobes[:1], sensor)  # the kernel loaded once, not timed
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    times = {}
    for name, unit in (("compiled", compiled_unit), ("numpy and scipy", _reference_unit)):
        lobe_model.LobeModel.unit = unit
        cpu = time.process_time()
        family, damping = lobe_onset.lobe_family(lobes, sensor)
        times[name] = time.process_time() - cpu
        lobe_model.LobeModel.unit = compiled_unit
        print(f"{name}: {family} {damping!r} in {times[name]:.2f} s of CPU")
    print(f"ratio (reference over compiled): {times['numpy and scipy'] / times['compiled']:.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
