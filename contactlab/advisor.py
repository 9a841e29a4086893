"""Sensor advisor: how fast a force sensor must be for a grain species.

A species (``data/species/*.toml``, or :class:`Species` built in Python) gives ranges of
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

import itertools
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from contactlab.bodies import Grain, Sensor
from contactlab.config import read_document
from contactlab.errors import ParameterError
from contactlab.laws import Hertz
from contactlab.study.setup import Scatter, StudySetup
from contactlab.study.sweep import simulate_point
from contactlab.validation import check_choice, check_number

__all__ = [
    "CASES",
    "QUANTITIES",
    "SPECIES_DIR",
    "Advice",
    "Species",
    "advise",
    "list_species",
    "load_species",
    "sensor_errors",
]

SPECIES_DIR = Path(__file__).resolve().parent.parent / "data" / "species"
"""Folder of the species presets."""

QUANTITIES = ("force", "time", "both")
"""Which error a target applies to: peak force, contact time, or the larger of the two."""

CASES = ("corners", "centre")
"""Grains evaluated per resonance: the corners of the ranges plus the centre, or the
centre only (a quick look)."""

SCAN_PER_DECADE = 8
"""Scan points per decade of resonance when bracketing the answer."""

ADVISOR_SAMPLES_PER_PERIOD = 40.0
"""Output grid of the advisor's impacts (samples per sensor period or contact time): the
lobe and the peaks are refined on the dense solution, the grid only has to find them."""

PAPER_SENSOR_MASS = 1.233e-3
"""Moving mass of the paper's sensor, a 10 mm x 2 mm steel disc [kg]."""

_PROPERTIES = {
    "diameter": "m",
    "density": "kg/m^3",
    "youngs_modulus": "Pa",
    "poisson_ratio": "-",
}


def _range(name, value, unit):
    """(low, high) from a number or a [low, high] pair, both checked."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise ParameterError(f"{name} must be a number or [low, high]; got {value!r}")
        lo, hi = (check_number(name, v, low=0.0, unit=unit) for v in value)
        if lo > hi:
            raise ParameterError(f"{name}: low {lo!r} is above high {hi!r}")
        return lo, hi
    v = check_number(name, value, low=0.0, unit=unit)
    return v, v


@dataclass(frozen=True)
class Species:
    """Ranges of a grain species' properties, with their sources.

    Parameters
    ----------
    name : str
        Species name.
    diameter : float or (float, float)
        Equivalent sphere diameter [m] (a value or a range).
    density : float or (float, float)
        Grain density [kg/m^3].
    youngs_modulus : float or (float, float)
        Young's modulus of the grain [Pa].
    poisson_ratio : float
        Poisson ratio [-].
    description : str, optional
        One line about the material (moisture range ...).
    sources : dict, optional
        Property name -> literature source.
    """

    name: str
    diameter: tuple
    density: tuple
    youngs_modulus: tuple
    poisson_ratio: float
    description: str = ""
    sources: dict = field(default_factory=dict)

    def __post_init__(self):
        for prop in ("diameter", "density", "youngs_modulus"):
            object.__setattr__(self, prop, _range(prop, getattr(self, prop), _PROPERTIES[prop]))
        object.__setattr__(
            self,
            "poisson_ratio",
            check_number("poisson_ratio", self.poisson_ratio, low=-1.0, high=0.5, high_open=False),
        )

    @classmethod
    def from_toml(cls, path):
        """Read a species file (see ``data/species/README.md`` for the format).

        Parameters
        ----------
        path : str or pathlib.Path
            The TOML file.

        Returns
        -------
        Species
        """
        path = Path(path)
        data = read_document(path, "species")
        allowed = {"name", "description", *_PROPERTIES}
        unknown = sorted(set(data) - allowed)
        missing = sorted(set(_PROPERTIES) - set(data))
        if unknown or missing:
            raise ParameterError(
                f"{path}: unknown key(s) {unknown}, missing table(s) {missing}; a species "
                f"file has name, description and tables {list(_PROPERTIES)}"
            )
        values, sources = {}, {}
        for prop, unit in _PROPERTIES.items():
            table = data[prop]
            if not isinstance(table, dict) or set(table) != {"value", "unit", "source"}:
                raise ParameterError(f"{path}: [{prop}] needs exactly value, unit and source")
            if table["unit"] != unit:
                raise ParameterError(
                    f"{path}: [{prop}] unit must be {unit!r}; got {table['unit']!r}"
                )
            if not str(table["source"]).strip():
                raise ParameterError(f"{path}: [{prop}] source is empty")
            values[prop], sources[prop] = table["value"], " ".join(str(table["source"]).split())
        try:
            return cls(
                name=str(data.get("name", path.stem)),
                description=str(data.get("description", "")),
                sources=sources,
                **values,
            )
        except ParameterError as exc:
            raise ParameterError(f"{path}: {exc}") from None

    def grains(self, cases="corners"):
        """The grains to evaluate: dicts of diameter [m], density [kg/m^3], modulus [Pa].

        Parameters
        ----------
        cases : {"corners", "centre"}
            Corners of the ranges plus the centre, or the centre only.
        """
        check_choice("cases", cases, CASES)
        ranges = [self.diameter, self.density, self.youngs_modulus]
        centre = tuple(0.5 * (lo + hi) for lo, hi in ranges)
        points = [centre]
        if cases == "corners":
            points += [c for c in itertools.product(*ranges) if c != centre]
        points = list(dict.fromkeys(points))
        keys = ("diameter", "density", "youngs_modulus")
        return [dict(zip(keys, p, strict=True)) for p in points]

    def to_dict(self):
        """Species data with unit-bearing keys and sources (JSON-ready)."""
        return {
            "name": self.name,
            "description": self.description,
            "diameter [m]": list(self.diameter),
            "density [kg/m^3]": list(self.density),
            "youngs_modulus [Pa]": list(self.youngs_modulus),
            "poisson_ratio [-]": self.poisson_ratio,
            "sources": dict(self.sources),
        }


def list_species():
    """Names of the species presets in ``data/species``."""
    return sorted(p.stem for p in SPECIES_DIR.glob("*.toml"))


def load_species(name):
    """A species preset by name, or a species TOML file by path.

    Parameters
    ----------
    name : str, pathlib.Path or Species
        A preset name (``"wheat"``, see :func:`list_species`), a path ending in
        ``.toml``, or a :class:`Species` (returned as it is).

    Returns
    -------
    Species
    """
    if isinstance(name, Species):
        return name
    if not isinstance(name, (str, os.PathLike)):
        raise ParameterError(
            f"species must be a Species, a preset name or a TOML path; got {name!r}"
        )
    path = Path(name)
    if path.suffix == ".toml":
        return Species.from_toml(path)
    check_choice("species", name, tuple(list_species()))
    return Species.from_toml(SPECIES_DIR / f"{name}.toml")


def _setup(species, velocity, sensor_mass, damping_ratio):
    """A study set-up whose Hertz law is rebuilt from each grain's material data."""
    lo = [r[0] for r in (species.diameter, species.density, species.youngs_modulus)]
    grain = Grain(
        diameter=lo[0], density=lo[1], youngs_modulus=lo[2], poisson_ratio=species.poisson_ratio
    )
    return StudySetup(
        grain=grain,
        sensor=Sensor.from_resonance(40e3, mass=sensor_mass, damping_ratio=damping_ratio),
        law=Hertz.from_material(*grain.material()),
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
    """
    species = load_species(species)
    resonance = check_number("resonance", resonance, low=0.0, unit="Hz")
    setup = _setup(species, velocity, sensor_mass, damping_ratio)
    rows = []
    for grain in species.grains(cases):
        overrides = {f"grain.{k}": v for k, v in grain.items()}
        overrides["sensor.resonance"] = resonance
        out = simulate_point(setup, overrides, [1.0])
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


def _worst(rows, quantity):
    keys = {"force": ["force"], "time": ["time"], "both": ["force", "time"]}[quantity]
    return max(abs(row[f"{k}_error [%]"]) for row in rows for k in keys)


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
        return _worst(self.at_resonance, self.quantity) if self.at_resonance else None

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
    if resonance is not None:
        resonance = check_number("resonance", resonance, low=0.0, unit="Hz")
    options = dict(
        velocity=velocity, sensor_mass=sensor_mass, damping_ratio=damping_ratio, cases=cases
    )
    evaluations = 0

    def error(f):
        nonlocal evaluations
        evaluations += 1
        return _worst(sensor_errors(species, f, **options), quantity)

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
