"""Benchmark: the compiled unit signal of the lobe model and its sampling at the window's
times (``contactlab.kernels.held_force``) in the contact family read of a record's first
touches (issue 22).

On ``bench_realistic.py --speed``'s record (1.5 million samples at 5 MHz, every effect),
:func:`contactlab.inverse.lobe_onset.lobe_family` on the record's 4 most significant
impacts, as ``dem_check.campaign.onsets`` calls it, three ways in the same run: both
kernels compiled; the sampling (``LobeModel.response``) through its numpy reference,
``numpy.interp``; and both through the references, ``numpy.interp`` and
``scipy.signal.lfilter`` as before (``tests/support/held_reference.py``). Prints the
family and damping each read (the same: the kernels equal the references to the last
bit), their CPU times and the ratios.

Run: ``.venv/bin/python benchmarks/bench_held_force.py``
"""

import os
import sys
import time
from pathlib import Path

import bench_family_read  # beside this script: the speed record's strongest lobes

from contactlab.inverse import lobe_model, lobe_onset

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
from held_reference import numpy_response, numpy_unit


def _reference_unit(model, tau, shape=None):
    """``LobeModel.unit`` through the numpy reference."""
    u, h = (model.u, model.h) if shape is None else shape
    count = model.fine * (model.t.size + 2)
    return numpy_unit(model.dt / model.fine, count, tau, u, h, *model.filter)


def _reference_response(model, t0, tau, unit=None):
    """``LobeModel.response`` through the numpy reference."""
    s, r = model.unit(tau) if unit is None else unit
    return numpy_response(model.t, t0, s, r)


def main():
    sensor, lobes = bench_family_read.strongest_lobes()
    compiled = lobe_model.LobeModel.unit, lobe_model.LobeModel.response
    lobe_onset.lobe_family(lobes[:1], sensor)  # the kernels loaded once, not timed
    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    ways = {
        "compiled": compiled,
        "numpy.interp sampling": (compiled[0], _reference_response),
        "numpy and scipy": (_reference_unit, _reference_response),
    }
    times = {}
    for name, (unit, response) in ways.items():
        lobe_model.LobeModel.unit, lobe_model.LobeModel.response = unit, response
        cpu = time.process_time()
        family, damping = lobe_onset.lobe_family(lobes, sensor)
        times[name] = time.process_time() - cpu
        lobe_model.LobeModel.unit, lobe_model.LobeModel.response = compiled
        print(f"{name}: {family} {damping!r} in {times[name]:.2f} s of CPU")
    for name in list(ways)[1:]:
        print(f"ratio ({name} over compiled): {times[name] / times['compiled']:.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
