"""LAMMPS against the reduced model: one check, a time-step convergence study, the paper's
base case (:mod:`dem_check.engines.check` with LAMMPS' drop test)."""

from dem_check.engines import check
from dem_check.engines.lammps.drop import drop_test

__all__ = ["base_case_check", "convergence_study", "engine_check"]

_NOTES = ("granular_model", "plate_radius [m]")
"""LAMMPS settings copied into a comparison's notes."""


def engine_check(grain, sensor, law, velocity, time_step=None, *, tolerances=None, **options):
    """Run the impact in LAMMPS and in the reduced model, and compare them.

    Parameters
    ----------
    grain, sensor, law, velocity, time_step
        As for :func:`~dem_check.engines.lammps.drop.drop_test`.
    tolerances : dict, optional
        Tolerances by quantity name (:data:`contactlab.compare.DEFAULT_TOLERANCES`).
    **options
        ``drop_test``'s keywords (``plate_radius``, ``gap``).

    Returns
    -------
    contactlab.compare.Comparison
        See :func:`dem_check.engines.check.engine_check`; ``notes`` also holds the LAMMPS
        granular model's words and the plate radius.
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
    """Errors of LAMMPS against the reduced model as the time step shrinks.

    See :func:`dem_check.engines.check.convergence_study` (``attrs["order"]``: the observed
    orders; 2 for undamped laws, 1 with damping, see ``docs/dem_check.md``).
    """
    return check.convergence_study(drop_test, grain, sensor, law, velocity, time_steps, **options)


def base_case_check(out_dir, time_step=None):
    """LAMMPS check of the paper's base case, written to a folder (``dem_check
    lammps-check``, ``make demo``).

    See :func:`dem_check.engines.check.base_case_check`: ``lammps_base_case.png``,
    ``.csv`` and ``.json``.
    """
    return check.base_case_check(drop_test, "lammps", out_dir, time_step, notes=_NOTES)
