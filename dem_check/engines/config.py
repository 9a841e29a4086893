"""The set-up an engine entry takes: one :class:`~contactlab.config.ImpactConfig`.

``drop_test(config, time_step=..., **options)`` and the checks built on it
(``engine_check``, ``convergence_study``) read the grain, sensor, law and impact speed
from an ImpactConfig, the one set-up shape of contactlab (TOML files, presets, the
study's grid points and the batch rows are made of it). The former positional form
``f(grain, sensor, law, velocity[, time_step])`` is still read, with a
``DeprecationWarning`` naming the new call; its fifth positional and the keyword together
are refused (the entries' keyword defaults to :data:`UNSET`, so a given keyword is told
from an omitted one).
"""

import warnings

from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError

__all__ = ["UNSET", "engine_config"]


class _Unset:
    """The type of :data:`UNSET`."""

    def __repr__(self):
        return "UNSET"


UNSET = _Unset()
"""Default of an engine entry's ``time_step`` (``time_steps``) keyword: not given, so
:func:`engine_config` can refuse it beside the old form's fifth positional argument."""


def engine_config(config, fields, time_step, call, last="time_step", default=None):
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
        The keyword value of ``last``, :data:`UNSET` when the caller omitted it.
    call : str
        The entry's name for messages, e.g. ``"dem_check.engines.lammps.drop_test"``.
    last : str, default "time_step"
        Name of the optional fifth positional argument of the old form (``time_steps``
        for a convergence study).
    default : object, default None
        The value of ``last`` when neither ``fields`` nor the keyword gives it.

    Returns
    -------
    config : ImpactConfig
    time_step : object
        ``fields``' fourth item, or the keyword's value, or ``default``.

    Raises
    ------
    ParameterError
        For a lone ``config`` that is not an ImpactConfig, or ``last`` given both as the
        old form's fifth positional argument and as the keyword.
    TypeError
        For positional arguments after an ImpactConfig, or an old form of the wrong length.
    """
    if isinstance(config, ImpactConfig):
        if fields:
            raise TypeError(f"{call}(config, ...) takes {last} as a keyword")
        return config, default if time_step is UNSET else time_step
    if not fields:
        raise ParameterError(
            f"config must be a contactlab.config.ImpactConfig; got {type(config).__name__}"
        )
    if len(fields) not in (3, 4):
        raise TypeError(
            f"{call} takes an ImpactConfig (or the deprecated grain, sensor, law, "
            f"velocity[, {last}]); got {1 + len(fields)} positional arguments"
        )
    if len(fields) == 4 and time_step is not UNSET:
        raise ParameterError(
            f"{last} is given twice to {call}: as the fifth positional argument "
            f"({fields[3]!r}) and as the keyword ({time_step!r}); give it once, as the keyword"
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
    if len(fields) == 4:
        return config, fields[3]
    return config, default if time_step is UNSET else time_step
