"""LAMMPS against the reduced model: one check, a time-step convergence study (orders 2
for undamped laws, 1 with damping, ``docs/dem_check.md``), the paper's base case (``dem-check
lammps-check``, ``make demo``): :class:`dem_check.engines.check.EngineChecks` with LAMMPS'
drop test; ``notes`` also hold the LAMMPS granular model's words and the plate radius."""

from dem_check.engines.check import EngineChecks
from dem_check.engines.lammps.drop import drop_test

__all__ = ["base_case_check", "convergence_study", "engine_check"]

_CHECKS = EngineChecks(drop_test, "lammps", ("granular_model", "plate_radius [m]"))

engine_check = _CHECKS.engine_check
convergence_study = _CHECKS.convergence_study
base_case_check = _CHECKS.base_case_check
