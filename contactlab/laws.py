"""Normal contact laws between a grain and a flat (or another grain).

Sign convention (stated once, used everywhere)
----------------------------------------------
The overlap ``d = x2 - x1`` [m] is positive in compression; its rate ``d' = v2 - v1``
[m/s] is positive while the bodies approach. A law returns the contact force ``S2`` [N],
which is **never tensile**: it is ``0`` for ``d <= 0`` and clipped at ``0`` where the
formula would pull (a damper at the end of contact). The contact therefore ends when the
force reaches zero, not when the overlap does (see :mod:`contactlab.analytic` for the
other convention and what it changes).

Each law is a plain vectorised function first (``hertz_force(overlap, k_hertz)``, pvlib
habit); the classes only gather parameters, validate them, and describe the law to the
solvers as a small state machine of *branches* (smooth pieces of the force such as
loading, yielding, unloading) with linear exit conditions. History laws carry one state
variable: the largest overlap reached so far, ``max_overlap`` [m].

The base class derives restitution, contact time and dissipated energy from an impact
on an immovable wall, and the work done along any overlap path.
"""

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.validation import KeywordChecked, check_choice, check_number, check_probability

__all__ = [
    "LAWS",
    "Branch",
    "ContactLaw",
    "Exit",
    "Hertz",
    "HertzDamped",
    "HuntCrossley",
    "KuwabaraKono",
    "LinearPlastic",
    "LinearViscoelastic",
    "PlasticTrapezoid",
    "SmoothLaw",
    "Thornton",
    "WaltonBraun",
    "get_law",
    "hertz_damped_force",
    "hertz_force",
    "hunt_crossley_force",
    "kuwabara_kono_force",
    "linear_plastic_force",
    "linear_viscoelastic_force",
    "plastic_trapezoid_force",
    "thornton_force",
    "walton_braun_force",
]


# ---------------------------------------------------------------------------
# Pure vectorised force functions
# ---------------------------------------------------------------------------
def _one_sided(overlap, raw):
    """Zero out of contact and never tensile."""
    return np.where(np.asarray(overlap) > 0, np.maximum(raw, 0.0), 0.0)


# The ``_*_raw`` formulas and :func:`_spow` use operators only, so they take Python floats
# as well as arrays: the adaptive solver calls them on floats thousands of times per
# impact, where a numpy call per operation would cost more than the arithmetic. Public
# functions convert their array_like inputs first.
def _spow(x, p):
    """Signed power ``sign(x) |x|**p`` for ``p >= 1``: the odd extension keeps a zero
    crossing visible."""
    return x * abs(x) ** (p - 1.0)


def _linear_raw(overlap, rate, stiffness, damping):
    return stiffness * overlap + damping * rate


def linear_viscoelastic_force(overlap, rate, stiffness, damping):
    """Linear spring-dashpot (Kelvin-Voigt) contact force, one-sided.

    Parameters
    ----------
    overlap : array_like
        Overlap ``d`` [m], positive in compression.
    rate : array_like
        Overlap rate ``d'`` [m/s], positive while approaching.
    stiffness : float
        Contact stiffness ``k`` [N/m].
    damping : float
        Damping coefficient ``c`` [N*s/m].

    Returns
    -------
    numpy.ndarray
        ``max(k d + c d', 0)`` for ``d > 0``, else 0 [N].

    Notes
    -----
    The paper's Eq. (6), ``S2 = k2 (x2 - x1) + c2 (v2 - v1)`` in the sign convention of
    this module, made one-sided.

    References
    ----------
    Keska W. et al. (2021) Applied Sciences 11, 11 (Eq. 6).
    Cundall P.A., Strack O.D.L. (1979) Geotechnique 29, 47-65. DOI 10.1680/geot.1979.29.1.47
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return _one_sided(overlap, _linear_raw(overlap, rate, stiffness, damping))


def _hertz_raw(overlap, k_hertz):
    return k_hertz * _spow(overlap, 1.5)


def hertz_force(overlap, k_hertz):
    """Hertz elastic sphere-flat force ``kH d**1.5`` [N] (0 for ``d <= 0``).

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    k_hertz : float
        Hertz stiffness ``kH = 4/3 E* sqrt(R*)`` [N/m**1.5].

    References
    ----------
    Hertz H. (1882) J. reine angew. Math. 92, 156-171.
    Johnson K.L. (1985) Contact Mechanics, Cambridge University Press, ch. 4.
    """
    overlap = np.asarray(overlap, dtype=float)
    return _one_sided(overlap, _hertz_raw(overlap, k_hertz))


def _hertz_damped_raw(overlap, rate, k_hertz, damping):
    root = abs(overlap) ** 0.25  # one power serves both terms: d**1.5 = d |d|**0.5
    return (k_hertz * overlap * root + damping * rate) * root


def hertz_damped_force(overlap, rate, k_hertz, damping):
    """Damped Hertz force of Tsuji et al. / EDEM / LIGGGHTS ``kH d**1.5 + eta d**0.25 d'`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    damping : float
        Damping coefficient ``eta = alpha sqrt(m* kH)`` [N*s/m**1.25].

    References
    ----------
    Tsuji Y., Tanaka T., Ishida T. (1992) Powder Technol. 71, 239-250.
    DOI 10.1016/0032-5910(92)88030-L
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return _one_sided(overlap, _hertz_damped_raw(overlap, rate, k_hertz, damping))


def _kuwabara_kono_raw(overlap, rate, k_hertz, dissipation):
    return k_hertz * (_spow(overlap, 1.5) + 1.5 * dissipation * abs(overlap) ** 0.5 * rate)


def kuwabara_kono_force(overlap, rate, k_hertz, dissipation):
    """Viscoelastic Hertz force ``kH (d**1.5 + 1.5 A d**0.5 d')`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    dissipation : float
        Dissipation constant ``A`` [s].

    References
    ----------
    Kuwabara G., Kono K. (1987) Jpn. J. Appl. Phys. 26, 1230. DOI 10.1143/JJAP.26.1230
    Brilliantov N.V. et al. (1996) Phys. Rev. E 53, 5382. DOI 10.1103/PhysRevE.53.5382
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return _one_sided(overlap, _kuwabara_kono_raw(overlap, rate, k_hertz, dissipation))


def _hunt_crossley_raw(overlap, rate, stiffness, exponent, damping):
    return stiffness * _spow(overlap, exponent) * (1.0 + 1.5 * damping * rate)


def hunt_crossley_force(overlap, rate, stiffness, exponent, damping):
    """Hunt-Crossley force ``k d**n (1 + 1.5 chi d')`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
    stiffness : float
        Stiffness ``k`` [N/m**n].
    exponent : float
        Exponent ``n`` [-] (1.5 for Hertz).
    damping : float
        Damping ``chi`` [s/m]; for small ``chi v`` the restitution is ``1 - chi v``.

    References
    ----------
    Hunt K.H., Crossley F.R.E. (1975) J. Appl. Mech. 42, 440-445. DOI 10.1115/1.3423596
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return _one_sided(overlap, _hunt_crossley_raw(overlap, rate, stiffness, exponent, damping))


def _history(overlap, max_overlap):
    overlap = np.asarray(overlap, dtype=float)
    if max_overlap is None:
        return overlap, overlap
    return overlap, np.maximum(np.asarray(max_overlap, dtype=float), overlap)


def walton_braun_force(overlap, max_overlap, loading_stiffness, unloading_stiffness):
    """Walton-Braun hysteretic linear force [N].

    Loading ``k1 d`` while ``d`` is at its maximum; otherwise unloading
    ``k2 (d - d0)`` with the plastic overlap ``d0 = d_max (1 - k1/k2)``.

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    max_overlap : array_like or None
        Largest overlap reached so far [m]; ``None`` means a virgin loading path.
    loading_stiffness, unloading_stiffness : float
        ``k1 <= k2`` [N/m].

    References
    ----------
    Walton O.R., Braun R.L. (1986) J. Rheol. 30, 949-980. DOI 10.1122/1.549893
    """
    d, d_max = _history(overlap, max_overlap)
    unloading = unloading_stiffness * (d - d_max * (1.0 - loading_stiffness / unloading_stiffness))
    return _one_sided(d, np.where(d >= d_max, loading_stiffness * d, unloading))


def linear_plastic_force(overlap, max_overlap, stiffness, yield_force):
    """Linear spring with a force cap (elastic-perfectly-plastic, linear) [N].

    ``min(k d, Fy)`` on loading; elastic unloading with slope ``k`` from the largest force
    reached.

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    max_overlap : array_like or None
        Largest overlap reached so far [m]; ``None`` means a virgin loading path.
    stiffness : float
        Spring stiffness ``k`` [N/m].
    yield_force : float
        Force cap ``Fy`` [N].
    """
    d, d_max = _history(overlap, max_overlap)
    f_max = np.minimum(stiffness * d_max, yield_force)
    return _one_sided(d, np.minimum(f_max + stiffness * (d - d_max), yield_force))


def thornton_force(overlap, max_overlap, effective_modulus, effective_radius, yield_pressure):
    """Thornton (1997) elastic-perfectly-plastic Hertz force [N].

    Hertz up to the yield overlap ``dy``, then ``Fy + pi py R* (d - dy)``; unloading is
    Hertzian with an enlarged radius ``Rp`` from the plastic overlap ``dp``.

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    max_overlap : array_like or None
        Largest overlap reached so far [m]; ``None`` means a virgin loading path.
    effective_modulus : float
        ``E*`` [Pa].
    effective_radius : float
        ``R*`` [m].
    yield_pressure : float
        Limiting contact pressure ``py`` [Pa].

    References
    ----------
    Thornton C. (1997) J. Appl. Mech. 64, 383-386. DOI 10.1115/1.2787319
    """
    d, d_max = _history(overlap, max_overlap)
    return _one_sided(
        d, _thornton_raw(d, d_max, effective_modulus, effective_radius, yield_pressure)
    )


def _thornton_loading(d, modulus, radius, yield_pressure):
    k_hertz = 4.0 / 3.0 * modulus * math.sqrt(radius)
    d_y = analytic.thornton_yield_overlap(modulus, radius, yield_pressure)
    f_y = analytic.thornton_yield_force(modulus, radius, yield_pressure)
    plastic = f_y + math.pi * yield_pressure * radius * (d - d_y)
    return np.where(d <= d_y, k_hertz * _spow(d, 1.5), plastic)


def _thornton_unloading(d_max, modulus, radius, yield_pressure):
    """Unloading curve ``(kp, dp)``: ``F = kp (d - dp)**1.5`` from ``d_max``."""
    d_max = np.asarray(d_max, dtype=float)
    d_y = analytic.thornton_yield_overlap(modulus, radius, yield_pressure)
    f_y = analytic.thornton_yield_force(modulus, radius, yield_pressure)
    f_max = np.asarray(_thornton_loading(d_max, modulus, radius, yield_pressure))
    with np.errstate(divide="ignore", invalid="ignore"):
        contact_radius_cubed = ((2.0 * f_max + f_y) / (2.0 * math.pi * yield_pressure)) ** 1.5
        r_p = 4.0 * modulus * contact_radius_cubed / (3.0 * f_max)
        k_p = 4.0 / 3.0 * modulus * np.sqrt(np.where(d_max > d_y, r_p, radius))
        d_p = np.where(d_max > d_y, d_max - (f_max / k_p) ** (2.0 / 3.0), 0.0)
    return k_p, d_p


def _thornton_raw(d, d_max, modulus, radius, yield_pressure):
    k_p, d_p = _thornton_unloading(d_max, modulus, radius, yield_pressure)
    loading = _thornton_loading(d, modulus, radius, yield_pressure)
    return np.where(d >= d_max, loading, k_p * _spow(d - d_p, 1.5))


def plastic_trapezoid_force(time, amplitude, contact_time, ramp_time):
    """The paper's perfectly plastic pulse: a trapezoid in time [N].

    Parameters
    ----------
    time : array_like
        Time since first touch [s].
    amplitude : float
        Plateau force [N]; ``m2 v0 / (contact_time - ramp_time)`` gives impulse ``m2 v0``.
    contact_time : float
        Total duration, ramps included [s].
    ramp_time : float
        Duration of the linear rise and of the linear fall [s] (0 gives a rectangle).

    References
    ----------
    Keska W. et al. (2021) Applied Sciences 11, 11 (Eqs. 7-8).
    """
    time = np.asarray(time, dtype=float)
    if ramp_time == 0.0:
        shape = ((time >= 0) & (time < contact_time)).astype(float)
    else:
        shape = np.clip(np.minimum(time, contact_time - time) / ramp_time, 0.0, 1.0)
    return amplitude * shape


# ---------------------------------------------------------------------------
# The solver's view of a law: branches with linear exit conditions
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Exit:
    """Condition that ends a branch: ``g = a*d + b*d' + offset`` crossing zero.

    Attributes
    ----------
    overlap_coef : float
        ``a`` [1/m * unit of g].
    rate_coef : float
        ``b``.
    offset : float
        Constant term.
    direction : int
        +1 when the branch ends as ``g`` rises through zero, -1 as it falls.
    target : str
        Name of the branch that follows.
    """

    overlap_coef: float
    rate_coef: float
    offset: float
    direction: int
    target: str

    def value(self, overlap, rate):
        """Event function value at the given overlap [m] and rate [m/s]."""
        return self.overlap_coef * overlap + self.rate_coef * rate + self.offset


def _rate_turns(target):
    """Exit when the overlap stops growing (largest overlap reached)."""
    return Exit(0.0, 1.0, 0.0, -1, target)


def _overlap_reaches(level, target):
    """Exit when the overlap rises through ``level`` [m]."""
    return Exit(1.0, 0.0, -level, +1, target)


@dataclass(frozen=True)
class Branch:
    """One smooth piece of a law, as the solvers see it.

    Attributes
    ----------
    name : str
        Branch name (``"load"``, ``"yield"``, ``"unload"``).
    force : callable
        ``force(overlap, rate)`` -> formula value [N], vectorised, *not* clipped (a sign
        change marks the end of contact; the solver clips).
    linear : tuple of float or None
        ``(k, c, f0)`` when the branch is ``k d + c d' + f0`` (exact solver), else None.
    exits : tuple of Exit
        Conditions that end the branch.
    loading : bool
        Whether the largest overlap follows the overlap on this branch.
    """

    name: str
    force: Callable
    linear: tuple | None = None
    exits: tuple = ()
    loading: bool = True


class ContactLaw(KeywordChecked, ABC):
    """Base class of normal contact laws.

    A law needs :meth:`_force` (the vectorised force from overlap, rate and history) and
    :meth:`branch` (how the solvers see it). Restitution, contact time, dissipated
    energy and work follow here.

    Sign convention: overlap ``d > 0`` in compression, rate ``d' > 0`` approaching, force
    ``>= 0`` always (0 for ``d <= 0``).
    """

    name: ClassVar[str]
    """Registry key used by the command line and TOML files."""
    has_history: ClassVar[bool] = False
    """Whether the force depends on the largest overlap reached so far."""
    piecewise_linear: ClassVar[bool] = False
    """Whether every branch is linear in overlap and rate (exact solver applies)."""
    prescribed: ClassVar[bool] = False
    """Whether the force is a prescribed function of time instead of overlap."""

    @abstractmethod
    def _force(self, overlap, rate, max_overlap):
        """Force formula (may be negative) for arrays of overlap, rate and history."""

    @abstractmethod
    def branch(self, name, max_overlap=0.0):
        """The :class:`Branch` called ``name`` given the largest overlap so far [m]."""

    def parameters(self):
        """Parameters as a dict (name -> value in SI units)."""
        return dict(self._params)

    def __repr__(self):
        args = ", ".join(f"{k}={v:.6g}" for k, v in self._params.items())
        return f"{type(self).__name__}({args})"

    def __eq__(self, other):
        return type(self) is type(other) and self._params == other._params

    def __hash__(self):
        return hash((type(self), tuple(self._params.items())))

    def force(self, overlap, rate=0.0, max_overlap=None):
        """Contact force [N] for overlap [m] and rate [m/s] (arrays broadcast).

        Parameters
        ----------
        overlap : array_like
            Overlap ``d`` [m], positive in compression.
        rate : array_like, default 0
            Overlap rate ``d'`` [m/s], positive while approaching.
        max_overlap : array_like or None
            Largest overlap reached before [m] (history laws); ``None`` is a virgin
            loading path (``max_overlap = overlap``).

        Returns
        -------
        numpy.ndarray
            Force, 0 for ``d <= 0`` and never negative [N].
        """
        overlap = np.asarray(overlap, dtype=float)
        return _one_sided(overlap, self._force(overlap, np.asarray(rate, float), max_overlap))

    initial_branch: ClassVar[str] = "load"

    def reentry(self, max_overlap):
        """Overlap [m] at which a separated grain touches again, and the branch it enters."""
        return 0.0, self.initial_branch

    def impact(self, mass, velocity, **kwargs):
        """Impact of a grain of ``mass`` [kg] at ``velocity`` [m/s] on an immovable wall.

        Returns the :class:`~contactlab.result.ImpactResult`; keyword arguments go to
        :func:`contactlab.simulate_impact`.
        """
        from contactlab.bodies import Grain, Sensor
        from contactlab.impact import simulate_impact

        kwargs.setdefault("duration", None)
        return simulate_impact(
            Grain.from_mass(mass), Sensor.rigid(), self, velocity=velocity, **kwargs
        )

    def restitution(self, mass, velocity):
        """Coefficient of restitution on an immovable wall [-] (force-zero contact end)."""
        return self.impact(mass, velocity).restitution

    def contact_time(self, mass, velocity):
        """Contact duration on an immovable wall [s] (force-zero contact end)."""
        return self.impact(mass, velocity).contact_time

    def dissipated_energy(self, mass, velocity):
        """Energy lost in one impact on an immovable wall [J]: ``m v**2 (1 - e**2) / 2``."""
        e = self.restitution(mass, velocity)
        return 0.5 * mass * velocity**2 * (1.0 - e**2)

    def work(self, overlap, rate=None):
        """Work done by the contact force along an overlap path [J] (trapezoidal rule).

        Parameters
        ----------
        overlap : array_like
            Overlap path [m], e.g. a loading-unloading cycle.
        rate : array_like or None
            Overlap rate along the path [m/s]; ``None`` is quasi-static (zero rate).

        Returns
        -------
        float
            ``integral F dd`` along the path; for a closed cycle, the energy dissipated.
        """
        d = np.asarray(overlap, dtype=float)
        rate = np.zeros_like(d) if rate is None else np.asarray(rate, dtype=float)
        d_max = np.maximum.accumulate(np.maximum(d, 0.0)) if self.has_history else None
        return float(np.trapezoid(self.force(d, rate, d_max), d))


def _positive(name, value, unit):
    return check_number(name, value, low=0.0, unit=unit)


def _non_negative(name, value, unit):
    return check_number(name, value, low=0.0, low_open=False, unit=unit)


class SmoothLaw(ContactLaw):
    """A law of one smooth branch without history: subclasses define :meth:`_raw`.

    The solvers see the single branch ``"load"``, whose force is the raw formula (it may
    turn negative, which marks the end of contact); a branch linear in overlap and rate
    also gives its coefficients (:meth:`_linear`) so the exact solver applies.
    """

    @abstractmethod
    def _raw(self, overlap, rate):
        """Force formula [N] for overlap [m] and rate [m/s] (floats or arrays)."""

    def _linear(self):
        """``(k, c, f0)`` if the formula is ``k d + c d' + f0``, else None."""
        return None

    def _force(self, overlap, rate, max_overlap):
        return self._raw(overlap, rate)

    def branch(self, name, max_overlap=0.0):
        return Branch("load", self._raw, linear=self._linear(), loading=False)


class LinearViscoelastic(SmoothLaw):
    """Linear spring-dashpot (Kelvin-Voigt) contact, one-sided: ``max(k d + c d', 0)``.

    Parameters
    ----------
    stiffness : float
        Contact stiffness ``k`` [N/m], > 0.
    damping : float, default 0
        Damping coefficient ``c`` [N*s/m], >= 0.

    Notes
    -----
    The paper's Eq. (6). The contact ends when the force reaches zero, before the
    overlap returns to zero when ``c > 0``; :func:`contactlab.analytic.linear_restitution`
    gives both conventions. See :func:`linear_viscoelastic_force`.
    """

    name = "linear"
    piecewise_linear = True

    def __init__(self, stiffness, damping=0.0):
        self.stiffness = _positive("stiffness", stiffness, "N/m")
        self.damping = _non_negative("damping", damping, "N*s/m")
        self._params = {"stiffness": self.stiffness, "damping": self.damping}

    @classmethod
    def from_restitution(cls, stiffness, restitution, mass, convention="overlap"):
        """Damping that gives a restitution coefficient for a grain of ``mass``.

        Parameters
        ----------
        stiffness : float
            Contact stiffness [N/m].
        restitution : float
            Target restitution in (0, 1] [-].
        mass : float
            Effective mass [kg].
        convention : {"overlap", "force"}
            Contact end assumed by the mapping. ``"overlap"`` (default) is the formula of
            LIGGGHTS, MercuryDPM and EDEM, ``zeta = -ln e / sqrt(pi**2 + ln(e)**2)``; it
            assumes the contact ends when the overlap returns to zero. This toolkit's
            solvers end the contact when the force reaches zero, where the same damping
            realises a *larger* restitution
            (``analytic.linear_restitution(k, c, m, "force")``; e.g. 0.5 -> 0.58).
            ``"force"`` inverts the force-zero relation so that the solver realises
            ``restitution`` exactly.
        """
        check_choice("convention", convention, ("overlap", "force"))
        damping = analytic.linear_damping_from_restitution(
            stiffness, restitution, mass, convention=convention
        )
        return cls(stiffness=stiffness, damping=damping)

    def _raw(self, overlap, rate):
        return _linear_raw(overlap, rate, self.stiffness, self.damping)

    def _linear(self):
        return (self.stiffness, self.damping, 0.0)


def _modulus_radius(youngs_modulus, poisson_ratio, radius, other):
    """Effective modulus and radius from a grain and an optional second body."""
    e1 = _positive("youngs_modulus", youngs_modulus, "Pa")
    nu1 = check_number("poisson_ratio", poisson_ratio, low=-1.0, high=0.5, high_open=False)
    r1 = _positive("radius", radius, "m")
    e2 = check_number("other_youngs_modulus", other[0], low=0.0, unit="Pa", allow_inf=True)
    nu2 = check_number("other_poisson_ratio", other[1], low=-1.0, high=0.5, high_open=False)
    r2 = check_number("other_radius", other[2], low=0.0, unit="m", allow_inf=True)
    modulus = analytic.effective_modulus(e1, nu1, e2, nu2)
    return modulus, analytic.effective_radius(r1, r2)


class Hertz(SmoothLaw):
    """Hertz elastic contact ``kH d**1.5``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness ``kH = 4/3 E* sqrt(R*)`` [N/m**1.5].

    See Also
    --------
    hertz_force
    """

    name = "hertz"

    def __init__(self, k_hertz):
        self.k_hertz = _positive("k_hertz", k_hertz, "N/m**1.5")
        self._params = {"k_hertz": self.k_hertz}

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        other_radius=math.inf,
    ):
        """Hertz law from material data [Pa, -, m]; a rigid flat unless a second body is given.

        The second body (another grain, a compliant plate) enters through
        ``1/E* = (1-nu1**2)/E1 + (1-nu2**2)/E2`` and ``1/R* = 1/R1 + 1/R2``.
        """
        modulus, radius_eff = _modulus_radius(
            youngs_modulus,
            poisson_ratio,
            radius,
            (other_youngs_modulus, other_poisson_ratio, other_radius),
        )
        return cls(k_hertz=analytic.hertz_stiffness(modulus, radius_eff))

    def _raw(self, overlap, rate):
        return _hertz_raw(overlap, self.k_hertz)


class HertzDamped(SmoothLaw):
    """Damped Hertz contact of Tsuji et al. (EDEM, LIGGGHTS): ``kH d**1.5 + eta d**0.25 d'``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    damping : float
        ``eta = alpha sqrt(m* kH)`` [N*s/m**1.25], >= 0.

    Notes
    -----
    With this form the restitution depends only on ``alpha``, not on the impact velocity.
    See :func:`hertz_damped_force`.
    """

    name = "hertz_damped"

    def __init__(self, k_hertz, damping):
        self.k_hertz = _positive("k_hertz", k_hertz, "N/m**1.5")
        self.damping = _non_negative("damping", damping, "N*s/m**1.25")
        self._params = {"k_hertz": self.k_hertz, "damping": self.damping}

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        restitution,
        mass,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        other_radius=math.inf,
    ):
        """Hertz-Mindlin normal law as EDEM and LIGGGHTS build it.

        Parameters
        ----------
        youngs_modulus, poisson_ratio, radius : float
            Grain data [Pa, -, m]; the optional second body as in :meth:`Hertz.from_material`.
        restitution : float
            Target restitution in (0, 1] [-].
        mass : float
            Effective mass [kg].

        Notes
        -----
        The EDEM mapping ``alpha = sqrt(5) (-ln e) / sqrt(pi**2 + ln(e)**2)`` assumes the
        overlap-zero contact end, under which it is exact (Antypov & Elliott 2011). This
        toolkit's one-sided contact ends when the force reaches zero and realises a larger
        restitution: 0.3 -> 0.397, 0.5 -> 0.550, 0.7 -> 0.718, 0.9 -> 0.902
        (:func:`contactlab.analytic.tsuji_restitution` with ``convention="force"``).
        """
        check_probability("restitution", restitution, low_open=True)
        mass = _positive("mass", mass, "kg")
        k_hertz = Hertz.from_material(
            youngs_modulus,
            poisson_ratio,
            radius,
            other_youngs_modulus,
            other_poisson_ratio,
            other_radius,
        ).k_hertz
        return cls(k_hertz, analytic.tsuji_damping_coefficient(k_hertz, mass, restitution))

    def _raw(self, overlap, rate):
        return _hertz_damped_raw(overlap, rate, self.k_hertz, self.damping)


class KuwabaraKono(SmoothLaw):
    """Viscoelastic Hertz contact (Kuwabara-Kono, Brilliantov): ``kH (d**1.5 + 1.5 A d**0.5 d')``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    dissipation : float
        Dissipation constant ``A`` [s], >= 0.

    See Also
    --------
    kuwabara_kono_force, contactlab.analytic.kuwabara_kono_restitution
    """

    name = "kuwabara_kono"

    def __init__(self, k_hertz, dissipation):
        self.k_hertz = _positive("k_hertz", k_hertz, "N/m**1.5")
        self.dissipation = _non_negative("dissipation", dissipation, "s")
        self._params = {"k_hertz": self.k_hertz, "dissipation": self.dissipation}

    def _raw(self, overlap, rate):
        return _kuwabara_kono_raw(overlap, rate, self.k_hertz, self.dissipation)


class HuntCrossley(SmoothLaw):
    """Hunt-Crossley contact ``k d**n (1 + 1.5 chi d')``.

    Parameters
    ----------
    stiffness : float
        ``k`` [N/m**n].
    exponent : float
        ``n`` in [1, 3] [-] (1.5 for Hertz).
    damping : float
        ``chi`` [s/m], >= 0.

    See Also
    --------
    hunt_crossley_force, contactlab.analytic.hunt_crossley_restitution
    """

    name = "hunt_crossley"

    def __init__(self, stiffness, exponent, damping):
        self.stiffness = _positive("stiffness", stiffness, "N/m**n")
        self.exponent = check_number("exponent", exponent, low=1.0, high=3.0, low_open=False)
        self.damping = _non_negative("damping", damping, "s/m")
        self._params = {
            "stiffness": self.stiffness,
            "exponent": self.exponent,
            "damping": self.damping,
        }

    def _raw(self, overlap, rate):
        return _hunt_crossley_raw(overlap, rate, self.stiffness, self.exponent, self.damping)


class WaltonBraun(ContactLaw):
    """Walton-Braun hysteretic linear contact (LIGGGHTS hooke/hysteresis, Luding's model).

    Parameters
    ----------
    loading_stiffness : float
        ``k1`` [N/m], > 0.
    unloading_stiffness : float
        ``k2 >= k1`` [N/m]. Restitution on a wall ``sqrt(k1/k2)``.

    See Also
    --------
    walton_braun_force
    """

    name = "walton_braun"
    has_history = True
    piecewise_linear = True

    def __init__(self, loading_stiffness, unloading_stiffness):
        self.loading_stiffness = _positive("loading_stiffness", loading_stiffness, "N/m")
        self.unloading_stiffness = check_number(
            "unloading_stiffness",
            unloading_stiffness,
            low=self.loading_stiffness,
            low_open=False,
            unit="N/m (>= loading_stiffness)",
        )
        self._params = {
            "loading_stiffness": self.loading_stiffness,
            "unloading_stiffness": self.unloading_stiffness,
        }

    def _force(self, overlap, rate, max_overlap):
        d, d_max = _history(overlap, max_overlap)
        k1, k2 = self.loading_stiffness, self.unloading_stiffness
        return np.where(d >= d_max, k1 * d, k2 * (d - self._plastic_overlap(d_max)))

    def _plastic_overlap(self, max_overlap):
        return max_overlap * (1.0 - self.loading_stiffness / self.unloading_stiffness)

    def branch(self, name, max_overlap=0.0):
        k1, k2 = self.loading_stiffness, self.unloading_stiffness
        if name == "load":
            return Branch("load", lambda d, r: k1 * d, (k1, 0.0, 0.0), (_rate_turns("unload"),))
        d0 = self._plastic_overlap(max_overlap)
        return Branch(
            "unload",
            lambda d, r: k2 * (d - d0),
            (k2, 0.0, -k2 * d0),
            (_overlap_reaches(max_overlap, "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return self._plastic_overlap(max_overlap), "unload"


class LinearPlastic(ContactLaw):
    """Linear spring with a force cap: elastic-perfectly-plastic, linear.

    Parameters
    ----------
    stiffness : float
        ``k`` [N/m], > 0.
    yield_force : float
        Force cap ``Fy`` [N], > 0. On a wall, ``e = min(1, Fy / (v sqrt(k m)))``.

    See Also
    --------
    linear_plastic_force
    """

    name = "linear_plastic"
    has_history = True
    piecewise_linear = True

    def __init__(self, stiffness, yield_force):
        self.stiffness = _positive("stiffness", stiffness, "N/m")
        self.yield_force = _positive("yield_force", yield_force, "N")
        self._params = {"stiffness": self.stiffness, "yield_force": self.yield_force}

    def _force(self, overlap, rate, max_overlap):
        d, d_max = _history(overlap, max_overlap)
        f_max = np.minimum(self.stiffness * d_max, self.yield_force)
        return np.minimum(f_max + self.stiffness * (d - d_max), self.yield_force)

    def branch(self, name, max_overlap=0.0):
        k, f_y = self.stiffness, self.yield_force
        if name == "load":
            return Branch(
                "load",
                lambda d, r: k * d,
                (k, 0.0, 0.0),
                (_rate_turns("unload"), _overlap_reaches(f_y / k, "yield")),
            )
        if name == "yield":
            return Branch(
                "yield",
                lambda d, r: np.full_like(d, f_y),
                (0.0, 0.0, f_y),
                (_rate_turns("unload"),),
            )
        f_max = min(k * max_overlap, f_y)
        return Branch(
            "unload",
            lambda d, r: f_max + k * (d - max_overlap),
            (k, 0.0, f_max - k * max_overlap),
            (_overlap_reaches(max_overlap, "yield" if f_max >= f_y else "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return max_overlap - min(self.stiffness * max_overlap, self.yield_force) / self.stiffness, (
            "unload"
        )


class Thornton(ContactLaw):
    """Thornton (1997) elastic-perfectly-plastic Hertz contact.

    Parameters
    ----------
    effective_modulus : float
        ``E*`` [Pa].
    effective_radius : float
        ``R*`` [m].
    yield_pressure : float
        Limiting contact pressure ``py`` [Pa].

    See Also
    --------
    thornton_force, contactlab.analytic.thornton_restitution
    """

    name = "thornton"
    has_history = True

    def __init__(self, effective_modulus, effective_radius, yield_pressure):
        self.effective_modulus = _positive("effective_modulus", effective_modulus, "Pa")
        self.effective_radius = _positive("effective_radius", effective_radius, "m")
        self.yield_pressure = _positive("yield_pressure", yield_pressure, "Pa")
        self._params = {
            "effective_modulus": self.effective_modulus,
            "effective_radius": self.effective_radius,
            "yield_pressure": self.yield_pressure,
        }

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        yield_pressure,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        other_radius=math.inf,
    ):
        """Thornton law from grain data [Pa, -, m] and yield pressure [Pa]; rigid flat default."""
        modulus, radius_eff = _modulus_radius(
            youngs_modulus,
            poisson_ratio,
            radius,
            (other_youngs_modulus, other_poisson_ratio, other_radius),
        )
        return cls(modulus, radius_eff, yield_pressure)

    @property
    def _material(self):
        return self.effective_modulus, self.effective_radius, self.yield_pressure

    def _force(self, overlap, rate, max_overlap):
        d, d_max = _history(overlap, max_overlap)
        return _thornton_raw(d, d_max, *self._material)

    def branch(self, name, max_overlap=0.0):
        modulus, radius, p_y = self._material
        d_y = analytic.thornton_yield_overlap(modulus, radius, p_y)
        if name == "load":
            k_hertz = analytic.hertz_stiffness(modulus, radius)
            return Branch(
                "load",
                lambda d, r: k_hertz * _spow(d, 1.5),
                exits=(_rate_turns("unload"), _overlap_reaches(d_y, "yield")),
            )
        if name == "yield":
            f_y = analytic.thornton_yield_force(modulus, radius, p_y)
            k_p = math.pi * p_y * radius
            return Branch(
                "yield",
                lambda d, r: f_y + k_p * (d - d_y),
                (k_p, 0.0, f_y - k_p * d_y),
                (_rate_turns("unload"),),
            )
        k_u, d_p = (float(v) for v in _thornton_unloading(max_overlap, *self._material))
        return Branch(
            "unload",
            lambda d, r: k_u * _spow(d - d_p, 1.5),
            exits=(_overlap_reaches(max_overlap, "yield" if max_overlap > d_y else "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return float(_thornton_unloading(max_overlap, *self._material)[1]), "unload"


class PlasticTrapezoid(KeywordChecked):
    """The paper's perfectly plastic contact: a prescribed trapezoidal force pulse.

    Parameters
    ----------
    contact_time : float
        Total pulse duration ``t_k``, ramps included [s].
    ramp_time : float, default 0
        Duration of the linear rise and of the linear fall [s], at most half the pulse.

    Notes
    -----
    The force is a function of time, not of overlap (Eqs. 7-8 of the paper, with the
    trapezoid the authors used instead of the rectangle). Its plateau is sized so that
    the impulse equals the grain's momentum ``m2 v0`` exactly: the grain stops
    (restitution 0). It is solved exactly (first-order hold) and never re-contacts.
    """

    name = "plastic_trapezoid"
    prescribed = True
    has_history = False
    piecewise_linear = True

    def __init__(self, contact_time, ramp_time=0.0):
        self.contact_time = _positive("contact_time", contact_time, "s")
        self.ramp_time = check_number(
            "ramp_time",
            ramp_time,
            low=0.0,
            high=0.5 * self.contact_time,
            low_open=False,
            unit="s (at most contact_time/2)",
        )
        self._params = {"contact_time": self.contact_time, "ramp_time": self.ramp_time}

    parameters = ContactLaw.parameters
    __repr__ = ContactLaw.__repr__
    __eq__ = ContactLaw.__eq__
    __hash__ = ContactLaw.__hash__
    impact = ContactLaw.impact

    def amplitude(self, mass, velocity):
        """Plateau force [N] for a grain of ``mass`` [kg] at ``velocity`` [m/s]."""
        return analytic.plastic_trapezoid_amplitude(
            mass, velocity, self.contact_time, self.ramp_time
        )

    def pieces(self, mass, velocity):
        """Straight pieces of the pulse: ``(t_start [s], t_end [s], F_start [N], F_end [N])``.

        A rectangle (``ramp_time = 0``) is one piece; a trapezoid is rise, plateau, fall
        (the plateau is dropped when the ramps meet).
        """
        amp, r, t = self.amplitude(mass, velocity), self.ramp_time, self.contact_time
        if r == 0.0:
            return [(0.0, t, amp, amp)]
        pieces = [(0.0, r, 0.0, amp), (r, t - r, amp, amp), (t - r, t, amp, 0.0)]
        return [p for p in pieces if p[1] > p[0]]

    def force_at(self, time, mass, velocity):
        """Contact force [N] at ``time`` [s] after first touch (see plastic_trapezoid_force)."""
        return plastic_trapezoid_force(
            time, self.amplitude(mass, velocity), self.contact_time, self.ramp_time
        )

    def restitution(self, mass, velocity):
        """Always 0: the impulse equals the grain's momentum."""
        return 0.0


LAWS = {
    cls.name: cls
    for cls in (
        LinearViscoelastic,
        Hertz,
        HertzDamped,
        KuwabaraKono,
        HuntCrossley,
        WaltonBraun,
        LinearPlastic,
        Thornton,
        PlasticTrapezoid,
    )
}
"""Registry: law name (as used in TOML files and on the command line) -> class."""


def get_law(name, **parameters):
    """Build a law by registry name, e.g. ``get_law("linear", stiffness=1e5, damping=1.0)``.

    An unknown name raises :class:`~contactlab.errors.ParameterError` listing the valid
    ones (with a near-match suggestion).
    """
    cls = LAWS[check_choice("law", name, tuple(LAWS))]
    if not isinstance(parameters, dict):
        raise ParameterError("law parameters must be keyword arguments")
    return cls(**parameters)
