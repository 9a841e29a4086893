"""Inverse problems on measured traces: the sensor, the true force, the contact law.

* :func:`identify_sensor`: resonance and damping ratio from free ringing.
* :func:`reconstruct_force`: the contact force S2(t) from the signal S1(t).
* :func:`fit_contact`: a contact law's parameters through the two-mass model, judged
  (``quality``: chi-squared against the noise, residual whiteness).
* :func:`compare_laws`: every fittable law fitted and ranked by BIC.
* :func:`export_dem`: the fitted law as LIGGGHTS, MercuryDPM, YADE or EDEM input.

See ``docs/inverse.md`` for the methods and the accuracies achieved.
"""

from contactlab.inverse.compare_laws import LawComparison, compare_laws
from contactlab.inverse.demo import reconstruction_demo
from contactlab.inverse.export import DEM_CODES, export_dem, read_fit
from contactlab.inverse.fit import (
    FIT_MODELS,
    ContactFit,
    FitQuality,
    FitQualityWarning,
    FittedParameter,
    IdentifiabilityWarning,
    fit_contact,
)
from contactlab.inverse.identify import SensorIdentification, identify_sensor, matrix_pencil
from contactlab.inverse.plots import (
    plot_fit,
    plot_identification,
    plot_reconstruction,
)
from contactlab.inverse.reconstruct import ForceReconstruction, reconstruct_force
from contactlab.inverse.synthetic import synthetic_trace

__all__ = [
    "DEM_CODES",
    "FIT_MODELS",
    "ContactFit",
    "FitQuality",
    "FitQualityWarning",
    "FittedParameter",
    "ForceReconstruction",
    "IdentifiabilityWarning",
    "LawComparison",
    "SensorIdentification",
    "compare_laws",
    "export_dem",
    "fit_contact",
    "identify_sensor",
    "matrix_pencil",
    "plot_fit",
    "plot_identification",
    "plot_reconstruction",
    "read_fit",
    "reconstruct_force",
    "reconstruction_demo",
    "synthetic_trace",
]
