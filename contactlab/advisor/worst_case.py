"""Worst-case sensor errors over a species' ranges (corners and centre)."""

from contactlab.advisor.species import load_species
from contactlab.bodies import Grain, Sensor
from contactlab.laws import Hertz
from contactlab.study.points import simulate_points
from contactlab.study.setup import Scatter, StudySetup
from contactlab.validation import check_number

__all__ = [
    "ADVISOR_SAMPLES_PER_PERIOD",
    "PAPER_SENSOR_MASS",
    "QUANTITIES",
    "sensor_errors",
    "worst_error",
]

QUANTITIES = ("force", "time", "both")
"""Which error a target applies to: peak force, contact time, or the larger of the two."""


ADVISOR_SAMPLES_PER_PERIOD = 40.0
"""Output grid of the advisor's impacts (samples per sensor period or contact time): the
lobe and the peaks are refined on the dense solution, the grid only has to find them."""

PAPER_SENSOR_MASS = 1.233e-3
"""Moving mass of the paper's sensor, a 10 mm x 2 mm steel disc [kg]."""


def _setup(species, velocity, sensor_mass, damping_ratio):
    """A study set-up whose Hertz law is rebuilt from each grain's material data."""
    lo = [r[0] for r in (species.diameter, species.density, species.youngs_modulus)]
    grain = Grain(
        diameter=lo[0], density=lo[1], youngs_modulus=lo[2], poisson_ratio=species.poisson_ratio
    )
    return StudySetup(
        grain=grain,
        sensor=Sensor.from_resonance(40e3, mass=sensor_mass, damping_ratio=damping_ratio),
        law=Hertz.from_material(grain.material()),
        velocity=velocity,
        scatter=Scatter(repetitions=1, spread=0.0),
        size_dependence="material",
        samples_per_period=ADVISOR_SAMPLES_PER_PERIOD,
    )


def sensor_errors(
    species,
    resonance,
    *,
    velocity=2.0,
    sensor_mass=PAPER_SENSOR_MASS,
    damping_ratio=0.02,
    cases="corners",
):
    """Errors a sensor makes on the grains of a species.

    Parameters
    ----------
    species : Species or str
        The species (or a preset name / TOML path).
    resonance : float
        Sensor resonance [Hz].
    velocity : float, default 2.0
        Impact speed [m/s].
    sensor_mass : float, default 1.233e-3
        Moving mass of the sensor [kg] (the paper's steel disc).
    damping_ratio : float, default 0.02
        Sensor damping ratio [-].
    cases : {"corners", "centre"}
        Grains evaluated (see :meth:`Species.grains`).

    Returns
    -------
    list of dict
        Per grain: ``diameter [m]``, ``density [kg/m^3]``, ``youngs_modulus [Pa]``,
        ``contact_time [s]``, ``time_error [%]``, ``force_error [%]`` (signed).

    Notes
    -----
    The grains' impacts (elastic Hertz from each grain's material) are solved together
    by :func:`contactlab.batch.hertz_impacts` (:func:`contactlab.study.points.simulate_points`).
    """
    species = load_species(species)
    resonance = check_number("resonance", resonance, low=0.0, unit="Hz")
    sensor_mass = check_number("sensor_mass", sensor_mass, low=0.0, unit="kg")
    setup = _setup(species, velocity, sensor_mass, damping_ratio)
    grains = species.grains(cases)
    overrides = [{f"grain.{k}": v for k, v in grain.items()} for grain in grains]
    tasks = [(setup, {**point, "sensor.resonance": resonance}, [1.0]) for point in overrides]
    rows = []
    for grain, out in zip(grains, simulate_points(tasks), strict=True):
        rows.append(
            {
                "diameter [m]": grain["diameter"],
                "density [kg/m^3]": grain["density"],
                "youngs_modulus [Pa]": grain["youngs_modulus"],
                "contact_time [s]": out["contact_time [s]"][0],
                "time_error [%]": out["time_error [%]"][0],
                "force_error [%]": out["force_error [%]"][0],
            }
        )
    return rows


def worst_error(rows, quantity):
    """Largest absolute error [%] of ``quantity`` over the rows of :func:`sensor_errors`."""
    keys = {"force": ["force"], "time": ["time"], "both": ["force", "time"]}[quantity]
    return max(abs(row[f"{k}_error [%]"]) for row in rows for k in keys)
