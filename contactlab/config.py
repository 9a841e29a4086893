"""Impact set-ups from TOML files and named presets.

A file has four tables, every value in SI units::

    [grain]       diameter [m], density [kg/m^3] or mass [kg], optional youngs_modulus
                  or shear_modulus [Pa] and poisson_ratio [-]
    [contact]     law = "<name>" (see contactlab.laws.LAWS) and that law's parameters;
                  Hertz-family laws may instead say from_material = true and take the
                  grain's material data (plus restitution or yield_pressure as needed)
    [sensor]      rigid = true; or mass [kg], stiffness [N/m], damping [N*s/m];
                  or resonance [Hz] with mass [kg] and damping_ratio [-] or damping;
                  or resonance [Hz] with a disc: diameter [m], thickness [m],
                  damping_ratio [-], density [kg/m^3]
    [simulation]  velocity [m/s], duration [s], sample_rate [Hz], method, threshold [N]

Unknown tables and keys are rejected by name.
"""

import tomllib
from dataclasses import dataclass
from pathlib import Path

from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import LAWS, get_law
from contactlab.validation import check_choice

__all__ = ["PRESET_DIR", "ImpactConfig", "list_presets", "load", "load_config", "load_preset"]

PRESET_DIR = Path(__file__).resolve().parent.parent / "data" / "presets"
"""Folder of the named impact presets (the paper's Figures 5-9)."""

_TABLES = ("grain", "contact", "sensor", "simulation")
_SIMULATION_KEYS = ("velocity", "duration", "sample_rate", "method", "threshold")


@dataclass
class ImpactConfig:
    """A complete impact set-up: the arguments of :func:`contactlab.simulate_impact`."""

    grain: Grain
    sensor: Sensor
    law: object
    simulation: dict

    def simulate(self, **overrides):
        """Run :func:`contactlab.simulate_impact` with this set-up."""
        from contactlab.impact import simulate_impact

        return simulate_impact(
            self.grain, self.sensor, self.law, **{**self.simulation, **overrides}
        )


def _law(table, grain, where):
    table = dict(table)
    if "law" not in table:
        raise ParameterError(f"{where}: [contact] needs law = one of {', '.join(LAWS)}")
    name = check_choice(f"{where}: [contact] law", table.pop("law"), tuple(LAWS))
    if table.pop("from_material", False):
        if name not in ("hertz", "hertz_damped", "thornton"):
            raise ParameterError(f"{where}: from_material is for Hertz-family laws, not {name!r}")
        if name == "hertz_damped":
            table.setdefault("mass", grain.mass)
        return LAWS[name].from_material(*grain.material(), **table)
    return get_law(name, **table)


def _sensor(table):
    table = dict(table)
    if table.pop("rigid", False):
        if table:
            raise ParameterError(f"[sensor] rigid = true takes no other keys; got {sorted(table)}")
        return Sensor.rigid()
    if "resonance" not in table:
        return Sensor(**table)
    if "thickness" in table:
        return Sensor.from_disc(**table)
    return Sensor.from_resonance(**table)


def _parse(data, where):
    unknown = sorted(set(data) - set(_TABLES))
    if unknown:
        raise ParameterError(f"{where}: unknown table(s) {unknown}; valid are {list(_TABLES)}")
    missing = [t for t in ("grain", "contact", "sensor") if t not in data]
    if missing:
        raise ParameterError(f"{where}: missing table(s) {missing}")
    simulation = dict(data.get("simulation", {}))
    bad = sorted(set(simulation) - set(_SIMULATION_KEYS))
    if bad:
        raise ParameterError(
            f"{where}: unknown key(s) {bad} in [simulation]; valid are {list(_SIMULATION_KEYS)}"
        )
    if "velocity" not in simulation:
        raise ParameterError(f"{where}: [simulation] needs velocity [m/s]")
    try:
        grain = Grain(**data["grain"])
        return ImpactConfig(
            grain, _sensor(data["sensor"]), _law(data["contact"], grain, where), simulation
        )
    except ParameterError as exc:
        raise ParameterError(f"{where}: {exc}") from None


def load_config(path):
    """Read an impact set-up from a TOML file (see the module docstring for the tables)."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ParameterError(f"config file not found: {path}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML: {exc}") from None
    return _parse(data, str(path))


def list_presets():
    """Names of the presets in ``data/presets`` (the paper's Figures 5-9)."""
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
