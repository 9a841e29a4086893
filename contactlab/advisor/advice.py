"""The lowest resonance that meets an error target: bracket on a log scan, then bisect."""

import math
from dataclasses import dataclass, field

import numpy as np

from contactlab.advisor.species import Species, load_species
from contactlab.advisor.worst_case import PAPER_SENSOR_MASS, QUANTITIES, sensor_errors, worst_error
from contactlab.bodies import Grain, Sensor
from contactlab.plausibility import check_plausible, internal
from contactlab.validation import check_choice, check_number

__all__ = ["SCAN_PER_DECADE", "Advice", "advise"]

SCAN_PER_DECADE = 8
"""Scan points per decade of resonance when bracketing the answer."""


@dataclass
class Advice:
    """What :func:`advise` found.

    Attributes
    ----------
    species : Species
    target : float
        Error target [%].
    quantity : str
        ``"force"``, ``"time"`` or ``"both"``.
    lowest_resonance : float or None
        Lowest resonance [Hz] meeting the target (None: not reached up to ``f_max``).
    error_at_lowest : float
        Worst-case error [%] at ``lowest_resonance`` (at ``f_max`` when not reached).
    f_min, f_max : float
        Search range [Hz].
    resonance : float or None
        The sensor asked about [Hz], if any.
    at_resonance : list of dict
        Per-grain errors of that sensor (:func:`sensor_errors`).
    settings : dict
        Impact speed, sensor mass and damping, cases, evaluations.
    """

    species: Species
    target: float
    quantity: str
    lowest_resonance: float
    error_at_lowest: float
    f_min: float
    f_max: float
    resonance: float = None
    at_resonance: list = field(default_factory=list)
    settings: dict = field(default_factory=dict)

    @property
    def error_at_resonance(self):
        """Worst-case error [%] of the sensor asked about (None if none was)."""
        return worst_error(self.at_resonance, self.quantity) if self.at_resonance else None

    def to_dict(self):
        """JSON-ready summary with unit-bearing keys."""
        return {
            "species": self.species.to_dict(),
            "target [%]": self.target,
            "quantity": self.quantity,
            "lowest_resonance [Hz]": self.lowest_resonance,
            "worst_error_at_lowest [%]": self.error_at_lowest,
            "search_range [Hz]": [self.f_min, self.f_max],
            "resonance [Hz]": self.resonance,
            "worst_error_at_resonance [%]": self.error_at_resonance,
            "errors_at_resonance": self.at_resonance,
            "settings": self.settings,
        }

    def format_text(self):
        """A few lines for the terminal."""
        what = {
            "force": "peak-force",
            "time": "contact-time",
            "both": "peak-force and contact-time",
        }
        lines = [
            f"species: {self.species.name} ({self.species.description})",
            f"  diameter {self.species.diameter[0] * 1e3:g}-{self.species.diameter[1] * 1e3:g} mm,"
            f" density {self.species.density[0]:g}-{self.species.density[1]:g} kg/m^3, "
            f"E {self.species.youngs_modulus[0] / 1e6:g}-{self.species.youngs_modulus[1] / 1e6:g}"
            f" MPa, impact {self.settings['velocity [m/s]']:g} m/s",
        ]
        target = f"{what[self.quantity]} error <= {self.target:g} % (worst case)"
        if self.lowest_resonance is None:
            lines.append(
                f"no sensor up to {self.f_max / 1e3:g} kHz meets {target}: "
                f"{self.error_at_lowest:.1f} % at {self.f_max / 1e3:g} kHz"
            )
        elif self.lowest_resonance <= self.f_min:
            lines.append(f"every sensor from {self.f_min / 1e3:g} kHz up meets {target}")
        else:
            lines.append(
                f"lowest sensor resonance for {target}: {self.lowest_resonance / 1e3:.3g} kHz "
                f"({self.error_at_lowest:.2f} % there)"
            )
        if self.resonance is not None:
            lines.append(
                f"a {self.resonance / 1e3:g} kHz sensor: worst {what[self.quantity]} error "
                f"{self.error_at_resonance:.1f} %"
            )
            for row in self.at_resonance:
                lines.append(
                    f"  d {row['diameter [m]'] * 1e3:.3g} mm, rho {row['density [kg/m^3]']:.4g}, "
                    f"E {row['youngs_modulus [Pa]'] / 1e6:.4g} MPa: contact "
                    f"{row['contact_time [s]'] * 1e6:.1f} us, time error "
                    f"{row['time_error [%]']:+.1f} %, force error {row['force_error [%]']:+.1f} %"
                )
        return "\n".join(lines)


def _warn_implausible(species, velocity, sensor_mass, damping_ratio, cases):
    """A :class:`~contactlab.errors.PlausibilityWarning` for each of the user's values
    outside what real grains and sensors span, once, before the search."""
    for corner in species.grains(cases):
        Grain(**corner, poisson_ratio=species.poisson_ratio)
    speed = check_number("velocity", velocity, low=0.0, unit="m/s")
    check_plausible("impact_velocity", speed, "velocity")
    Sensor.from_resonance(40e3, mass=sensor_mass, damping_ratio=damping_ratio)


def advise(
    species,
    target=5.0,
    *,
    quantity="force",
    resonance=None,
    velocity=2.0,
    sensor_mass=PAPER_SENSOR_MASS,
    damping_ratio=0.02,
    f_min=5e3,
    f_max=1e6,
    rtol=0.01,
    cases="corners",
):
    """The lowest sensor resonance that meets an error target for a grain species.

    Parameters
    ----------
    species : Species or str
        A :class:`Species`, a preset name (:func:`list_species`) or a TOML path.
    target : float, default 5
        Largest acceptable worst-case error [%].
    quantity : {"force", "time", "both"}
        Which error the target applies to.
    resonance : float, optional
        Also report the errors of a sensor with this resonance [Hz].
    velocity : float, default 2.0
        Impact speed [m/s].
    sensor_mass : float, default 1.233e-3
        Moving mass of the sensor [kg].
    damping_ratio : float, default 0.02
        Sensor damping ratio [-].
    f_min, f_max : float
        Search range [Hz].
    rtol : float, default 0.01
        Relative width of the final bracket [-].
    cases : {"corners", "centre"}
        Grains evaluated per resonance (see :meth:`Species.grains`).

    Returns
    -------
    Advice
    """
    species = load_species(species)
    target = check_number("target", target, low=0.0, unit="%")
    check_choice("quantity", quantity, QUANTITIES)
    f_min = check_number("f_min", f_min, low=0.0, unit="Hz")
    f_max = check_number("f_max", f_max, low=f_min, unit=f"Hz (> f_min = {f_min:g})")
    rtol = check_number("rtol", rtol, low=1e-6, high=1.0, low_open=False)
    sensor_mass = check_number("sensor_mass", sensor_mass, low=0.0, unit="kg")
    if resonance is not None:
        resonance = check_number("resonance", resonance, low=0.0, unit="Hz")
        check_plausible("sensor_resonance", resonance, "resonance")
    _warn_implausible(species, velocity, sensor_mass, damping_ratio, cases)
    options = dict(
        velocity=velocity, sensor_mass=sensor_mass, damping_ratio=damping_ratio, cases=cases
    )
    evaluations = 0

    def error(f):
        nonlocal evaluations
        evaluations += 1
        with internal():  # the scan's own resonances reach beyond real sensors
            return worst_error(sensor_errors(species, f, **options), quantity)

    n = max(2, math.ceil(SCAN_PER_DECADE * math.log10(f_max / f_min)) + 1)
    scan = np.geomspace(f_min, f_max, n)[::-1]
    good, good_error = None, None
    bad = None
    for f in scan:
        e = error(float(f))
        if e > target:
            bad = float(f)
            break
        good, good_error = float(f), e
    if good is None:
        lowest, at_lowest = None, e
    elif bad is None:
        lowest, at_lowest = good, good_error
    else:
        while math.log(good / bad) > math.log1p(rtol):
            mid = math.sqrt(good * bad)
            e = error(mid)
            if e > target:
                bad = mid
            else:
                good, good_error = mid, e
        lowest, at_lowest = good, good_error
    at_resonance = []
    if resonance is not None:
        at_resonance = sensor_errors(species, resonance, **options)
    return Advice(
        species=species,
        target=target,
        quantity=quantity,
        lowest_resonance=lowest,
        error_at_lowest=at_lowest,
        f_min=f_min,
        f_max=f_max,
        resonance=resonance,
        at_resonance=at_resonance,
        settings={
            "velocity [m/s]": velocity,
            "sensor_mass [kg]": sensor_mass,
            "sensor_damping_ratio [-]": damping_ratio,
            "cases": cases,
            "grains per resonance": len(species.grains(cases)),
            "evaluations": evaluations,
            "law": "hertz (elastic, from the grain's material data)",
        },
    )
