"""Impact set-ups from TOML files and named presets.

A file has four tables, every value in SI units::

    [grain]       diameter [m], density [kg/m^3] or mass [kg], optional youngs_modulus
                  or shear_modulus [Pa] and poisson_ratio [-]
    [contact]     law = "<name>" (see contactlab.laws.LAWS) and that law's parameters;
                  Hertz-family laws may instead say from_material = true and take the
                  grain's material data (plus restitution or yield_pressure as needed,
                  and other_youngs_modulus, other_poisson_ratio, other_radius for a
                  second body other than a rigid flat)
    [sensor]      rigid = true; or mass [kg], stiffness [N/m], damping [N*s/m];
                  or resonance [Hz] with mass [kg] and damping_ratio [-] or damping;
                  or resonance [Hz] with a disc: diameter [m], thickness [m],
                  damping_ratio [-], density [kg/m^3]
    [simulation]  velocity [m/s], duration [s], sample_rate [Hz], method, threshold [N]

Unknown tables and keys are rejected by name; the flags ``rigid`` and ``from_material``
must be TOML booleans (``true``/``false``), not strings or numbers.
"""

import inspect
import json
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from contactlab.analytic import RIGID_FLAT, Material
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import LAWS
from contactlab.laws.base import stated
from contactlab.quantities import column
from contactlab.solver import simulate_impact
from contactlab.validation import check_choice, check_path, unknown_keywords, with_suggestion

__all__ = [
    "PRESET_DIR",
    "ImpactConfig",
    "law_from_table",
    "list_presets",
    "load",
    "load_config",
    "load_preset",
    "read_document",
    "second_body",
    "sensor_from_table",
]

PRESET_DIR = Path(__file__).resolve().parent / "data" / "presets"
"""Folder of the named impact presets (the paper's Figures 5-9)."""

_TABLES = ("grain", "contact", "sensor", "simulation")
_SIMULATION_KEYS = ("velocity", "duration", "sample_rate", "method", "threshold")
OTHER_BODY_KEYS = tuple(f"other_{field}" for field in Material._fields)
"""A ``[contact]`` table's keys of a from_material law's second body (its ``other``;
a rigid flat where none is given)."""


@dataclass
class ImpactConfig:
    """A complete impact set-up: the arguments of :func:`contactlab.simulate_impact`.

    The one shape of a set-up: a TOML file or preset reads into it, the study's grid
    points are made of it (:meth:`contactlab.study.StudySetup.config`), and it writes its
    own batch row (:meth:`batch_row`) and runs itself (:meth:`simulate`).
    """

    grain: Grain
    sensor: Sensor
    law: object
    simulation: dict

    @property
    def velocity(self):
        """Grain speed towards the sensor at the touch [m/s]."""
        return self.simulation["velocity"]

    def batch_row(self):
        """The set-up as one input row of a batch solver (columns named as in
        :mod:`contactlab.quantities`; the law gives its own, ``law._batch_contact()``):
        :func:`contactlab.batch.linear_impacts` for a LinearViscoelastic law,
        :func:`contactlab.batch.hertz_impacts` for Hertz and HertzDamped (elastic Hertz:
        zero damping).

        Raises
        ------
        ParameterError
            For a law no batch solver takes.
        """
        law, sensor = self.law, self.sensor
        batch_contact = stated(law, "_batch_contact")
        if batch_contact is None:
            have = ", ".join(cls.__name__ for cls in LAWS.values() if "_batch_contact" in vars(cls))
            raise ParameterError(
                f"law {type(law).__name__} has no batch solver ({have} have); use simulate()"
            )
        _, contact = batch_contact()
        return {
            column("m1"): sensor.mass,
            column("k1"): sensor.stiffness,
            column("c1"): sensor.damping,
            column("m2"): self.grain.mass,
            **contact,
            column("v0"): self.velocity,
        }

    def simulate(self, **overrides):
        """Run :func:`contactlab.simulate_impact` with this set-up."""
        return simulate_impact(
            self.grain, self.sensor, self.law, **{**self.simulation, **overrides}
        )


def _flag(table, key, name):
    """Remove the boolean ``key`` from a table (default false); anything else is refused."""
    value = table.pop(key, False)
    if not isinstance(value, bool):
        raise ParameterError(f"[{name}] {key} must be true or false; got {value!r}")
    return value


def _build(name, function, *args, **table):
    """``function(*args, **table)``; a key it does not take (with the nearest valid one)
    or one it lacks is named."""
    unknown_keywords(f"[{name}]", function, args, table, noun="key", skip=len(args))
    return function(*args, **table)


def second_body(table):
    """A law table's keys of the second body (:data:`OTHER_BODY_KEYS`) as ``other``, the
    :class:`~contactlab.analytic.Material` the laws' ``from_material`` take.

    Parameters
    ----------
    table : dict
        A ``[contact]`` (``from_material = true``) or ``[tangential]`` table.

    Returns
    -------
    dict
        A copy of ``table`` without those keys and, if any was given, with ``other``:
        their Material (a rigid flat's value for a key not given).

    Raises
    ------
    ParameterError
        For a table that is not a dict, a key ``other`` (a table gives the second body by
        the three keys) or a bad value, each named.
    """
    table = dict(_table("table", table))
    if "other" in table:
        raise ParameterError(
            f"a table gives the second body as {', '.join(OTHER_BODY_KEYS)}; not other"
        )
    given = {key: table.pop(key) for key in OTHER_BODY_KEYS if key in table}
    if given:
        try:
            table["other"] = Material(*map(given.get, OTHER_BODY_KEYS, RIGID_FLAT))
        except ParameterError as exc:
            raise ParameterError(f"the second body ({', '.join(given)}): {exc}") from None
    return table


def _law(table, grain):
    table = dict(table)
    if "law" not in table:
        raise ParameterError(f"[contact] needs law = one of {', '.join(LAWS)}")
    name = check_choice("[contact] law", table.pop("law"), tuple(LAWS))
    if _flag(table, "from_material", "contact"):
        from_material = getattr(LAWS[name], "from_material", None)
        if from_material is None:
            have = ", ".join(key for key, cls in LAWS.items() if hasattr(cls, "from_material"))
            raise ParameterError(f"from_material is for Hertz-family laws ({have}), not {name!r}")
        parameters = list(inspect.signature(from_material).parameters)[1:]
        if "mass" in parameters:
            table.setdefault("mass", grain.mass)
        names = [key for key in parameters if key != "other"] + list(OTHER_BODY_KEYS)
        table = second_body(table)
        unknown_keywords("[contact]", from_material, (grain.material(),), table, "key", 1, names)
        return from_material(grain.material(), **table)
    return _build("contact", LAWS[name], **table)


def _sensor(table):
    table = dict(table)
    if _flag(table, "rigid", "sensor"):
        if table:
            raise ParameterError(f"[sensor] rigid = true takes no other keys; got {sorted(table)}")
        return Sensor.rigid()
    if "resonance" not in table:
        return _build("sensor", Sensor, **table)
    if "thickness" in table:
        return _build("sensor", Sensor.from_disc, **table)
    return _build("sensor", Sensor.from_resonance, **table)


def _table(name, table):
    """A TOML table given as an argument: a dict, or a ParameterError naming it."""
    if not isinstance(table, Mapping):
        raise ParameterError(f"{name} must be a dict (a TOML table); got {table!r}")
    return table


def law_from_table(table, grain):
    """A contact law from a ``[contact]`` table (``law = ...`` and its parameters, or
    ``from_material = true`` for the Hertz family, built from ``grain``'s material)."""
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    return _law(_table("table", table), grain)


def sensor_from_table(table):
    """A sensor from a ``[sensor]`` table (``rigid``, ``resonance`` or ``m1, k1, c1``)."""
    return _sensor(_table("table", table))


def _parse(data, where):
    unknown = sorted(set(data) - set(_TABLES))
    if unknown:
        named = ", ".join(with_suggestion(t, _TABLES) for t in unknown)
        raise ParameterError(f"{where}: unknown table(s) {named}; valid are {list(_TABLES)}")
    missing = [t for t in ("grain", "contact", "sensor") if t not in data]
    if missing:
        raise ParameterError(f"{where}: missing table(s) {missing}")
    for name, table in data.items():
        if not isinstance(table, dict):
            raise ParameterError(f"{where}: {name} must be a table [{name}]; got {table!r}")
    simulation = dict(data.get("simulation", {}))
    bad = sorted(set(simulation) - set(_SIMULATION_KEYS))
    if bad:
        named = ", ".join(with_suggestion(k, _SIMULATION_KEYS) for k in bad)
        raise ParameterError(
            f"{where}: unknown key(s) {named} in [simulation]; valid are {list(_SIMULATION_KEYS)}"
        )
    if "velocity" not in simulation:
        raise ParameterError(f"{where}: [simulation] needs velocity [m/s]")
    try:
        grain = _build("grain", Grain, **data["grain"])
        return ImpactConfig(
            grain, _sensor(data["sensor"]), _law(data["contact"], grain), simulation
        )
    except ParameterError as exc:
        raise ParameterError(f"{where}: {exc}") from None


def read_document(path, what, kind="TOML"):
    """The contents of a TOML or JSON parameter file, or a ParameterError naming the file.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    what : str
        What the file is, for the messages (``"config"``, ``"species"``, ``"fit"``).
    kind : {"TOML", "JSON"}
        Its syntax.

    Returns
    -------
    dict
    """
    parsers = {
        "TOML": (tomllib.loads, tomllib.TOMLDecodeError),
        "JSON": (json.loads, json.JSONDecodeError),
    }
    loads, error = parsers[check_choice("kind", kind, tuple(parsers))]
    path = Path(check_path("path", path))
    try:
        return loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ParameterError(f"{what} file not found: {path}") from None
    except OSError as exc:  # a folder, no permission
        raise ParameterError(f"cannot read {what} file {path}: {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise ParameterError(f"{path}, byte {exc.start}: not UTF-8 text, so not {kind}") from None
    except error as exc:
        raise ParameterError(f"{path}: not valid {kind}: {exc}") from None


def load_config(path):
    """Read an impact set-up from a TOML file (see the module docstring for the tables)."""
    return _parse(read_document(path, "config"), str(Path(path)))


def list_presets():
    """Names of the presets in ``contactlab/data/presets`` (the paper's Figures 5-9)."""
    return sorted(p.stem for p in PRESET_DIR.glob("*.toml"))


def load_preset(name):
    """Load a named preset, e.g. ``load_preset("fig6")``."""
    check_choice("preset", name, tuple(list_presets()))
    return load_config(PRESET_DIR / f"{name}.toml")


def load(config=None, preset=None):
    """An impact set-up from a TOML file or a named preset: exactly one of the two.

    The command lines' ``CONFIG.toml | --preset NAME`` choice in one place.

    Parameters
    ----------
    config : str or os.PathLike, optional
        TOML file (see the module docstring).
    preset : str, optional
        Preset name (:func:`list_presets`).

    Returns
    -------
    ImpactConfig
    """
    if (config is None) == (preset is None):
        raise ParameterError("give a CONFIG.toml file or --preset NAME (not both)")
    return load_preset(preset) if preset is not None else load_config(config)
