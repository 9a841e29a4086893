"""contactlab: grain impacts on force sensors, exactly.

A grain (mass ``m2``) strikes a force sensor's moving mass ``m1`` through a contact law;
the sensor's measuring element (``k1``, ``c1``) reports ``S1 = k1 x1 + c1 v1``, which is
not the true contact force ``S2``. This package gives the contact laws DEM codes use, an
exact two-mass solver, pulse metrics, and the error study of Keska et al. (2021).

SI units everywhere. Overlap ``d = x2 - x1 > 0`` in compression; ``S2 >= 0``.
"""

from contactlab import analytic, laws, metrics, solver
from contactlab.bodies import Grain, Sensor
from contactlab.errors import (
    ParameterError,
    PlausibilityWarning,
    ResolutionWarning,
    TraceFormatError,
    UnknownParameterError,
    WindowWarning,
)
from contactlab.oblique_result import ObliqueResult
from contactlab.result import ImpactResult
from contactlab.solver import (  # noqa: F401 (handed on through solver.__all__)
    METHODS,
    simulate_impact,
    simulate_oblique,
    wall_contact_time,
    wall_dissipated_energy,
    wall_impact,
    wall_restitution,
)

__all__ = [
    "Grain",
    "ImpactResult",
    "ObliqueResult",
    "ParameterError",
    "PlausibilityWarning",
    "ResolutionWarning",
    "Sensor",
    "TraceFormatError",
    "UnknownParameterError",
    "WindowWarning",
    "analytic",
    "laws",
    "metrics",
]
__all__ += solver.__all__  # the solver's public names, handed on (one list)

__version__ = "0.1.0"

_SUBPACKAGES = ("advisor", "inverse", "study", "testing")
"""Imported on first use (``cl.study``...): they pull in pandas, the trace readers or the
engine bench, which a single simulation does not need."""


def __getattr__(name):
    if name in _SUBPACKAGES:
        import importlib

        return importlib.import_module(f"contactlab.{name}")
    raise AttributeError(f"module 'contactlab' has no attribute {name!r}")
