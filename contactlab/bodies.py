"""The two bodies of an impact: the grain and the force sensor.

The sensor is the paper's reduced model (Figure 3b): a moving mass ``m1`` on the
measuring element, a spring ``k1`` with a damper ``c1``. Its signal is the force carried
by the element, ``S1 = k1 x1 + c1 v1`` [N].
"""

import math

from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.plausibility import check_plausible, internal
from contactlab.validation import KeywordChecked, check_number, check_samples

__all__ = ["DRAWING_DIAMETER", "STEEL_DENSITY", "Grain", "Sensor"]

STEEL_DENSITY = 7850.0
"""Density of steel [kg/m**3], the default for sensor discs."""


DRAWING_DIAMETER = 1e-3
"""Diameter [m] drawn for a grain known only by its mass (:meth:`Grain.from_mass`)."""


def _optional(name, value, **limits):
    return None if value is None else check_number(name, value, **limits)


def _plausible(key, value, name):
    return None if value is None else check_plausible(key, value, name)


class Grain(KeywordChecked):
    """A spherical grain.

    Give the diameter and either the density or the mass; material data are optional and
    let Hertz-family laws be built from the grain.

    Parameters
    ----------
    diameter : float
        Diameter [m].
    density : float, optional
        Density [kg/m**3]; the mass follows as ``density * pi d**3 / 6``.
    mass : float, optional
        Mass [kg] (instead of the density).
    youngs_modulus : float, optional
        Young's modulus [Pa].
    shear_modulus : float, optional
        Shear (Kirchhoff) modulus [Pa]; with the Poisson ratio it gives
        ``E = 2 G (1 + nu)``. Give at most one of the two moduli.
    poisson_ratio : float, optional
        Poisson ratio [-] in (-1, 0.5].

    Warns
    -----
    PlausibilityWarning
        A diameter, density, mass or modulus outside what real grains, seeds and
        calibration balls span (:data:`contactlab.plausibility.RANGES`); the message names
        the likely unit slip.

    Examples
    --------
    The paper's grain (Keska et al. 2021, Section 2.2):

    >>> g = Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
    >>> round(g.mass * 1e5, 3)
    5.007
    """

    def __init__(
        self,
        diameter,
        density=None,
        mass=None,
        youngs_modulus=None,
        shear_modulus=None,
        poisson_ratio=None,
    ):
        self.diameter = check_number("diameter", diameter, low=0.0, unit="m")
        check_plausible("grain_diameter", self.diameter, "diameter")
        if (density is None) == (mass is None):
            raise ParameterError(
                f"Grain needs exactly one of density [kg/m**3] or mass [kg]; "
                f"got density={density!r}, mass={mass!r}"
            )
        volume = math.pi / 6.0 * self.diameter * self.diameter * self.diameter
        if not 0.0 < volume < math.inf:  # d**3 under- or overflows a float
            raise ParameterError(
                f"diameter = {self.diameter!r} m gives a volume of {volume!r} m**3, which a "
                "float cannot hold; give the diameter in metres"
            )
        if density is not None:
            self.density = check_number("density", density, low=0.0, unit="kg/m**3")
            check_plausible("grain_density", self.density, "density")
            self.mass = self.density * volume
        else:
            self.mass = check_number("mass", mass, low=0.0, unit="kg")
            check_plausible("grain_mass", self.mass, "mass")
            self.density = self.mass / volume
        if not (0.0 < self.mass < math.inf and 0.0 < self.density < math.inf):
            raise ParameterError(
                f"diameter = {self.diameter!r} m with mass {self.mass!r} kg and density "
                f"{self.density!r} kg/m**3: a float cannot hold them; check the units"
            )
        if density is None:
            check_plausible(
                "grain_density", self.density, f"density (mass / volume of a {diameter:g} m sphere)"
            )
        self.poisson_ratio = _optional(
            "poisson_ratio", poisson_ratio, low=-1.0, high=0.5, high_open=False
        )
        if youngs_modulus is not None and shear_modulus is not None:
            raise ParameterError("give youngs_modulus or shear_modulus, not both")
        if shear_modulus is not None:
            if self.poisson_ratio is None:
                raise ParameterError("shear_modulus needs poisson_ratio to give Young's modulus")
            g = check_number("shear_modulus", shear_modulus, low=0.0, unit="Pa")
            check_plausible("shear_modulus", g, "shear_modulus")
            self.youngs_modulus = analytic.youngs_from_shear(g, self.poisson_ratio)
        else:
            self.youngs_modulus = _optional("youngs_modulus", youngs_modulus, low=0.0, unit="Pa")
            _plausible("youngs_modulus", self.youngs_modulus, "youngs_modulus")

    @classmethod
    def from_mass(cls, mass, diameter=None):
        """A grain known only by its mass [kg].

        The diameter [m] only sizes drawings. Without one, :data:`DRAWING_DIAMETER` is
        drawn and the density it implies is neither checked nor meaningful.
        """
        mass = check_plausible("grain_mass", check_number("mass", mass, low=0.0, unit="kg"), "mass")
        if diameter is not None:
            return cls(diameter=diameter, mass=mass)
        grain = cls.__new__(cls)
        grain.diameter, grain.mass = DRAWING_DIAMETER, mass
        grain.density = mass / (math.pi * DRAWING_DIAMETER**3 / 6.0)
        grain.youngs_modulus = grain.poisson_ratio = None
        return grain

    @property
    def radius(self):
        """Radius [m]."""
        return 0.5 * self.diameter

    @property
    def shear_modulus(self):
        """Shear modulus ``E / (2 (1 + nu))`` [Pa], or None without material data."""
        if self.youngs_modulus is None or self.poisson_ratio is None:
            return None
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    def material(self):
        """The grain's :class:`~contactlab.analytic.Material` (Young's modulus [Pa],
        Poisson ratio [-], radius [m]) for the laws' ``from_material``.

        Raises
        ------
        ParameterError
            If the grain was built without Young's (or shear) modulus and Poisson ratio.
        """
        if self.youngs_modulus is None or self.poisson_ratio is None:
            raise ParameterError(
                "this grain has no material data: give youngs_modulus (or shear_modulus) "
                "and poisson_ratio to build a Hertz-family law from it"
            )
        return analytic.Material(self.youngs_modulus, self.poisson_ratio, self.radius)

    def to_dict(self):
        """Grain data with unit-bearing keys."""
        return {
            "diameter [m]": self.diameter,
            "density [kg/m^3]": self.density,
            "mass [kg]": self.mass,
            "youngs_modulus [Pa]": self.youngs_modulus,
            "poisson_ratio [-]": self.poisson_ratio,
        }

    def __repr__(self):
        extra = ""
        if self.youngs_modulus is not None:
            extra = (
                f", youngs_modulus={self.youngs_modulus:.4g}, poisson_ratio={self.poisson_ratio}"
            )
        return f"Grain(diameter={self.diameter:.4g}, mass={self.mass:.4g}{extra})"


class Sensor(KeywordChecked):
    """A force sensor: moving mass ``m1`` on a measuring element ``k1, c1``.

    Parameters
    ----------
    mass : float
        Moving (parasitic) mass ``m1`` [kg].
    stiffness : float
        Stiffness of the measuring element ``k1`` [N/m].
    damping : float, default 0
        Damping of the measuring element ``c1`` [N*s/m].

    Notes
    -----
    The signal is ``S1 = k1 x1 + c1 v1`` [N]; the transfer function from contact force
    to signal is ``(c1 s + k1) / (m1 s**2 + c1 s + k1)``. The paper leaves the damping
    open; quartz sensors have damping ratios of about 0.01-0.05. (The paper's software
    screen shows "Damp. const. 500 N*s/m", a damping ratio of 0.8 with the paper's disc.)

    A moving mass, resonance or damping ratio outside what real force sensors span
    (:data:`contactlab.plausibility.RANGES`) gives a :class:`PlausibilityWarning` naming
    the likely unit slip.
    """

    def __init__(self, mass, stiffness, damping=0.0):
        self.mass = check_number("mass", mass, low=0.0, unit="kg", allow_inf=True)
        self.stiffness = check_number("stiffness", stiffness, low=0.0, unit="N/m", allow_inf=True)
        self.damping = check_number(
            "damping", damping, low=0.0, low_open=False, unit="N*s/m", allow_inf=True
        )
        if math.isinf(self.mass) != math.isinf(self.stiffness):
            raise ParameterError(
                "an immovable sensor needs mass = stiffness = inf (use Sensor.rigid()); "
                f"got mass={self.mass}, stiffness={self.stiffness}"
            )
        if math.isinf(self.damping) and not self.is_rigid:
            raise ParameterError("damping must be finite for a moving sensor")
        if not self.is_rigid and not (
            0.0 < self.stiffness * self.mass < math.inf
            and 0.0 < self.stiffness / self.mass < math.inf
        ):
            raise ParameterError(
                f"mass = {self.mass!r} kg and stiffness = {self.stiffness!r} N/m: their "
                "product or ratio (resonance, damping ratio) is beyond what a float holds; "
                "check the units"
            )
        if not self.is_rigid:
            check_plausible("sensor_mass", self.mass, "mass")
            check_plausible("sensor_resonance", self.resonance, "resonance sqrt(k1/m1)/(2 pi)")
            check_plausible("sensor_damping_ratio", self.damping_ratio, "damping ratio")

    @classmethod
    def rigid(cls):
        """An immovable wall: the signal equals the contact force (S1 == S2)."""
        return cls(mass=math.inf, stiffness=math.inf, damping=0.0)

    @classmethod
    def from_resonance(cls, resonance, mass, damping_ratio=None, damping=None):
        """Sensor with a given undamped resonance frequency.

        Parameters
        ----------
        resonance : float
            Undamped natural frequency ``f1 = sqrt(k1/m1) / (2 pi)`` [Hz].
        mass : float
            Moving mass ``m1`` [kg].
        damping_ratio : float, optional
            ``zeta1 = c1 / (2 sqrt(k1 m1))`` [-] (default 0 when ``damping`` is not given).
        damping : float, optional
            ``c1`` [N*s/m] instead of the ratio.
        """
        f1 = check_plausible(
            "sensor_resonance",
            check_number("resonance", resonance, low=0.0, unit="Hz"),
            "resonance",
        )
        m1 = check_plausible(
            "sensor_mass", check_number("mass", mass, low=0.0, unit="kg"), "sensor mass"
        )
        k1 = m1 * (2.0 * math.pi * f1) ** 2
        if damping_ratio is not None and damping is not None:
            raise ParameterError("give damping_ratio or damping, not both")
        if damping is None:
            zeta = check_number(
                "damping_ratio",
                0.0 if damping_ratio is None else damping_ratio,
                low=0.0,
                low_open=False,
            )
            check_plausible("sensor_damping_ratio", zeta, "damping_ratio")
            damping = 2.0 * zeta * math.sqrt(k1 * m1)
        else:
            damping = check_number("damping", damping, low=0.0, low_open=False, unit="N*s/m")
            check_plausible("sensor_damping_ratio", damping / (2.0 * math.sqrt(k1 * m1)), "damping")
        with internal():  # checked above, by the names the caller gave
            return cls(mass=m1, stiffness=k1, damping=damping)

    @classmethod
    def from_disc(cls, diameter, thickness, resonance, damping_ratio=0.0, density=STEEL_DENSITY):
        """Sensor whose moving mass is a disc, as the paper's software sized it.

        Parameters
        ----------
        diameter : float
            Disc diameter [m] (paper: 10 mm).
        thickness : float
            Disc thickness [m] (paper: 2 mm).
        resonance : float
            Resonance frequency [Hz].
        damping_ratio : float, default 0
            Damping ratio [-].
        density : float, default 7850
            Disc density [kg/m**3] (steel: a 10 mm x 2 mm disc weighs 1.233 g).
        """
        dia = check_plausible(
            "disc_diameter", check_number("diameter", diameter, low=0.0, unit="m"), "diameter"
        )
        thick = check_plausible(
            "disc_thickness", check_number("thickness", thickness, low=0.0, unit="m"), "thickness"
        )
        rho = check_plausible(
            "grain_density", check_number("density", density, low=0.0, unit="kg/m**3"), "density"
        )
        f1 = check_plausible(
            "sensor_resonance",
            check_number("resonance", resonance, low=0.0, unit="Hz"),
            "resonance",
        )
        with internal():  # the disc's mass follows from the values checked above
            sensor = cls.from_resonance(
                f1, mass=rho * math.pi * dia**2 / 4.0 * thick, damping_ratio=damping_ratio
            )
        check_plausible("sensor_damping_ratio", sensor.damping_ratio, "damping_ratio")
        sensor.diameter, sensor.thickness = dia, thick
        return sensor

    diameter = None
    """Plate diameter [m] when known (disc sensors), used by the engine bench."""
    thickness = None
    """Plate thickness [m] when known."""

    @property
    def is_rigid(self):
        """Whether this is an immovable wall."""
        return math.isinf(self.mass)

    def signal(self, states, contact_force):
        """Sensor signal S1 [N] of states ``[x1, v1, ...]`` (n, >= 2) [m, m/s]:
        ``k1 x1 + c1 v1``, or on an immovable wall the contact force S2 [N] itself.

        Parameters
        ----------
        states : array_like
            Solver states, shape (n, >= 2): plate displacement [m] and velocity [m/s]
            first.
        contact_force : array_like or None
            Contact force S2 [N] at the n states; None for a moving sensor, whose signal
            does not depend on it.
        """
        states = check_samples("states", states, ndim=2, copy=False)  # read, on every result
        if states.shape[1] < 2:
            raise ParameterError(
                f"states must have columns x1 [m], v1 [m/s], ...; got shape {states.shape}"
            )
        if contact_force is not None or self.is_rigid:
            contact_force = check_samples("contact_force", contact_force, unit="N", copy=False)
            if contact_force.shape != states.shape[:1]:
                raise ParameterError(
                    f"contact_force must hold one value per state ({states.shape[0]}); got "
                    f"{contact_force.size}"
                )
        if self.is_rigid:
            return contact_force
        signal = states[:, 0] * self.stiffness
        signal += self.damping * states[:, 1]
        return signal

    def energy(self, x1, v1):
        """Kinetic and elastic energy [J] of the plate at displacement ``x1`` [m] and velocity
        ``v1`` [m/s] (0 on an immovable wall)."""
        x1, v1 = check_number("x1", x1, unit="m"), check_number("v1", v1, unit="m/s")
        if self.is_rigid:
            return 0.0
        return 0.5 * self.mass * v1**2 + 0.5 * self.stiffness * x1**2

    @property
    def angular_frequency(self):
        """Undamped natural angular frequency ``w1 = sqrt(k1/m1)`` [rad/s] (inf if rigid)."""
        return math.inf if self.is_rigid else math.sqrt(self.stiffness / self.mass)

    @property
    def resonance(self):
        """Undamped resonance frequency [Hz] (inf if rigid)."""
        return self.angular_frequency / (2.0 * math.pi)

    @property
    def period(self):
        """Undamped natural period [s] (0 if rigid)."""
        return 0.0 if self.is_rigid else 1.0 / self.resonance

    @property
    def damping_ratio(self):
        """``zeta1 = c1 / (2 sqrt(k1 m1))`` [-] (0 if rigid)."""
        if self.is_rigid:
            return 0.0
        return self.damping / (2.0 * math.sqrt(self.stiffness * self.mass))

    def to_dict(self):
        """Sensor data with unit-bearing keys."""
        return {
            "mass [kg]": self.mass,
            "stiffness [N/m]": self.stiffness,
            "damping [N*s/m]": self.damping,
            "resonance [Hz]": self.resonance,
            "damping_ratio [-]": self.damping_ratio,
        }

    def __repr__(self):
        if self.is_rigid:
            return "Sensor.rigid()"
        return (
            f"Sensor(mass={self.mass:.4g}, stiffness={self.stiffness:.4g}, "
            f"damping={self.damping:.4g})  # {self.resonance / 1e3:.4g} kHz, "
            f"zeta={self.damping_ratio:.3g}"
        )
