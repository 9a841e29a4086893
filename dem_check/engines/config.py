"""The set-up an engine entry takes: one :class:`~contactlab.config.ImpactConfig`.

``drop_test(config, time_step=..., **options)`` and the checks built on it
(``engine_check``, ``convergence_study``) read the grain, sensor, law and impact speed
from an ImpactConfig, the one set-up shape of contactlab (TOML files, presets, the
study's grid points and the batch rows are made of it). The former positional form
``f(grain, sensor, law, velocity[, time_step])`` is still read, with a
``DeprecationWarning`` naming the new call.
"""

import warnings

from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError

__all__ = ["engine_config"]


def engine_config(config, fields, time_step, call, last="time_step"):
    """The ImpactConfig and the trailing argument of an engine entry's arguments.

    Parameters
    ----------
    config : ImpactConfig or Grain
        The set-up; a Grain (or anything not an ImpactConfig) followed by ``fields`` is the
        deprecated positional form.
    fields : tuple
        The further positional arguments: empty for an ImpactConfig, else ``(sensor, law,
        velocity[, last])``.
    time_step : object
        The keyword value of ``last`` (returned unless ``fields`` gives it).
    call : str
        The entry's name for messages, e.g. ``"dem_check.engines.lammps.drop_test"``.
    last : str, default "time_step"
        Name of the optional fifth positional argument of the old form (``time_steps``
        for a convergence study).

    Returns
    -------
    config : ImpactConfig
    time_step : object
        ``fields``' fourth item if given, else ``time_step``.

    Raises
    ------
    ParameterError
        For a lone ``config`` that is not an ImpactConfig.
    TypeError
        For positional arguments after an ImpactConfig, or an old form of the wrong length.
    """
    if isinstance(config, ImpactConfig):
        if fields:
            raise TypeError(f"{call}(config, ...) takes {last} as a keyword")
        return config, time_step
    if not fields:
        raise ParameterError(
            f"config must be a contactlab.config.ImpactConfig; got {type(config).__name__}"
        )
    if len(fields) not in (3, 4):
        raise TypeError(
            f"{call} takes an ImpactConfig (or the deprecated grain, sensor, law, "
            f"velocity[, {last}]); got {1 + len(fields)} positional arguments"
        )
    warnings.warn(
        f"{call}(grain, sensor, law, velocity, ...) is deprecated: call "
        f"{call}(ImpactConfig(grain, sensor, law, {{'velocity': velocity}}), {last}=...) "
        "(contactlab.config.ImpactConfig)",
        DeprecationWarning,
        stacklevel=3,
    )
    sensor, law, velocity = fields[:3]
    config = ImpactConfig(config, sensor, law, {"velocity": velocity})
    return config, fields[3] if len(fields) == 4 else time_step
