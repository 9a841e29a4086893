"""How the files of this folder were made from the published records (see README.md).

Run once, with the five ``measurements_<n>.npy`` files of ladisk/pyFRF at commit
55431fd3c328ddc719232cc34b891291c9982a2e in a folder::

    python data/traces/real/extract.py /path/to/pyFRF/data

Each source file holds three rows of 25600 float64 values: time [s], the impact
hammer's force [N] and the response. Only the force row is kept, every sample, as
float64 (bit for bit), in the HDF5 convention of ``contactlab.traces.hdf5`` (gzip).
"""

import sys
from pathlib import Path

import h5py
import numpy as np

SAMPLE_RATE = 25600.0
"""The records' sample rate [Hz]: their time row is n / 25600 to within 1 ns."""


def main(source):
    here = Path(__file__).parent
    for n in range(1, 6):
        t, force, _ = np.load(Path(source) / f"measurements_{n}.npy")
        assert np.max(np.abs(t - np.arange(t.size) / SAMPLE_RATE)) < 1e-9
        with h5py.File(here / f"pyfrf_hammer_{n}.h5", "w") as h5file:
            data = h5file.create_dataset(
                "hammer/force", data=force, compression="gzip", compression_opts=9
            )
            data.attrs["unit"] = "N"
            data.attrs["start_time"] = 0.0
            data.attrs["sample_interval"] = 1.0 / SAMPLE_RATE
            data.attrs["instrument"] = (
                f"impact hammer force, ladisk/pyFRF data/measurements_{n}.npy (row 1)"
            )


if __name__ == "__main__":
    main(sys.argv[1])
