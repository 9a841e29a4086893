"""What every DEM writer needs, derived once from a fit: the exported contact.

A fit (a :class:`~contactlab.inverse.fit.ContactFit` or its FIT.json dict) becomes an
:class:`ExportContact` in SI units: the law family, its parameters with intervals, the
grain, and the derived quantities the codes take (restitution, Young's modulus behind
``E*`` given the plate, the contact time of the fitted law on a rigid plate).
"""

import math
from dataclasses import dataclass

from contactlab import analytic
from contactlab.config import read_document
from contactlab.errors import ParameterError
from contactlab.inverse.export.rebound import rebound_line
from contactlab.inverse.export.schema import check_fit
from contactlab.inverse.fit_models import FIT_MODELS
from contactlab.inverse.fit_result import ContactFit
from contactlab.laws import LAWS, get_law
from contactlab.solver import wall_impact
from contactlab.validation import (
    check_non_negative,
    check_number,
    check_poisson_ratio,
    check_positive,
)

__all__ = [
    "ExportContact",
    "contact_from_fit",
    "linear_step",
    "number",
    "read_fit",
    "type_pair",
]

LINEAR_STEPS_PER_CONTACT = 50
"""Linear laws: time step = contact time / 50 (MercuryDPM's guidance,
``getCollisionTime(mass) / 50``; velocity Verlet then errs ~1e-3 in restitution)."""

STEEL_YOUNGS_MODULUS = 210e9
"""Default sensor plate: steel, E [Pa] ..."""

STEEL_POISSON_RATIO = 0.3
"""... and Poisson ratio [-]."""

PLACEHOLDER_FRICTION = 0.5
"""Friction coefficient written where a code requires one; marked NOT FITTED."""


@dataclass(frozen=True)
class ExportContact:
    """What every writer needs, derived once from a fit (SI units)."""

    family: str  # the law's dem_export: "linear" or "hertz"
    law: str
    fitted: dict
    fixed: dict
    source: str
    mass: float
    radius: float
    density: float
    velocity: float
    contact_time: float
    stiffness: float = math.nan
    damping: float = math.nan
    restitution: float = math.nan
    effective_modulus: float = math.nan
    youngs_modulus: float = math.nan
    poisson_ratio: float = math.nan
    plate_youngs_modulus: float = math.nan
    plate_poisson_ratio: float = math.nan
    friction: float = PLACEHOLDER_FRICTION
    friction_fitted: bool = False
    contact_law: object = None  # the fitted law itself (a contactlab.laws law)

    def __post_init__(self):
        """Every number a writer may print is finite and physical (SI units)."""
        for name in ("mass", "radius", "density", "velocity", "contact_time"):
            check_positive(f"exported {name}", getattr(self, name))
        check_non_negative("exported friction", self.friction)
        if self.family == "linear":
            check_positive("exported stiffness", self.stiffness, "N/m")
            check_non_negative("exported damping", self.damping, "N*s/m")
        else:
            for name in ("effective_modulus", "youngs_modulus", "plate_youngs_modulus"):
                check_positive(f"exported {name}", getattr(self, name), "Pa")
            for name in ("poisson_ratio", "plate_poisson_ratio"):
                check_poisson_ratio(f"exported {name}", getattr(self, name))
        check_number("exported restitution", self.restitution, low=0.0, high=1.0)

    @property
    def shear_modulus(self):
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def plate_shear_modulus(self):
        return self.plate_youngs_modulus / (2.0 * (1.0 + self.plate_poisson_ratio))

    @property
    def rayleigh_time(self):
        return analytic.rayleigh_time(
            self.radius, self.density, self.shear_modulus, self.poisson_ratio
        )

    def header(self, code, comment, guidance, step):
        lines = [
            f"contactlab export-dem: {code} input for a grain striking the sensor plate",
            f"source: {self.source}",
            f"fitted law: {self.law}; "
            + "; ".join(
                [
                    f"{k} = {number(v['value'])}{_unit(_fixed_unit(self.law, k))}{_ci(v)}"
                    for k, v in self.fitted.items()
                ]
                + [
                    f"{k} = {number(v)}{_unit(_fixed_unit(self.law, k))} (fixed)"
                    for k, v in self.fixed.items()
                ]
            ),
            f"grain: radius {number(self.radius)} m, density {number(self.density)} kg/m^3, mass "
            f"{number(self.mass)} kg; impact velocity {number(self.velocity)} m/s",
            rebound_line(code, self),
            f"time step {number(step)} s: {guidance}; the fitted contact lasts "
            f"{number(self.contact_time)} s = {self.contact_time / step:.0f} steps",
            "SI units throughout. NOT FITTED marks values a normal impact cannot determine.",
        ]
        return [f"{comment} {line}" for line in lines]

    def friction_note(self):
        return "fitted" if self.friction_fitted else "NOT FITTED (placeholder)"


def number(value):
    """A number as the codes read it (shortest round-trip form up to 7 digits).

    Raises :class:`~contactlab.errors.ParameterError` for NaN or infinity, which no code
    reads as a parameter: the last guard behind :func:`check_fit` and
    :meth:`ExportContact.__post_init__`.
    """
    if not math.isfinite(value):
        raise ParameterError(f"a non-finite number ({value!r}) would be written into the deck")
    return f"{value:.7g}"


def _fixed_unit(law, name):
    """Unit of a law parameter, from the code's registry (never from the fit file)."""
    spec = FIT_MODELS[law]
    return dict(zip(spec.parameters, spec.units, strict=True))[name]


def _unit(unit):
    return "" if unit == "-" else f" {unit}"


def _ci(entry):
    low, high = entry.get("ci95", (None, None))
    if low is None or high is None:
        return " (95 % CI unbounded)"
    return f" (95 % CI {number(low)}-{number(high)})"


# ---------------------------------------------------------------------------
# Reading a fit
# ---------------------------------------------------------------------------
def read_fit(path):
    """Load a FIT.json written by :meth:`ContactFit.to_json`.

    Parameters
    ----------
    path : str or pathlib.Path
        The FIT.json file.

    Returns
    -------
    dict
        Its contents, for :func:`export_dem`.
    """
    return read_document(path, "fit", "JSON")


def _law_value(common, name, where):
    """A law parameter of the fit, fitted or held fixed."""
    if name in common["fitted"]:
        return float(common["fitted"][name]["value"])
    if name in common["fixed"]:
        return float(common["fixed"][name])
    raise ParameterError(f"{where}: {name!r} is neither fitted nor fixed (not a contactlab fit)")


def contact_from_fit(
    fit, source, poisson_ratio, plate_youngs_modulus, plate_poisson_ratio, friction
):
    if isinstance(fit, ContactFit):
        data = fit.to_dict()
    elif isinstance(fit, dict):
        data = fit
    else:
        raise ParameterError(
            f"fit must be a ContactFit or the dict of a FIT.json (read_fit(path)); got "
            f"{type(fit).__name__}"
        )
    where = source
    data = check_fit(data, where)
    law_name = data["law"]
    grain = data["grain"]
    mass = float(grain["mass [kg]"])
    radius = 0.5 * float(grain["diameter [m]"])
    velocity = float(data["velocity [m/s]"])
    law = get_law(law_name, **data["law_parameters"])
    common = {
        "law": law_name,
        "fitted": {k: v for k, v in data["parameters"].items() if k not in ("velocity", "onset")},
        "fixed": dict(data.get("fixed", {})),
        "source": source,
        "mass": mass,
        "radius": radius,
        "density": float(grain["density [kg/m^3]"]),
        "velocity": velocity,
        "contact_time": wall_impact(law, mass, velocity).contact_time,
        "contact_law": law,
    }
    if friction is not None:
        common["friction"] = check_number("friction", friction, low=0.0, low_open=False)
        common["friction_fitted"] = True
    family = LAWS[law_name].dem_export
    if family == "linear":
        k, c = law.stiffness, law.damping
        e = analytic.linear_restitution(k, c, mass, convention="overlap")
        return ExportContact("linear", stiffness=k, damping=c, restitution=e, **common)
    modulus = _law_value(common, "effective_modulus", where)
    elastic = "restitution" not in FIT_MODELS[law_name].parameters
    e = 1.0 if elastic else _law_value(common, "restitution", where)
    nu = poisson_ratio if poisson_ratio is not None else grain.get("poisson_ratio [-]")
    if nu is None:
        raise ParameterError(
            "poisson_ratio is needed to turn E* into Young's modulus: the fit's grain has "
            "none; give poisson_ratio (e.g. --poisson-ratio 0.3)"
        )
    nu = check_number("poisson_ratio", nu, low=-1.0, high=0.5)
    e_p = check_number("plate_youngs_modulus", plate_youngs_modulus, low=0.0, unit="Pa")
    nu_p = check_number("plate_poisson_ratio", plate_poisson_ratio, low=-1.0, high=0.5)
    compliance = 1.0 / modulus - (1.0 - nu_p**2) / e_p
    if compliance <= 0.0:
        raise ParameterError(
            f"fitted E* = {modulus:.4g} Pa is stiffer than the plate allows "
            f"(plate_youngs_modulus = {e_p:.4g} Pa): give the plate's real modulus"
        )
    return ExportContact(
        family,
        effective_modulus=modulus,
        restitution=e,
        youngs_modulus=(1.0 - nu**2) / compliance,
        poisson_ratio=nu,
        plate_youngs_modulus=e_p,
        plate_poisson_ratio=nu_p,
        **common,
    )


# ---------------------------------------------------------------------------
# Writers
# ---------------------------------------------------------------------------
def linear_step(contact):
    step = contact.contact_time / LINEAR_STEPS_PER_CONTACT
    return step, f"contact time / {LINEAR_STEPS_PER_CONTACT} (MercuryDPM's guidance)"


def rayleigh_step(contact, fraction, guidance):
    """A time step of ``fraction`` of the contact's Rayleigh time [s] and its guidance
    line (``guidance`` names where the fraction comes from)."""
    step = fraction * contact.rayleigh_time
    return (
        step,
        f"{fraction:.0%} of the Rayleigh time {number(contact.rayleigh_time)} s ({guidance})",
    )


def snippet(contact, code, comment, hertz_step, lines):
    """One code's input: the header, then ``lines(contact, step)``.

    Parameters
    ----------
    contact : ExportContact
        The fitted contact.
    code : str
        The code's name in the header.
    comment : str
        The code's comment mark (``"#"``, ``"//"``).
    hertz_step : callable
        ``hertz_step(contact)`` gives the time step [s] of a Hertz contact and the
        guidance it follows; a linear contact takes :func:`linear_step` in every code.
    lines : callable
        ``lines(contact, step)`` gives the code's lines at time step ``step`` [s].

    Returns
    -------
    list of str
    """
    step, why = (linear_step if contact.family == "linear" else hertz_step)(contact)
    return [*contact.header(code, comment, why, step), *lines(contact, step)]


def type_pair(value):
    """A peratomtypepair matrix for 2 atom types (grain, plate) with one value."""
    return " ".join([number(value)] * 4)
