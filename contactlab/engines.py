"""DEM engines as plug-ins: found by name through package metadata, never imported by name.

contactlab runs beside DEM engines (the demo's drop bench, ``contactlab benchmark
chung-ooi --engines lammps,kratos``) but does not depend on the package that wraps them:
an engine registers itself in the entry-point group :data:`GROUP`, in the
``pyproject.toml`` of the package that provides it, and contactlab looks it up by name
when a command asks for it (:func:`load_engine`). The dependency points one way, from
the engines to contactlab: contactlab defines the interface, :mod:`dem_check.engines`
implements it for pybullet, LAMMPS and Kratos, and a third package can add an engine
without touching either (the way pytest finds its plug-ins).

The interface
-------------
The entry point names a module (or any object) that provides::

    drop_test(config, *, time_step=None, **options) -> result

with ``config`` a :class:`contactlab.config.ImpactConfig` (grain, sensor, law and the
impact speed ``config.velocity`` [m/s], the one set-up shape), ``time_step`` the engine
step [s] (``None``: the engine's default) and ``result`` read as
:class:`contactlab.ImpactResult` is (``t``, ``contact_force``, ``sensor_force`` [N],
``contact_time`` [s], ``peak_contact_force`` [N], ``restitution``), and optionally::

    oblique_impact(grain, normal_law, tangential_law, velocity, angle, *, spin=0.0)
    base_case_check(out) -> list of pathlib.Path   # the paper's base case, files written
    load()                                          # ImportError naming the missing extra

A name is registered when the providing package is installed (``pip install -e .``
re-reads ``pyproject.toml``).
"""

import difflib
from importlib.metadata import entry_points

from contactlab.errors import ParameterError

__all__ = ["GROUP", "engine_names", "load_engine"]

GROUP = "contactlab.engines"
"""Entry-point group in which DEM engines register (name -> module)."""


def _registered():
    return {point.name: point for point in entry_points(group=GROUP)}


def engine_names():
    """Names of the registered engines, sorted.

    Returns
    -------
    tuple of str
    """
    return tuple(sorted(_registered()))


def load_engine(name):
    """The engine registered as ``name`` (the object its entry point names).

    Parameters
    ----------
    name : str
        Engine name, e.g. ``"lammps"``.

    Returns
    -------
    module
        It provides ``drop_test`` and perhaps ``oblique_impact``, ``base_case_check`` and
        ``load`` (module docstring).

    Raises
    ------
    ParameterError
        For a name no installed package registers; the message lists the registered ones.
    """
    registered = _registered()
    if not isinstance(name, str) or name not in registered:
        near = difflib.get_close_matches(str(name), registered, n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        names = ", ".join(sorted(registered)) or "none (is the engines' package installed?)"
        raise ParameterError(f"unknown engine {name!r}{hint}; valid names: {names}")
    return registered[name].load()
