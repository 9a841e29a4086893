"""Benchmark: the contact family read of a record's first touches (issue 22), its cost.

On ``bench_realistic.py --speed``'s record (1.5 million samples at 5 MHz, every effect),
:func:`contactlab.inverse.lobe_onset.lobe_family` on the record's 4 most significant
impacts as ``dem_check.campaign.onsets`` calls it: each damping's fit started from its
neighbour's (one scan per lobe and family), against the reference of the same run that
scans every fit (``start`` dropped: as before the warm start). Prints both families and
dampings read, the CPU times, their ratio and the fits made.

Run: ``.venv/bin/python benchmarks/bench_family_read.py``
"""

import os
import time

import bench_realistic  # beside this script: its speed record

from contactlab.inverse import lobe_onset
from dem_check.campaign import find_impacts, onsets
from dem_check.campaign.detection import ANALYSED


def strongest_lobes():
    """The speed record's sensor and the first lobes of its ``onsets.FAMILY_IMPACTS`` most
    significant analysed impacts, as ``dem_check.campaign.onsets`` reads the family on
    (with ``onsets.FAMILY_NOISE_MODEL``'s noise model)."""
    _, sensor, _ = bench_realistic.hard()
    found = find_impacts(bench_realistic.speed_record().trace, sensor, fit_onsets=False)
    windows = [w for w in found.impacts if w.status in ANALYSED]
    strongest = sorted(windows, key=lambda w: -w.significance)[: onsets.FAMILY_IMPACTS]
    return sensor, [onsets._lobe(found, w, sensor, onsets.FAMILY_NOISE_MODEL) for w in strongest]


def main():
    sensor, lobes = strongest_lobes()
    fit_lobe, fits = lobe_onset.fit_lobe, {"started": 0, "scanned": 0}

    def counted(*args, **kwargs):
        fits["started" if kwargs.get("start") is not None else "scanned"] += 1
        return fit_lobe(*args, **kwargs)

    def scanned(*args, **kwargs):  # the reference: every fit scans
        return counted(*args, **{**kwargs, "start": None})

    print(f"load average before: {os.getloadavg()[0]:.1f} (1 min)")
    for name, patch in (("warm-started", counted), ("every fit scanned", scanned)):
        lobe_onset.fit_lobe = patch
        fits.update(started=0, scanned=0)
        cpu = time.process_time()
        family, damping = lobe_onset.lobe_family(lobes, sensor)
        cpu = time.process_time() - cpu
        lobe_onset.fit_lobe = fit_lobe
        print(f"{name}: {family} {damping} in {cpu:.2f} s of CPU ({fits})")
        if name == "warm-started":
            warm = cpu
    print(f"ratio (reference over warm-started): {cpu / warm:.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f} (1 min)")


if __name__ == "__main__":
    main()
