"""Write a fitted contact law as input for DEM codes: LIGGGHTS, MercuryDPM, YADE, EDEM.

Each writer turns a fit (a :class:`~contactlab.inverse.fit.ContactFit` or its FIT.json
dict) into a commented snippet in the code's own parameter names and SI units, with the
time step the code's guidance picks. Two law families are exported:

* linear spring-dashpot (``linear``): stiffness ``k`` [N/m] and damping ``c`` [N*s/m]
  go in directly where the code takes them (LIGGGHTS ``hooke/stiffness`` with absolute
  damping, MercuryDPM ``LinearViscoelasticSpecies``, YADE ``ViscElMat``); EDEM's Linear
  Spring takes the restitution, converted with the codes' overlap-convention formula.
* damped Hertz (``hertz_damped``, ``hertz``): the effective modulus ``E*`` of the
  grain-plate contact and the restitution ``e`` of the Tsuji mapping, which LIGGGHTS
  (``model hertz``), YADE (``Ip2_FrictMat_FrictMat_MindlinPhys(en=...)``), EDEM
  (Hertz-Mindlin no slip) and MercuryDPM (``setElasticModulusAndRestitutionCoefficient``)
  all implement as ``kH d**1.5 + sqrt(5) beta sqrt(m* kH) d**0.25 d'``. The grain's
  Young's modulus follows from ``1/E* = (1-nu**2)/E + (1-nu_p**2)/E_p`` with the plate's
  (steel by default).

Friction, rolling resistance and tangential stiffness are not fitted by a normal impact:
where a code requires them the snippet writes a placeholder marked ``NOT FITTED``.
"""

import math
from dataclasses import dataclass

from contactlab import analytic
from contactlab.bodies import STEEL_DENSITY
from contactlab.config import read_document
from contactlab.errors import ParameterError
from contactlab.inverse.fit import FIT_MODELS, ContactFit
from contactlab.laws import get_law
from contactlab.validation import check_choice, check_number

__all__ = ["DEM_CODES", "export_dem", "read_fit"]

LINEAR_STEPS_PER_CONTACT = 50
"""Linear laws: time step = contact time / 50 (MercuryDPM's guidance,
``getCollisionTime(mass) / 50``; velocity Verlet then errs ~1e-3 in restitution)."""

LIGGGHTS_RAYLEIGH_FRACTION = 0.1
"""LIGGGHTS Hertz: 10 % of the Rayleigh time (``fix check/timestep/gran`` example)."""

EDEM_RAYLEIGH_FRACTION = 0.2
"""EDEM: 20 % of the Rayleigh time step (its auto time step; 10-40 % is its range)."""

YADE_PWAVE_FRACTION = 0.5
"""YADE Hertz: ``O.dt = 0.5 * PWaveTimeStep()``, ``PWaveTimeStep = R sqrt(rho / E)``."""

YADE_VISCEL_FRACTION = 0.05
"""YADE ViscElMat: ``O.dt = 0.05 * tc``, as YADE's viscoelastic example scripts set it."""

STEEL_YOUNGS_MODULUS = 210e9
"""Default sensor plate: steel, E [Pa] ..."""

STEEL_POISSON_RATIO = 0.3
"""... and Poisson ratio [-]."""

EXPORTED_LAWS = ("linear", "hertz", "hertz_damped")
"""Fitted laws the DEM codes take as they are."""

PLACEHOLDER_FRICTION = 0.5
"""Friction coefficient written where a code requires one; marked NOT FITTED."""


@dataclass(frozen=True)
class _Contact:
    """What every writer needs, derived once from a fit (SI units)."""

    family: str  # "linear" or "hertz"
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
                    f"{k} = {_g(v['value'])}{_unit(v['unit'])}{_ci(v)}"
                    for k, v in self.fitted.items()
                ]
                + [
                    f"{k} = {_g(v)}{_unit(_fixed_unit(self.law, k))} (fixed)"
                    for k, v in self.fixed.items()
                ]
            ),
            f"grain: radius {_g(self.radius)} m, density {_g(self.density)} kg/m^3, mass "
            f"{_g(self.mass)} kg; impact velocity {_g(self.velocity)} m/s",
            f"time step {_g(step)} s: {guidance}; the fitted contact lasts "
            f"{_g(self.contact_time)} s = {self.contact_time / step:.0f} steps",
            "SI units throughout. NOT FITTED marks values a normal impact cannot determine.",
        ]
        return [f"{comment} {line}" for line in lines]

    def friction_note(self):
        return "fitted" if self.friction_fitted else "NOT FITTED (placeholder)"


def _g(value):
    """A number as the codes read it (shortest round-trip form up to 7 digits)."""
    return f"{value:.7g}"


def _fixed_unit(law, name):
    """Unit of a law parameter held fixed in the fit."""
    spec = FIT_MODELS[law]
    return dict(zip(spec.parameters, spec.units, strict=True))[name]


def _unit(unit):
    return "" if unit == "-" else f" {unit}"


def _ci(entry):
    low, high = entry.get("ci95", (None, None))
    if low is None or high is None:
        return " (95 % CI unbounded)"
    return f" (95 % CI {_g(low)}-{_g(high)})"


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


def _value(data, key, where):
    try:
        return data[key]
    except (KeyError, TypeError):
        raise ParameterError(f"{where}: missing {key!r} (not a contactlab fit)") from None


def _law_value(common, name, where):
    """A law parameter of the fit, fitted or held fixed."""
    if name in common["fitted"]:
        return float(common["fitted"][name]["value"])
    if name in common["fixed"]:
        return float(common["fixed"][name])
    raise ParameterError(f"{where}: {name!r} is neither fitted nor fixed (not a contactlab fit)")


def _contact(fit, source, poisson_ratio, plate_youngs_modulus, plate_poisson_ratio, friction):
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
    law_name = _value(data, "law", where)
    if law_name not in EXPORTED_LAWS:
        raise ParameterError(
            f"export of law {law_name!r} is not supported; fit one of {list(EXPORTED_LAWS)} "
            "for the DEM codes"
        )
    grain = _value(data, "grain", where)
    mass = float(_value(grain, "mass [kg]", where))
    radius = 0.5 * float(_value(grain, "diameter [m]", where))
    velocity = float(_value(data, "velocity [m/s]", where))
    law = get_law(law_name, **_value(data, "law_parameters", where))
    common = {
        "law": law_name,
        "fitted": {
            k: v
            for k, v in _value(data, "parameters", where).items()
            if k not in ("velocity", "onset")
        },
        "fixed": dict(data.get("fixed", {})),
        "source": source,
        "mass": mass,
        "radius": radius,
        "density": float(_value(grain, "density [kg/m^3]", where)),
        "velocity": velocity,
        "contact_time": law.contact_time(mass, velocity),
    }
    if friction is not None:
        common["friction"] = check_number("friction", friction, low=0.0, low_open=False)
        common["friction_fitted"] = True
    if law_name == "linear":
        k, c = law.stiffness, law.damping
        e = analytic.linear_restitution(k, c, mass, convention="overlap")
        return _Contact("linear", stiffness=k, damping=c, restitution=e, **common)
    modulus = _law_value(common, "effective_modulus", where)
    e = _law_value(common, "restitution", where) if law_name == "hertz_damped" else 1.0
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
    return _Contact(
        "hertz",
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
def _linear_step(contact):
    step = contact.contact_time / LINEAR_STEPS_PER_CONTACT
    return step, f"contact time / {LINEAR_STEPS_PER_CONTACT} (MercuryDPM's guidance)"


def _pair(value):
    """A peratomtypepair matrix for 2 atom types (grain, plate) with one value."""
    return " ".join([_g(value)] * 4)


def _liggghts(c):
    if c.family == "linear":
        step, why = _linear_step(c)
        body = [
            "# atom type 1 = grain, atom type 2 = sensor plate (wall mesh); units si",
            "# hooke/stiffness with absolute damping: F = kn d + gamman_abs d' (limitForce:",
            "# never tensile, as the fitted one-sided law)",
            "pair_style gran model hooke/stiffness tangential history absolute_damping on "
            "limitForce on",
            "pair_coeff * *",
            f"fix m1 all property/global kn peratomtypepair 2 {_pair(c.stiffness)}",
            f"fix m2 all property/global gamman_abs peratomtypepair 2 {_pair(c.damping)}",
            "# NOT FITTED (placeholders): tangential stiffness kt = 2/7 kn, no tangential damping",
            f"fix m3 all property/global kt peratomtypepair 2 {_pair(2.0 / 7.0 * c.stiffness)}",
            f"fix m4 all property/global gammat_abs peratomtypepair 2 {_pair(0.0)}",
        ]
    else:
        step = LIGGGHTS_RAYLEIGH_FRACTION * c.rayleigh_time
        why = (
            f"{LIGGGHTS_RAYLEIGH_FRACTION:g} x Rayleigh time {_g(c.rayleigh_time)} s "
            "(fix check/timestep/gran)"
        )
        body = [
            "# atom type 1 = grain, atom type 2 = sensor plate (wall mesh); units si",
            "# Hertz with Tsuji damping from the restitution (limitForce: never tensile)",
            "pair_style gran model hertz tangential history limitForce on",
            "pair_coeff * *",
            "fix m1 all property/global youngsModulus peratomtype "
            f"{_g(c.youngs_modulus)} {_g(c.plate_youngs_modulus)}",
            "fix m2 all property/global poissonsRatio peratomtype "
            f"{_g(c.poisson_ratio)} {_g(c.plate_poisson_ratio)}",
            "# restitution measured for grain-plate; used for grain-grain too",
            f"fix m3 all property/global coefficientRestitution peratomtypepair 2 "
            f"{_pair(c.restitution)}",
            "# warns when the step exceeds the guidance (needs youngsModulus: Hertz only)",
            f"fix ts_check all check/timestep/gran 1000 {LIGGGHTS_RAYLEIGH_FRACTION:g} "
            f"{LIGGGHTS_RAYLEIGH_FRACTION:g}",
        ]
    body += [
        f"# coefficientFriction: {c.friction_note()}",
        f"fix m5 all property/global coefficientFriction peratomtypepair 2 {_pair(c.friction)}",
        f"timestep {_g(step)}",
    ]
    return [*c.header("LIGGGHTS", "#", why, step), *body]


def _mercurydpm(c):
    if c.family == "linear":
        step, why = _linear_step(c)
        body = [
            "// normal force k d + c d' (LinearViscoelasticSpecies)",
            "auto species = speciesHandler.copyAndAddObject(LinearViscoelasticSpecies());",
            f"species->setDensity({_g(c.density)}); // [kg/m^3]",
            f"species->setStiffness({_g(c.stiffness)}); // [N/m]",
            f"species->setDissipation({_g(c.damping)}); // [N*s/m]",
        ]
    else:
        step = c.contact_time / LINEAR_STEPS_PER_CONTACT
        why = (
            f"Hertz contact time at the impact velocity / {LINEAR_STEPS_PER_CONTACT} "
            "(MercuryDPM's getCollisionTime / 50 habit)"
        )
        body = [
            "// normal force 4/3 E* sqrt(R d) d + alpha sqrt(m* kn) d' with alpha from e",
            "// (HertzianViscoelasticNormalSpecies); the species' modulus is the contact's E*:",
            "// this value is for grain-plate contacts (grain-grain: E/(2(1-nu^2)))",
            "auto species = speciesHandler.copyAndAddObject(HertzianViscoelasticMindlinSpecies());",
            f"species->setDensity({_g(c.density)}); // [kg/m^3]",
            "species->setElasticModulusAndRestitutionCoefficient("
            f"{_g(c.effective_modulus)}, {_g(c.restitution)}); // E* [Pa], e [-]",
        ]
    body += [
        f"// sliding friction: {c.friction_note()} (set it on a friction species)",
        f"setTimeStep({_g(step)}); // [s]",
    ]
    return [*c.header("MercuryDPM", "//", why, step), *body]


def _yade(c):
    friction = f"atan({_g(c.friction)})"
    if c.family == "linear":
        step = YADE_VISCEL_FRACTION * c.contact_time
        why = f"{YADE_VISCEL_FRACTION:g} x contact time (YADE's ViscElMat examples)"
        body = [
            "# Law2_ScGeom_ViscElPhys_Basic: the contact's kn is 1/(1/kn1 + 1/kn2) of the",
            "# two materials (likewise cn), so one material on grain and plate carries 2 k, 2 c",
            f"# frictionAngle: {c.friction_note()}; ks, cs NOT FITTED (ks = 2/7 kn, cs = 0)",
            "viscel = O.materials.append(",
            f"    ViscElMat(kn={_g(2.0 * c.stiffness)}, cn={_g(2.0 * c.damping)}, "
            f"ks={_g(2.0 * 2.0 / 7.0 * c.stiffness)}, cs=0.0,",
            f"              density={_g(c.density)}, frictionAngle={friction}, "
            'label="grain_and_plate")',
            ")",
            "O.engines = [",
            "    ForceResetter(),",
            "    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),",
            "    InteractionLoop(",
            "        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],",
            "        [Ip2_ViscElMat_ViscElMat_ViscElPhys()],",
            "        [Law2_ScGeom_ViscElPhys_Basic()],",
            "    ),",
            "    NewtonIntegrator(gravity=(0, 0, -9.81)),",
            "]",
        ]
    else:
        pwave = c.radius * math.sqrt(c.density / c.youngs_modulus)
        step = YADE_PWAVE_FRACTION * pwave
        why = f"{YADE_PWAVE_FRACTION:g} x PWaveTimeStep() = {YADE_PWAVE_FRACTION:g} x {_g(pwave)} s"
        body = [
            "# Hertz-Mindlin with Tsuji damping from en (Ip2_FrictMat_FrictMat_MindlinPhys)",
            f"# frictionAngle: {c.friction_note()}",
            "grain = O.materials.append(",
            f"    FrictMat(young={_g(c.youngs_modulus)}, poisson={_g(c.poisson_ratio)}, "
            f"density={_g(c.density)},",
            f'             frictionAngle={friction}, label="grain")',
            ")",
            "plate = O.materials.append(",
            f"    FrictMat(young={_g(c.plate_youngs_modulus)}, "
            f"poisson={_g(c.plate_poisson_ratio)}, density={_g(STEEL_DENSITY)},",
            f'             frictionAngle={friction}, label="sensor_plate")',
            ")",
            "O.engines = [",
            "    ForceResetter(),",
            "    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),",
            "    InteractionLoop(",
            "        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],",
            f"        [Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(algo='val', "
            f"val={_g(c.restitution)}))],",
            "        [Law2_ScGeom_MindlinPhys_Mindlin()],",
            "    ),",
            "    NewtonIntegrator(gravity=(0, 0, -9.81)),",
            "]",
        ]
    return [
        *c.header("YADE", "#", why, step),
        "from math import atan",
        "",
        *body,
        f"O.dt = {_g(step)}",
    ]


def _edem(c):
    if c.family == "linear":
        step, why = _linear_step(c)
        body = [
            "[Physics]",
            "Particle to Geometry normal model = Linear Spring",
            "[Interaction: grain - sensor plate]",
            f"Normal stiffness [N/m] = {_g(c.stiffness)}",
            f"Coefficient of Restitution = {_g(c.restitution)}",
            f"# dashpot c = {_g(c.damping)} N*s/m = 2 sqrt(m k) (-ln e)/sqrt(pi^2 + ln^2 e)",
        ]
    else:
        step = EDEM_RAYLEIGH_FRACTION * c.rayleigh_time
        why = (
            f"{EDEM_RAYLEIGH_FRACTION:.0%} of the Rayleigh time step {_g(c.rayleigh_time)} s "
            "(EDEM's auto time step)"
        )
        body = [
            "[Physics]",
            "Particle to Geometry contact model = Hertz-Mindlin (no slip)",
            "[Bulk Material: grain]",
            f"Poisson's Ratio = {_g(c.poisson_ratio)}",
            f"Solids Density [kg/m3] = {_g(c.density)}",
            f"Shear Modulus [Pa] = {_g(c.shear_modulus)}",
            "[Equipment Material: sensor plate]",
            f"Poisson's Ratio = {_g(c.plate_poisson_ratio)}",
            f"Solids Density [kg/m3] = {_g(STEEL_DENSITY)}",
            f"Shear Modulus [Pa] = {_g(c.plate_shear_modulus)}",
            "[Interaction: grain - sensor plate]",
            f"Coefficient of Restitution = {_g(c.restitution)}",
        ]
    body += [
        f"# Coefficient of Static Friction: {c.friction_note()}",
        f"Coefficient of Static Friction = {_g(c.friction)}",
        "[Simulator]",
        f"Fixed Time Step [s] = {_g(step)}",
    ]
    return [*c.header("EDEM", "#", why, step), *body]


DEM_CODES = {"liggghts": _liggghts, "mercurydpm": _mercurydpm, "yade": _yade, "edem": _edem}
"""Export targets: code name -> writer."""


def export_dem(
    fit,
    code,
    *,
    source="contactlab fit",
    poisson_ratio=None,
    plate_youngs_modulus=STEEL_YOUNGS_MODULUS,
    plate_poisson_ratio=STEEL_POISSON_RATIO,
    friction=None,
):
    """Input snippet for a DEM code from a fitted contact law.

    Parameters
    ----------
    fit : ContactFit or dict
        A fit, or the dict of a FIT.json (:func:`read_fit`). Law parameters held fixed
        in the fit (its ``fixed``) are exported like fitted ones.
    code : {"liggghts", "mercurydpm", "yade", "edem"}
        Target code.
    source : str, default "contactlab fit"
        Named in the snippet's header (e.g. the FIT.json path).
    poisson_ratio : float, optional
        Grain Poisson ratio [-] (Hertz laws); default the fit's grain value.
    plate_youngs_modulus : float, default 210e9
        Sensor plate's Young's modulus [Pa] (steel).
    plate_poisson_ratio : float, default 0.3
        Sensor plate's Poisson ratio [-] (steel).
    friction : float, optional
        Friction coefficient [-]; without it a placeholder marked NOT FITTED is written.

    Returns
    -------
    str
        The snippet, comments in the code's syntax, ending in a newline.

    Notes
    -----
    Time steps follow each code's guidance (module constants): a fiftieth of the contact
    time for linear laws and for MercuryDPM's Hertz (MercuryDPM's habit), 10 % of the
    Rayleigh time for LIGGGHTS' Hertz,
    20 % for EDEM, ``0.5 PWaveTimeStep()`` for YADE's Hertz and ``0.05 tc`` for its
    ViscElMat. The contact time is that of the fitted law on a rigid plate at the fitted
    velocity. The Rayleigh time is ``pi R sqrt(rho/G) / (0.1631 nu + 0.8766)``.

    References
    ----------
    Tsuji Y., Tanaka T., Ishida T. (1992) Powder Technol. 71, 239-250.
    DOI 10.1016/0032-5910(92)88030-L (damping from restitution).
    Antypov D., Elliott J.A. (2011) EPL 94, 50004. DOI 10.1209/0295-5075/94/50004
    """
    code = check_choice("code", code, tuple(DEM_CODES))
    contact = _contact(
        fit, source, poisson_ratio, plate_youngs_modulus, plate_poisson_ratio, friction
    )
    return "\n".join(DEM_CODES[code](contact)) + "\n"
