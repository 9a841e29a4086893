"""The pybullet drop bench against the reduced model: one check, a convergence study, the
paper's base case (:mod:`dem_check.engines.check` with pybullet's drop test)."""

from dem_check.engines import check
from dem_check.engines.bullet.drop import drop_test
from dem_check.engines.check import EngineChecks
from dem_check.engines.config import UNSET, engine_config

__all__ = ["base_case_check", "convergence_study", "engine_check"]

_NOTES = ("contact_damping_passed [N*s/m]", "compensate_damping")
"""pybullet's own settings copied into a comparison's notes."""

_CHECKS = EngineChecks(drop_test, "bullet", _NOTES)

TIME_STEPS = (4e-7, 2e-7, 1e-7, 5e-8)
"""Default engine steps [s] of :func:`convergence_study`."""


def engine_check(config, *fields, time_step=UNSET, compensate_damping=False, tolerances=None):
    """Run the impact in pybullet and in the reduced model, and compare them.

    Parameters
    ----------
    config, time_step, compensate_damping
        As for :func:`drop_test` (no gravity: the reduced model has none).
    *fields
        Deprecated: ``engine_check(grain, sensor, law, velocity[, time_step])``
        (:func:`dem_check.engines.config.engine_config`).
    tolerances : dict, optional
        Tolerances by quantity name (:data:`contactlab.compare.DEFAULT_TOLERANCES`).

    Returns
    -------
    contactlab.compare.Comparison
        See :func:`dem_check.engines.check.engine_check`; ``notes`` also holds the damping
        passed to the engine and ``compensate_damping``.
    """
    config, time_step = engine_config(config, fields, time_step, "dem_check.bullet.engine_check")
    return _CHECKS.engine_check(
        config,
        time_step=time_step,
        tolerances=tolerances,
        compensate_damping=compensate_damping,
    )


def convergence_study(config, *fields, time_steps=UNSET, compensate_damping=False):
    """Errors of pybullet against the reduced model as the time step shrinks.

    ``config`` is an ImpactConfig and ``time_steps`` the engine steps [s], default
    :data:`TIME_STEPS` (the deprecated ``grain, sensor, law, velocity[, time_steps]`` form
    warns; with ``time_steps`` also given as the keyword it is refused). See
    :func:`dem_check.engines.check.convergence_study`; ``attrs["compensate_damping"]``
    records the setting.
    """
    config, time_steps = engine_config(
        config,
        fields,
        time_steps,
        "dem_check.bullet.convergence_study",
        last="time_steps",
        default=TIME_STEPS,
    )
    frame = check.convergence_study(
        drop_test, config, time_steps, compensate_damping=compensate_damping
    )
    frame.attrs["compensate_damping"] = bool(compensate_damping)
    return frame


base_case_check = _CHECKS.base_case_check
"""pybullet check of the paper's base case, written to a folder (``make demo``):
``bullet_base_case.png``, ``.csv`` and ``.json``."""
