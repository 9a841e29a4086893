"""Grain species presets: ranges of diameter, density and modulus, each with its source."""

import itertools
import os
from dataclasses import dataclass, field
from pathlib import Path

from contactlab.config import read_document
from contactlab.errors import ParameterError
from contactlab.validation import check_choice, check_number

__all__ = ["CASES", "SPECIES_DIR", "Species", "list_species", "load_species", "value_range"]

SPECIES_DIR = Path(__file__).resolve().parent.parent / "data" / "species"
"""Folder of the species presets."""

CASES = ("corners", "centre")
"""Grains evaluated per resonance: the corners of the ranges plus the centre, or the
centre only (a quick look)."""

_PROPERTIES = {
    "diameter": "m",
    "density": "kg/m^3",
    "youngs_modulus": "Pa",
    "poisson_ratio": "-",
}

_OPTIONAL = {"friction_steel": "-"}
"""Tables a species file may add: the grain's Coulomb friction coefficient against steel
(a sensor head), for oblique impacts (:class:`contactlab.laws.Mindlin`)."""


def value_range(name, value, unit):
    """(low, high) from a number or a [low, high] pair, both checked (a ParameterError
    naming ``name`` otherwise)."""
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
    friction_steel : float or (float, float), optional
        Coulomb friction coefficient of the grain against steel [-].
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
    friction_steel: tuple | None = None
    description: str = ""
    sources: dict = field(default_factory=dict)

    def __post_init__(self):
        for prop in ("diameter", "density", "youngs_modulus"):
            object.__setattr__(
                self, prop, value_range(prop, getattr(self, prop), _PROPERTIES[prop])
            )
        object.__setattr__(
            self,
            "poisson_ratio",
            check_number("poisson_ratio", self.poisson_ratio, low=-1.0, high=0.5, high_open=False),
        )
        if self.friction_steel is not None:
            object.__setattr__(
                self, "friction_steel", value_range("friction_steel", self.friction_steel, "-")
            )

    @classmethod
    def from_toml(cls, path):
        """Read a species file (see ``contactlab/data/species/README.md`` for the format).

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
        allowed = {"name", "description", *_PROPERTIES, *_OPTIONAL}
        unknown = sorted(set(data) - allowed)
        missing = sorted(set(_PROPERTIES) - set(data))
        if unknown or missing:
            raise ParameterError(
                f"{path}: unknown key(s) {unknown}, missing table(s) {missing}; a species "
                f"file has name, description and tables {list(_PROPERTIES)} (optionally "
                f"{list(_OPTIONAL)})"
            )
        values, sources = {}, {}
        present = {p: u for p, u in (_PROPERTIES | _OPTIONAL).items() if p in data}
        for prop, unit in present.items():
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
            "friction_steel [-]": None
            if self.friction_steel is None
            else list(self.friction_steel),
            "sources": dict(self.sources),
        }


def list_species():
    """Names of the species presets in ``contactlab/data/species``."""
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
