"""A grain stream case: particle kinds, flow, feed, plate, sensor and run settings.

A case is plain data (frozen dataclasses) read from a TOML file by :func:`read_case` or
built in Python; :data:`DEFAULT_CASE` is a small built-in stream (wheat and chaff on a
40 kHz sensor, a few hundredths of a second) that runs in seconds. Every number is SI
(angles in degrees, named ``*_deg``).

TOML layout (every table but ``[[particles]]`` optional; keys as the dataclasses below)::

    [stream]      duration, seed, gravity, time_step, steps_per_contact, sample_rate,
                  noise, slot
    [sensor]      resonance, mass, damping_ratio   (contactlab's [sensor] table)
    [plate]       length, width, thickness, inclination_deg
    [flow]        kind ("count" [1/s] or "mass" [kg/s]), rate, profile ("steady",
                  "ramp", "oscillating"), end_rate, amplitude, frequency
    [feed]        speed, speed_sd, incidence_deg, incidence_sd_deg, spot, release
    [effects]     a laboratory's record effects on the written trace (keys of
                  dem_check.campaign.Effects: pink, drift, hum, mains, harmonics,
                  crosstalk, plate_modes, full_scale, bits, steps, step_size)
    [[particles]] name, species or diameter/density/youngs_modulus/poisson_ratio,
                  share, diameter_classes, density_classes, spheres, spacing, tilt_deg
                  (spheres > 1: a straw, a rigid clump of spheres in a row),
                  [particles.contact] (contactlab's [contact] table),
                  [particles.tangential] law = "mindlin" or "spring" (optional)
"""

import math
from dataclasses import dataclass, field, fields, replace

import numpy as np
import pandas as pd

from contactlab.advisor.species import value_range
from contactlab.bodies import Grain, Sensor
from contactlab.config import law_from_table, read_document, second_body, sensor_from_table
from contactlab.entry_checks import check_instance
from contactlab.errors import ParameterError
from contactlab.laws import Mindlin, TangentialSpring
from contactlab.validation import (
    check_choice,
    check_count,
    check_number,
    check_poisson_ratio,
    check_samples,
    check_text,
)
from dem_check.campaign.records import Effects, add_effects

__all__ = [
    "ARRIVALS",
    "DEFAULT_CASE",
    "FLOW_KINDS",
    "PROFILES",
    "STRAW",
    "Feed",
    "Flow",
    "ParticleKind",
    "Plate",
    "StreamCase",
    "read_case",
]

FLOW_KINDS = ("count", "mass")
"""Flow rate as particles per second or kilograms per second."""

ARRIVALS = ("poisson", "regular")
"""Arrival times: a Poisson process of the flow's rate (a real feed), or regular (the
``k + 1/2``-th particle arrives when the cumulative flow reaches ``k + 1/2``: a
deterministic stream for tests and calibration)."""

PROFILES = ("steady", "ramp", "oscillating")
"""Flow in time: constant, linear from ``rate`` to ``end_rate``, or ``rate (1 + amplitude
sin(2 pi frequency t))`` (the three flows of ASABE S587's yield-monitor tests)."""


def _class_values(low, high, count):
    """Midpoints of ``count`` equal-probability bins of a uniform [low, high]."""
    return [low + (high - low) * (k + 0.5) / count for k in range(count)]


@dataclass(frozen=True)
class ParticleKind:
    """One kind of particle in the stream (grain, chaff or straw), binned into classes.

    Diameters [m] and densities [kg/m^3] are uniform over their ranges; the stream uses
    ``diameter_classes * density_classes`` classes (the midpoints of equal-probability
    bins), each a LAMMPS atom type with its own exactly mapped contact law, because
    LAMMPS' mapping depends on the contact's ``m*`` and ``R*``
    (:func:`contactlab.laws.lammps.granular_model`).

    ``spheres > 1`` makes each particle a **straw**: a rigid clump (LAMMPS ``fix
    rigid/small``) of that many spheres of the kind's diameter in a straight row, centres
    ``spacing`` diameters apart (1: touching, < 1: overlapping), each of the kind's
    density, so the clump's mass is ``spheres`` times a sphere's. Its axis lies at a
    uniform azimuth, tilted from the plate's plane by a uniform angle in
    ``[0, tilt_deg]``. LAMMPS gives a wall contact of a clump's sphere the clump's mass
    as ``m*`` (``fix wall/gran``: "if part of a rigid body, use the body mass"), so each
    sphere-plate contact is the kind's law mapped for ``m* =`` the clump's mass and
    ``R* =`` the sphere's radius; the law's grain (``from_material``, a restitution)
    is a sphere of the sphere's diameter with the clump's mass.
    """

    name: str
    diameter: tuple
    density: tuple
    contact: dict
    youngs_modulus: float | None = None
    poisson_ratio: float | None = None
    share: float = 1.0
    tangential: dict | None = None
    diameter_classes: int = 1
    density_classes: int = 1
    spheres: int = 1
    spacing: float = 1.0
    tilt_deg: float = 0.0

    def __post_init__(self):
        check_text("particles name", self.name)
        where = f"particles {self.name!r}"
        object.__setattr__(self, "diameter", value_range(f"{where}: diameter", self.diameter, "m"))
        object.__setattr__(
            self, "density", value_range(f"{where}: density", self.density, "kg/m^3")
        )
        check_number(f"{where}: share", self.share, low=0.0)
        check_count(f"{where}: diameter_classes", self.diameter_classes, low=1)
        check_count(f"{where}: density_classes", self.density_classes, low=1)
        check_count(f"{where}: spheres", self.spheres, low=1)
        check_number(f"{where}: spacing", self.spacing, low=0.0, high=1.0, high_open=False)
        check_number(
            f"{where}: tilt_deg", self.tilt_deg, low=0.0, high=90.0, low_open=False, high_open=False
        )
        if not isinstance(self.contact, dict):
            raise ParameterError(f"{where}: contact must be a table; got {self.contact!r}")
        if self.youngs_modulus is not None:
            check_number(f"{where}: youngs_modulus", self.youngs_modulus, low=0.0, unit="Pa")
        if self.poisson_ratio is not None:
            check_poisson_ratio(f"{where}: poisson_ratio", self.poisson_ratio)
        if self.tangential is not None and not isinstance(self.tangential, dict):
            raise ParameterError(f"{where}: tangential must be a table; got {self.tangential!r}")

    def classes(self):
        """``[(grain, law, tangential_law), ...]``: one per class (``tangential_law`` None
        means no tangential force)."""
        out = []
        for d in _class_values(*self.diameter, self.diameter_classes):
            for rho in _class_values(*self.density, self.density_classes):
                heft = {"density": rho}
                if self.spheres > 1:  # the clump's mass on one sphere (class docstring)
                    heft = {"mass": self.spheres * rho * math.pi / 6.0 * d**3}
                grain = Grain(
                    diameter=d,
                    youngs_modulus=self.youngs_modulus,
                    poisson_ratio=self.poisson_ratio,
                    **heft,
                )
                try:
                    law = law_from_table(self.contact, grain)
                    tangential = self._tangential(grain)
                except ParameterError as exc:
                    raise ParameterError(f"particles {self.name!r}: {exc}") from None
                out.append((grain, law, tangential))
        return out

    def offsets(self, diameter):
        """Sphere centres of a clump along its axis, from its centre of mass [m], for
        spheres of ``diameter`` [m]."""
        step = self.spacing * check_number("diameter", diameter, low=0.0, unit="m")
        return [(k - 0.5 * (self.spheres - 1)) * step for k in range(self.spheres)]

    def _tangential(self, grain):
        if self.tangential is None:
            return None
        table = dict(self.tangential)
        name = check_choice("[tangential] law", table.pop("law", None), ("mindlin", "spring"))
        if name == "spring":
            return TangentialSpring(**table)
        return Mindlin.from_material(grain.material(), **second_body(table))


@dataclass(frozen=True)
class Flow:
    """Feed rate in time (count [1/s] or mass [kg/s], see :data:`PROFILES` and
    :data:`ARRIVALS`)."""

    rate: float
    kind: str = "count"
    profile: str = "steady"
    end_rate: float | None = None
    amplitude: float = 0.0
    frequency: float = 0.0
    arrivals: str = "poisson"

    def __post_init__(self):
        check_choice("flow kind", self.kind, FLOW_KINDS)
        check_choice("flow arrivals", self.arrivals, ARRIVALS)
        check_choice("flow profile", self.profile, PROFILES)
        check_number("flow rate", self.rate, low=0.0, low_open=False)
        if self.profile == "ramp" and self.end_rate is None:
            raise ParameterError("flow profile 'ramp' needs end_rate")
        if self.end_rate is not None:
            check_number("flow end_rate", self.end_rate, low=0.0, low_open=False)
        check_number("flow amplitude", self.amplitude, low=0.0, high=1.0, low_open=False)
        check_number("flow frequency", self.frequency, low=0.0, low_open=False, unit="Hz")

    def at(self, t, duration):
        """Rate at times ``t`` [s] (numpy array) in a run of ``duration`` [s]."""
        t = check_samples("t", t, min_size=1, unit="s")
        duration = check_number("duration", duration, low=0.0, unit="s")
        if self.profile == "ramp":
            return self.rate + (self.end_rate - self.rate) * t / duration
        if self.profile == "oscillating":
            return self.rate * (1.0 + self.amplitude * np.sin(2.0 * math.pi * self.frequency * t))
        return np.full_like(t, self.rate)

    def peak(self):
        """Largest rate of the profile."""
        if self.profile == "ramp":
            return max(self.rate, self.end_rate)
        if self.profile == "oscillating":
            return self.rate * (1.0 + self.amplitude)
        return self.rate


@dataclass(frozen=True)
class Feed:
    """Speeds and directions at the plate, and where the particles aim.

    ``speed`` [m/s] and ``incidence_deg`` (from the plate's normal) are normal
    distributions (``*_sd``) truncated at zero and 89 deg; the azimuth is uniform. Aim
    points are uniform on a disc of radius ``spot`` [m] at the plate's centre; each
    particle enters the box at least ``release`` [m] of straight travel before its aim.
    """

    speed: float = 3.0
    speed_sd: float = 0.0
    incidence_deg: float = 0.0
    incidence_sd_deg: float = 0.0
    spot: float = 5e-3
    release: float = 10e-3

    def __post_init__(self):
        check_number("feed speed", self.speed, low=0.0, unit="m/s")
        check_number("feed speed_sd", self.speed_sd, low=0.0, low_open=False, unit="m/s")
        check_number("feed incidence_deg", self.incidence_deg, low=0.0, high=89.0, low_open=False)
        check_number("feed incidence_sd_deg", self.incidence_sd_deg, low=0.0, low_open=False)
        check_number("feed spot", self.spot, low=0.0, low_open=False, unit="m")
        check_number("feed release", self.release, low=0.0, unit="m")


@dataclass(frozen=True)
class Plate:
    """A flat rectangular sensor plate (``length`` along x, ``width`` along y,
    ``thickness``, all [m]); ``inclination_deg`` tilts gravity, not the plate: the
    simulation runs in the plate's frame (z its normal), which is exact for a flat plate."""

    length: float = 0.03
    width: float = 0.03
    thickness: float = 2e-3
    inclination_deg: float = 0.0

    def __post_init__(self):
        for name in ("length", "width", "thickness"):
            check_number(f"plate {name}", getattr(self, name), low=0.0, unit="m")
        check_number(
            "plate inclination_deg",
            self.inclination_deg,
            low=0.0,
            high=90.0,
            low_open=False,
            high_open=False,
        )


@dataclass(frozen=True)
class StreamCase:
    """Everything a stream simulation needs (see the module docstring).

    ``time_step`` [s] defaults to the shortest class's wall contact time over
    ``steps_per_contact``; ``sample_rate`` [Hz] is the oscilloscope's; ``noise`` [N]
    is the white noise added to the written trace and ``effects`` a laboratory's record
    effects on it (:class:`dem_check.campaign.Effects`: 1/f noise, drift, hum, plate
    crosstalk, ADC, offset steps; not its ``bounce``: the stream's bounces are
    simulated); ``slot`` [s] is how often new
    particles are inserted (each is placed on its own straight path, so the slot
    changes no trajectory, only the number of LAMMPS runs).
    """

    particles: tuple
    sensor: Sensor = field(
        default_factory=lambda: Sensor.from_resonance(40e3, mass=1.2e-3, damping_ratio=0.02)
    )
    flow: Flow = field(default_factory=lambda: Flow(rate=200.0))
    feed: Feed = field(default_factory=Feed)
    plate: Plate = field(default_factory=Plate)
    duration: float = 0.02
    seed: int = 0
    gravity: float = 9.81
    time_step: float | None = None
    steps_per_contact: int = 50
    sample_rate: float = 1e6
    noise: float = 0.0
    slot: float = 5e-4
    effects: Effects | None = None

    def __post_init__(self):
        if isinstance(self.particles, ParticleKind) or not isinstance(self.particles, tuple | list):
            raise ParameterError(
                f"particles must be a tuple of ParticleKind; got {self.particles!r}"
            )
        if not self.particles:
            raise ParameterError("a stream case needs at least one [[particles]] kind")
        object.__setattr__(self, "particles", tuple(self.particles))
        for kind in self.particles:
            check_instance("particles", kind, ParticleKind)
        check_instance("sensor", self.sensor, Sensor)
        check_instance("flow", self.flow, Flow)
        check_instance("feed", self.feed, Feed)
        check_instance("plate", self.plate, Plate)
        if self.sensor.is_rigid:
            raise ParameterError("sensor must be a moving sensor (m1, k1, c1), not rigid")
        check_number("duration", self.duration, low=0.0, unit="s")
        check_count("seed", self.seed, low=0)
        check_number("gravity", self.gravity, low=0.0, low_open=False, unit="m/s**2")
        if self.time_step is not None:
            check_number("time_step", self.time_step, low=0.0, unit="s")
        check_count("steps_per_contact", self.steps_per_contact, low=10)
        check_number("sample_rate", self.sample_rate, low=0.0, unit="Hz")
        check_number("noise", self.noise, low=0.0, low_open=False, unit="N")
        check_number("slot", self.slot, low=0.0, unit="s")
        if sum(kind.share for kind in self.particles) <= 0.0:
            raise ParameterError("particles: the shares sum to zero")
        if self.effects is not None:
            _check_effects(self.effects)

    def with_(self, **changes):
        """A copy with some fields changed (``flow``, ``duration``, ``seed`` ...)."""
        return replace(self, **changes)


def _check_effects(effects):
    """Refuse bad effects before a long run rather than when the trace is written."""
    if not isinstance(effects, Effects):
        raise ParameterError(f"effects must be a dem_check.campaign.Effects; got {effects!r}")
    if effects.bounce != 0.0:
        raise ParameterError(
            f"effects.bounce = {effects.bounce!r}: a stream simulates its bounces "
            "(re-contacts are in the truth); leave bounce at 0"
        )
    # add_effects checks every field: one second of sixteen samples and no impact
    nothing = pd.DataFrame({"onset [s]": [], "peak_sensor_force [N]": []})
    t = np.linspace(0.0, 1.0, 16)
    add_effects(t, np.zeros(16), effects, nothing, 0.0, np.random.default_rng(0))


def _particles(table, where):
    from contactlab.advisor import load_species

    table = dict(table)
    name = table.pop("name", None) or table.get("species") or "particles"
    if "species" in table:
        species = load_species(table.pop("species"))
        table.setdefault("diameter", species.diameter)
        table.setdefault("density", species.density)
        table.setdefault("youngs_modulus", sum(species.youngs_modulus) / 2.0)
        table.setdefault("poisson_ratio", species.poisson_ratio)
    allowed = {f.name for f in fields(ParticleKind)}
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise ParameterError(f"{where}: unknown key(s) {unknown}; valid are {sorted(allowed)}")
    for key in ("diameter", "density", "contact"):
        if key not in table:
            raise ParameterError(f"{where}: particles {name!r} needs {key} (or species)")
    return ParticleKind(name=str(name), **table)


def _table(cls, data, key, where):
    table = dict(data.get(key, {}))
    allowed = {f.name for f in fields(cls)}
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise ParameterError(
            f"{where}: unknown key(s) {unknown} in [{key}]; valid {sorted(allowed)}"
        )
    return cls(**table)


def _effects(table, where):
    """An :class:`Effects` from an ``[effects]`` table (TOML arrays become tuples)."""
    table = {
        key: tuple(tuple(v) if isinstance(v, list) else v for v in value)
        if isinstance(value, list)
        else value
        for key, value in dict(table).items()
    }
    return _table(Effects, {"effects": table}, "effects", where)


def read_case(path):
    """A :class:`StreamCase` from a TOML file (module docstring), errors naming the file."""
    data = read_document(path, "stream case")
    where = str(path)
    known = {"stream", "sensor", "plate", "flow", "feed", "particles", "effects"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ParameterError(f"{where}: unknown table(s) {unknown}; valid are {sorted(known)}")
    try:
        particles = [_particles(t, where) for t in data.get("particles", [])]
        stream = dict(data.get("stream", {}))
        allowed = {f.name for f in fields(StreamCase)} - {
            "particles",
            "sensor",
            "flow",
            "feed",
            "plate",
            "effects",
        }
        bad = sorted(set(stream) - allowed)
        if bad:
            raise ParameterError(f"unknown key(s) {bad} in [stream]; valid are {sorted(allowed)}")
        if "flow" not in data:
            raise ParameterError("missing table [flow] (rate, kind, profile)")
        extra = {"sensor": sensor_from_table(data["sensor"])} if "sensor" in data else {}
        if "effects" in data:
            extra["effects"] = _effects(data["effects"], where)
        return StreamCase(
            particles=tuple(particles),
            flow=_table(Flow, data, "flow", where),
            feed=_table(Feed, data, "feed", where),
            plate=_table(Plate, data, "plate", where),
            **extra,
            **stream,
        )
    except (ParameterError, TypeError) as exc:
        raise ParameterError(f"{where}: {exc}") from None


def _default_case():
    wheat = ParticleKind(
        name="wheat",
        diameter=(3.07e-3, 4.26e-3),
        density=(1190.0, 1390.0),
        youngs_modulus=0.25e9,
        poisson_ratio=0.3,
        contact={"law": "hertz_damped", "from_material": True, "restitution": 0.5},
        diameter_classes=2,
    )
    chaff = ParticleKind(
        name="chaff",
        diameter=(3e-3, 5e-3),
        density=(200.0, 300.0),
        contact={"law": "linear", "stiffness": 2e3, "damping": 0.05},
        diameter_classes=2,
    )
    return StreamCase(
        particles=(wheat, chaff, STRAW),
        flow=Flow(rate=400.0),
        feed=Feed(spot=12e-3),
        plate=Plate(length=0.04, width=0.04),
        duration=0.025,
        noise=0.01,
    )


STRAW = ParticleKind(
    name="straw",
    diameter=3e-3,
    density=250.0,
    contact={"law": "linear", "stiffness": 5e3, "damping": 0.05},
    share=0.5,
    spheres=6,
    tilt_deg=20.0,
)
"""Short straw pieces: rigid rows of six 3 mm spheres (18 mm long, 0.021 g), density
250 kg/m^3 (a hollow stem's bulk), a soft lossy linear contact per sphere, tilted up to
20 deg from the plate; half as many as grains."""

DEFAULT_CASE = _default_case()
"""A small stream: wheat (Hertz-Mindlin normal law, restitution 0.5), as many chaff
particles (soft, lossy linear law) and half as many straw pieces (:data:`STRAW`),
400 particles/s for 25 ms aimed at a 12 mm disc of a 40 mm plate, on a 40 kHz sensor;
the trace has 0.01 N of white noise."""
