"""Kratos against the reduced model: one check and a time-step convergence study
(:mod:`dem_check.engines.check` with Kratos' drop test)."""

from dem_check.engines import check
from dem_check.engines.kratos.drop import drop_test

__all__ = ["convergence_study", "engine_check"]

_NOTES = ("kratos_law", "damping_gamma [-]", "plate_radius [m]")
"""Kratos settings copied into a comparison's notes."""


def engine_check(grain, sensor, law, velocity, time_step=None, *, tolerances=None, **options):
    """Run the impact in Kratos and in the reduced model, and compare them.

    See :func:`dem_check.engines.check.engine_check`; ``notes`` also holds Kratos' law
    name, ``DAMPING_GAMMA`` and the plate radius.
    """
    return check.engine_check(
        drop_test,
        grain,
        sensor,
        law,
        velocity,
        time_step,
        tolerances=tolerances,
        notes=_NOTES,
        **options,
    )


def convergence_study(grain, sensor, law, velocity, time_steps, **options):
    """Errors of Kratos against the reduced model as the time step shrinks.

    See :func:`dem_check.engines.check.convergence_study` (``attrs["order"]``: the observed
    orders).
    """
    return check.convergence_study(drop_test, grain, sensor, law, velocity, time_steps, **options)
