"""The two-mass grain/sensor solver: one impact, cut into pieces at its events.

* :mod:`~contactlab.solver.impact`: :func:`simulate_impact`, the event loop and its checks;
* :mod:`~contactlab.solver.system`: the two-mass system (matrices, right-hand side, signal);
* :mod:`~contactlab.solver.exact`: linear contact branches and free flight, exactly;
* :mod:`~contactlab.solver.adaptive`: nonlinear contact pieces with DOP853;
* :mod:`~contactlab.solver.propagators`: the modes of linear time-invariant pieces and
  their events;
* :mod:`~contactlab.solver.dop853`: the lean DOP853 stepper;
* :mod:`~contactlab.solver.euler`: the paper's explicit Euler (reference method);
* :mod:`~contactlab.solver.wall`: a law's impact on an immovable wall and its numbers;
* :mod:`~contactlab.solver.oblique`: :func:`simulate_oblique`, friction and spin.

The solved pieces are data (:mod:`contactlab.kernels.segments`), which
:class:`~contactlab.ImpactResult` evaluates from the layer below it.
"""

from contactlab.solver.impact import METHODS, simulate_impact
from contactlab.solver.oblique import simulate_oblique
from contactlab.solver.wall import (
    wall_contact_time,
    wall_dissipated_energy,
    wall_impact,
    wall_restitution,
)

__all__ = [
    "METHODS",
    "simulate_impact",
    "simulate_oblique",
    "wall_contact_time",
    "wall_dissipated_energy",
    "wall_impact",
    "wall_restitution",
]
