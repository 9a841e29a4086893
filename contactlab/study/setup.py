"""What one grid point of a study simulates: the set-up, its parameters and the scatter.

A :class:`StudySetup` is the base impact (grain, sensor, contact law, impact speed) plus
how the contact stiffness scatters between repetitions (:class:`Scatter`) and how the law
follows the grain's size. A grid point changes any of its parameters by name:

* ``grain.diameter`` [m], ``grain.density`` [kg/m^3], ``grain.youngs_modulus`` [Pa],
  ``grain.poisson_ratio`` [-];
* ``sensor.resonance`` [Hz], ``sensor.mass`` [kg], ``sensor.damping_ratio`` [-] (a new
  resonance keeps the moving mass and the damping ratio; the element stiffness follows);
* ``law.<parameter>`` for every parameter of the law (``law.stiffness``,
  ``law.damping``, ...);
* ``velocity`` [m/s].
"""

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.special import ndtr, ndtri

from contactlab.bodies import Grain, Sensor
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError
from contactlab.laws import LAWS, ContactLaw, LinearViscoelastic, PlasticTrapezoid
from contactlab.laws.base import stated
from contactlab.validation import check_choice, check_count, check_number

__all__ = [
    "DISTRIBUTIONS",
    "SIZE_DEPENDENCE",
    "STIFFNESS_PARAMETERS",
    "Scatter",
    "StudySetup",
]

DISTRIBUTIONS = ("uniform", "normal")
"""Distributions of the stiffness factor (see :class:`Scatter`)."""

SIZE_DEPENDENCE = ("fixed", "material")
"""How the contact law follows the grain diameter (see :class:`StudySetup`)."""

STIFFNESS_PARAMETERS = {
    name: cls.stiffness_parameters for name, cls in LAWS.items() if cls.stiffness_parameters
}
"""Law parameters that make up "the contact stiffness" the scatter multiplies, as each law
states them (``stiffness_parameters``; all by the same factor, so that e.g. Walton-Braun
keeps its restitution). The prescribed plastic pulse has none: name what to scatter with
``StudySetup(vary=...)``."""

_RESULT_NAMES = ("contact_time",)
"""Law parameters named like a result column; their columns get a ``law_`` prefix."""


def _law_column(param, unit, suffix=""):
    prefix = "law_" if param in _RESULT_NAMES else ""
    return f"{prefix}{param}{suffix} [{unit}]"


_GRAIN_COLUMNS = {
    "grain.diameter": "diameter [m]",
    "grain.density": "density [kg/m^3]",
    "grain.youngs_modulus": "youngs_modulus [Pa]",
    "grain.poisson_ratio": "poisson_ratio [-]",
}
_SENSOR_COLUMNS = {
    "sensor.resonance": "resonance [Hz]",
    "sensor.mass": "sensor_mass [kg]",
    "sensor.damping_ratio": "sensor_damping_ratio [-]",
}
_OTHER_COLUMNS = {"velocity": "velocity [m/s]"}

_TRUNCATION = 3.0
"""The normal stiffness factor is truncated at this many standard deviations."""


@dataclass(frozen=True)
class Scatter:
    """Random scatter of the contact stiffness between the repetitions of a grid point.

    Each repetition multiplies the law's stiffness parameter(s) by a factor ``f`` with
    mean 1 (the paper: 10 repetitions, ``f`` uniform in [0.5, 1.5]).

    Parameters
    ----------
    repetitions : int, default 10
        Impacts per grid point, >= 1.
    spread : float, default 0.5
        ``"uniform"``: half-width of ``f`` (``f`` in ``[1 - spread, 1 + spread]``), in
        [0, 1). ``"normal"``: standard deviation of the normal ``f`` is drawn from, in
        [0, 1/3); it is truncated at 3 standard deviations so that ``f`` stays positive,
        which makes the standard deviation of ``f`` itself 1.3 % smaller.
    distribution : {"uniform", "normal"}
        Distribution of ``f``.

    Notes
    -----
    Draws come from one :class:`numpy.random.SeedSequence` per grid point (see
    :meth:`factors`), so a point's draws do not depend on the grid around it, on the
    number of workers or on the order in which points are run. The truncated normal is
    sampled by inverting its distribution function, one uniform draw per factor.
    """

    repetitions: int = 10
    spread: float = 0.5
    distribution: str = "uniform"

    def __post_init__(self):
        check_count("repetitions", self.repetitions)
        check_choice("distribution", self.distribution, DISTRIBUTIONS)
        high = 1.0 if self.distribution == "uniform" else 1.0 / _TRUNCATION
        check_number(
            "spread",
            self.spread,
            low=0.0,
            high=high,
            low_open=False,
            high_open=True,
            unit=f"- (relative; {self.distribution})",
        )

    def factors(self, seed_sequence):
        """Stiffness factors [-] of one grid point, shape ``(repetitions,)``.

        Parameters
        ----------
        seed_sequence : numpy.random.SeedSequence
            The grid point's own seed sequence.
        """
        if not isinstance(seed_sequence, np.random.SeedSequence):
            raise ParameterError(
                f"seed_sequence must be a numpy.random.SeedSequence; got {seed_sequence!r}"
            )
        u = np.random.default_rng(seed_sequence).random(self.repetitions)
        if self.distribution == "uniform":
            return 1.0 + self.spread * (2.0 * u - 1.0)
        lo = ndtr(-_TRUNCATION)
        return 1.0 + self.spread * ndtri(lo + u * (1.0 - 2.0 * lo))


def _names(name, value):
    """A parameter name or a sequence of names, as a tuple of str."""
    names = (value,) if isinstance(value, str) else value
    try:
        names = tuple(names)
    except TypeError:
        names = None
    if names is None or not all(isinstance(n, str) for n in names):
        raise ParameterError(
            f"{name} must be a law parameter name or a tuple of them; got {value!r}"
        )
    return names


def law_units(law):
    """Units of a law's parameters, name -> unit string (the law's own ``units``)."""
    return dict(law.units)


@dataclass(frozen=True)
class StudySetup:
    """The base impact of a study and how its repetitions scatter.

    Parameters
    ----------
    grain : Grain
        Base grain.
    sensor : Sensor
        Base sensor (not rigid: studies sweep its resonance).
    law : ContactLaw or PlasticTrapezoid
        Base contact law (its stiffness is the mean of the scatter).
    velocity : float, default 2.0
        Impact speed [m/s].
    scatter : Scatter, default Scatter()
        Repetitions and stiffness scatter (the paper's: 10, uniform, +-50 %).
    size_dependence : {"fixed", "material"}
        ``"fixed"``: the law is used as given at every grain size (the paper's program
        took the contact stiffness as an input independent of the diameter).
        ``"material"``: at every grid point the law is rebuilt from the grain's material
        data (``youngs_modulus``, ``poisson_ratio``, radius): ``hertz`` through
        :meth:`Hertz.from_material`; ``hertz_damped`` likewise, keeping the base law's
        damping factor ``eta / sqrt(m kH)`` (so its restitution); ``linear`` with the
        equivalent stiffness ``m (pi / t_H)**2`` of the elastic Hertz contact (the spring
        with the same rigid-wall contact time ``t_H`` at this impact speed; it grows in
        proportion to the diameter) and the base law's damping ratio. The base law's own
        stiffness is then not used.
    vary : str or tuple of str, optional
        Law parameters the scatter multiplies; default (None) the law's stiffness
        (:data:`STIFFNESS_PARAMETERS`), which follows the law when it is replaced.
    samples_per_period : float, default 100
        Output grid: samples per the shorter of the sensor period and the rigid-wall
        contact time of the shortest draw, >= 20. The sensor lobe and both peaks are
        refined on the dense solution, so the grid only has to find them; with 100 samples
        a peak read off the grid itself would be within ``(pi/100)**2 / 2 = 0.05 %``.
    """

    grain: Grain
    sensor: Sensor
    law: object
    velocity: float = 2.0
    scatter: Scatter = field(default_factory=Scatter)
    size_dependence: str = "fixed"
    vary: tuple = None
    samples_per_period: float = 100.0

    def __post_init__(self):
        if not isinstance(self.grain, Grain):
            raise ParameterError(f"grain must be a contactlab.Grain; got {self.grain!r}")
        if not isinstance(self.sensor, Sensor) or self.sensor.is_rigid:
            raise ParameterError(
                f"sensor must be a moving contactlab.Sensor (studies sweep its resonance); "
                f"got {self.sensor!r}"
            )
        if not isinstance(self.law, (ContactLaw, PlasticTrapezoid)):
            raise ParameterError(f"law must be a law from contactlab.laws; got {self.law!r}")
        if not isinstance(self.scatter, Scatter):
            raise ParameterError(f"scatter must be a Scatter; got {self.scatter!r}")
        object.__setattr__(
            self, "velocity", check_number("velocity", self.velocity, low=0.0, unit="m/s")
        )
        check_choice("size_dependence", self.size_dependence, SIZE_DEPENDENCE)
        if self.size_dependence == "material":
            if stated(self.law, "_resized") is None:
                resizable = ", ".join(name for name, cls in LAWS.items() if "_resized" in vars(cls))
                raise ParameterError(
                    f"law {self.law.name!r} cannot follow the grain size "
                    f"(size_dependence='material'); the laws that can: {resizable}"
                )
            self.grain.material()  # raises when the grain has no material data
        object.__setattr__(
            self,
            "samples_per_period",
            check_number("samples_per_period", self.samples_per_period, low=20.0, low_open=False),
        )
        if self.vary is not None:
            object.__setattr__(self, "vary", _names("vary", self.vary))
        if not self.varied and self.scatter.spread > 0.0:
            what = "no contact stiffness" if self.vary is None else "vary=() names nothing"
            raise ParameterError(
                f"law {self.law.name!r}: {what} to scatter with spread "
                f"{self.scatter.spread:g}; name the parameter(s) with vary=(...), one of "
                f"{tuple(self.law.parameters())}, or set Scatter(spread=0)"
            )
        for name in self.varied:
            check_choice("vary", name, tuple(self.law.parameters()))

    @property
    def varied(self):
        """Law parameters the scatter multiplies: ``vary``, or the law's stiffness."""
        if self.vary is None:
            return self.law.stiffness_parameters
        return tuple(self.vary)

    @classmethod
    def paper(cls, **changes):
        """The set-up of the paper's error study (Keska et al. 2021, Section 2.2).

        Grain 5.0 mm, 765 kg/m^3, G = 9 MPa, nu = 0.2; linear contact k2 = 1e5 N/m
        (hard, dry grain) with the paper's damping c2 = 1 N*s/m; steel disc sensor
        10 mm x 2 mm (1.233 g) at 40 kHz with damping ratio 0.02 (the paper leaves it
        open); impact speed 2 m/s; 10 repetitions, stiffness uniform within +-50 %.
        Keyword arguments replace fields (``StudySetup.paper(velocity=3.0)``).
        """
        base = cls(
            grain=Grain(diameter=5.0e-3, density=765.0, shear_modulus=9.0e6, poisson_ratio=0.2),
            sensor=Sensor.from_disc(10.0e-3, 2.0e-3, 40.0e3, damping_ratio=0.02),
            law=LinearViscoelastic(stiffness=1.0e5, damping=1.0),
        )
        return replace(base, **changes)

    # -- parameter names -------------------------------------------------------
    def parameter_names(self):
        """Names a grid may change (see the module docstring)."""
        laws = tuple(f"law.{p}" for p in self.law.parameters())
        return (*_GRAIN_COLUMNS, *_SENSOR_COLUMNS, *laws, *_OTHER_COLUMNS)

    def check_parameter(self, name):
        """Return ``name`` if a grid may change it, else raise with a near-match hint."""
        check_choice("grid parameter", name, self.parameter_names())
        if self.size_dependence == "material" and name.startswith("law."):
            raise ParameterError(
                f"{name} cannot be swept with size_dependence='material': the law is built "
                "from the grain's material data at every point"
            )
        return name

    def column(self, name):
        """Unit-bearing column name of a grid parameter, e.g. ``"resonance [Hz]"``."""
        check_choice("name (a grid parameter)", name, self.parameter_names())
        if name.startswith("law."):
            param = name[4:]
            suffix = "_mean" if param in self.varied else ""
            return _law_column(param, law_units(self.law)[param], suffix)
        return {**_GRAIN_COLUMNS, **_SENSOR_COLUMNS, **_OTHER_COLUMNS}[name]

    def varied_columns(self):
        """Column names of the scattered law parameters in the per-impact frame."""
        units = law_units(self.law)
        return [_law_column(p, units[p]) for p in self.varied]

    # -- building one grid point -----------------------------------------------
    def config(self, overrides):
        """The set-up at a grid point: grain, sensor, mean law and impact speed.

        Parameters
        ----------
        overrides : dict
            Grid parameter name -> value (names checked by :meth:`check_parameter`).

        Returns
        -------
        ImpactConfig
            ``law`` is the law before scatter; ``simulation`` holds the velocity [m/s].
        """
        grain_kw = {
            "diameter": self.grain.diameter,
            "density": self.grain.density,
            "youngs_modulus": self.grain.youngs_modulus,
            "poisson_ratio": self.grain.poisson_ratio,
        }
        sensor_kw = {
            "resonance": self.sensor.resonance,
            "mass": self.sensor.mass,
            "damping_ratio": self.sensor.damping_ratio,
        }
        if not isinstance(overrides, Mapping):
            raise ParameterError(
                f"overrides must be a dict of grid parameter name -> value; got {overrides!r}"
            )
        for name in overrides:
            self.check_parameter(name)
        law_kw = self.law.parameters()
        velocity = self.velocity
        for name, value in overrides.items():
            group, _, param = name.partition(".")
            if group == "grain":
                grain_kw[param] = value
            elif group == "sensor":
                sensor_kw[param] = value
            elif group == "law":
                law_kw[param] = value
            else:
                velocity = check_number("velocity", value, low=0.0, unit="m/s")
        grain = Grain(**grain_kw)
        sensor = Sensor.from_resonance(**sensor_kw)
        if self.size_dependence == "material":
            law = self.law._resized(self.grain.mass, grain, velocity)
        else:
            law = type(self.law)(**law_kw)
        return ImpactConfig(grain, sensor, law, {"velocity": velocity})

    def scattered(self, law, factor):
        """The law with its :attr:`vary` parameters multiplied by ``factor`` [-].

        Parameters
        ----------
        law : ContactLaw or PlasticTrapezoid
            A law of the set-up's kind (:meth:`config` gives it at a grid point).
        factor : float
            Scatter factor [-], > 0.
        """
        if type(law) is not type(self.law):
            raise ParameterError(
                f"law must be a {type(self.law).__name__}, the set-up's law; got {law!r}"
            )
        factor = check_number("factor", factor, low=0.0, unit="-")
        if not self.varied:
            return law
        params = law.parameters()
        params.update({p: params[p] * factor for p in self.varied})
        return type(law)(**params)
