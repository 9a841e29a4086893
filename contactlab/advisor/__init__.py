"""Sensor advisor: how fast a force sensor must be for a grain species.

A species (``contactlab/data/species/*.toml``, or :class:`Species` built in Python) gives ranges of
grain diameter, density and Young's modulus, each with its literature source. The grain
hits the sensor through the elastic Hertz law built from that material data
(:meth:`contactlab.laws.Hertz.from_material`: the force rises smoothly from zero, as a real
contact does), at a given impact speed.

The *worst-case error* of a sensor is the largest absolute error (peak force, contact time,
or either) over the corners of the species' ranges plus their centre. The errors are not
monotone in the parameters (the sensor's ringing overlaps the pulse differently for each
grain), so this is a guide, not a bound.

:func:`advise` finds the lowest resonance whose worst-case error meets a target:

1. bracket: scan a log-spaced grid (:data:`SCAN_PER_DECADE` points per decade) from
   ``f_max`` down until the error first exceeds the target;
2. root: bisect in ``log f`` between that failing point and the next passing one, keeping
   a passing upper end, until the bracket is narrower than ``rtol``.

The answer is the upper end: a resonance that meets the target, above which the scan saw no
failure. A failing band narrower than the scan step can hide between scan points.
"""

from contactlab.advisor.advice import SCAN_PER_DECADE, Advice, advise
from contactlab.advisor.species import CASES, SPECIES_DIR, Species, list_species, load_species
from contactlab.advisor.worst_case import (
    ADVISOR_SAMPLES_PER_PERIOD,
    PAPER_SENSOR_MASS,
    QUANTITIES,
    sensor_errors,
)

__all__ = [
    "ADVISOR_SAMPLES_PER_PERIOD",
    "CASES",
    "PAPER_SENSOR_MASS",
    "QUANTITIES",
    "SCAN_PER_DECADE",
    "SPECIES_DIR",
    "Advice",
    "Species",
    "advise",
    "list_species",
    "load_species",
    "sensor_errors",
]
