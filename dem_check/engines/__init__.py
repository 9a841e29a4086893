"""Engines that rebuild the reduced model's impact: one module per engine, one interface.

>>> import contactlab as cl
>>> from dem_check.engines import drop_test
>>> grain = cl.Grain(diameter=5e-3, density=765.0)
>>> law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=0.0)
>>> setup = cl.config.ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": 2.0})
>>> res = drop_test(setup, engine="bullet")
>>> round(res.contact_time * 1e6, 1)  # pi sqrt(m/k) = 70.3 us
70.3

The interface
-------------
An engine is a module (or package) of this package, named in :data:`ENGINES`, that
provides::

    drop_test(config, *, time_step=None, **options) -> EngineResult

* ``config`` is a :class:`contactlab.config.ImpactConfig`, the one set-up shape: its
  ``grain``, ``sensor`` (``Sensor.rigid()`` is an immovable plate), ``law`` and
  ``velocity`` (grain speed towards the sensor at release [m/s]) mean what they mean for
  :func:`contactlab.simulate_impact`; ``time_step`` is the engine step [s] (``None``: the
  engine's own default). The engines here still read the former positional form
  ``drop_test(grain, sensor, law, velocity[, time_step])`` with a ``DeprecationWarning``
  (:func:`dem_check.engines.config.engine_config`);
* ``options`` are the engine's own keywords, each a keyword-only parameter of its
  ``drop_test`` (so an unknown one raises TypeError there);
* a law the engine cannot represent, or a time step too coarse for the contact or the
  sensor, raises :class:`~contactlab.errors.ParameterError` naming it;
* the result is an :class:`~dem_check.engines.result.EngineResult`: time from the first
  touch, the model's axis (x along the grain's travel, into the sensor), contact force S2
  and sensor signal S1 = k1 x1 + c1 v1 [N], so :func:`contactlab.compare` reads it as it
  reads :class:`contactlab.ImpactResult`.

Adding an engine is one module beside :mod:`dem_check.engines.bullet` and one line in
``pyproject.toml``'s ``[project.entry-points."contactlab.engines"]`` (the registry
:mod:`contactlab.engines` reads, so contactlab's own commands find the engine too, without
importing dem_check). Engines are imported when first asked for, so one whose library is
an optional extra costs nothing until it is used.
"""

from importlib.metadata import entry_points

from contactlab.audit import warn_if_broken
from contactlab.engines import GROUP, load_engine
from dem_check.engines.config import UNSET, engine_config
from dem_check.engines.result import EngineResult

__all__ = ["ENGINES", "EngineResult", "drop_test", "engine_module"]

ENGINES = {point.name: point.value for point in entry_points(group=GROUP)}
"""Engine name -> the module that implements the interface (see the module docstring), as
registered in ``pyproject.toml`` (bullet: pybullet's soft contact, LinearViscoelastic;
lammps: LAMMPS GRANULAR, linear and Hertz family, an extra; kratos: Kratos DEM, linear,
Hertz, damped Hertz, an extra)."""


engine_module = load_engine
"""The module of an engine named in :data:`ENGINES` (:func:`contactlab.engines.load_engine`:
an unknown name raises ParameterError listing the valid ones)."""


def drop_test(config, *fields, time_step=UNSET, engine="bullet", **options):
    """Drop the grain on the sensor in an engine and read the impact like the reduced model.

    Parameters
    ----------
    config : contactlab.config.ImpactConfig
        The set-up: grain, sensor, law (one the engine represents; pybullet:
        ``LinearViscoelastic``) and the grain speed towards the sensor at release [m/s]
        (``config.velocity``), as :func:`contactlab.simulate_impact` takes them; its other
        simulation keys (duration, sample rate, method) are the reduced model's, not the
        engine's.
    *fields
        Deprecated: ``drop_test(grain, sensor, law, velocity[, time_step])``, the same
        set-up as separate arguments; read with a ``DeprecationWarning``
        (:func:`dem_check.engines.config.engine_config`).
    time_step : float, optional
        Engine step [s]; default the engine's own.
    engine : str, default "bullet"
        A name in :data:`ENGINES`.
    **options
        The engine's own keywords (pybullet:
        :func:`dem_check.engines.bullet.drop_test`); an unknown one raises TypeError.

    Returns
    -------
    EngineResult
        Audited (:meth:`EngineResult.audit`: energy, one-sided force, momentum against the
        step's tolerances); an :class:`~contactlab.errors.AuditWarning` names a broken
        invariant.

    Raises
    ------
    ParameterError
        For a ``config`` that is not an ImpactConfig, an unknown engine (listing the valid
        names) or what the engine refuses.
    TypeError
        For arguments of neither form.
    """
    config, time_step = engine_config(config, fields, time_step, "dem_check.drop_test")
    module = engine_module(engine)
    result = module.drop_test(config, time_step=time_step, **options)
    warn_if_broken(result.audit(), f"the {engine} engine's result")
    return result
