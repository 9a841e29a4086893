"""Kratos against the reduced model: one check and a time-step convergence study
(:class:`dem_check.engines.check.EngineChecks` with Kratos' drop test); ``notes`` also hold
Kratos' law name, ``DAMPING_GAMMA`` and the plate radius."""

from dem_check.engines.check import EngineChecks
from dem_check.engines.kratos.drop import drop_test

__all__ = ["convergence_study", "engine_check"]

_CHECKS = EngineChecks(drop_test, "kratos", ("kratos_law", "damping_gamma [-]", "plate_radius [m]"))

engine_check = _CHECKS.engine_check
convergence_study = _CHECKS.convergence_study
