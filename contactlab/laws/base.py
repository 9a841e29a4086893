"""The contact-law base: sign convention, branches, the abstract law.

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

A law defines forces only. Its impact on an immovable wall (restitution, contact time,
dissipated energy) is a simulation: :mod:`contactlab.solver.wall` (``wall_impact``,
``wall_restitution``, ``wall_contact_time``, ``wall_dissipated_energy``), above the laws.
"""

import functools
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from types import MappingProxyType
from typing import ClassVar

import numpy as np

from contactlab.errors import ParameterError
from contactlab.validation import KeywordChecked, check_samples, numbers_checked

__all__ = ["Branch", "ContactLaw", "Exit", "PowerForm", "SmoothLaw"]


def read_only(**units):
    """A law's table (parameter units, typical ranges), read-only:
    ``units = read_only(k_hertz="N/m**1.5")``."""
    return MappingProxyType(units)


def stated(law, name):
    """The method ``name`` of ``law`` if its own class states it, else None.

    What a law says about itself beyond its force (closed forms, batch columns, DEM
    mappings) is not inherited: a subclass may change the force, so it states them again
    or is refused by name.
    """
    method = vars(type(law)).get(name)
    return None if method is None else method.__get__(law)


def force_function(*optional):
    """Decorator of a public force function: its arguments are checked as
    :func:`~contactlab.validation.numbers_checked` checks them (``optional`` may be
    ``None``), and a force beyond the float range (an overlap or a parameter no contact
    has) raises :class:`~contactlab.errors.ParameterError` instead of an overflow warning
    and ``inf``."""

    def decorate(function):
        @functools.wraps(function)
        def finite(*args, **kwargs):
            with np.errstate(over="ignore", invalid="ignore"):
                force = function(*args, **kwargs)
            if not np.all(np.isfinite(force)):
                raise ParameterError(
                    f"{function.__name__}: the force overflows the float range for these "
                    "arguments (an overlap or a parameter no contact has)"
                )
            return force

        return numbers_checked(*optional)(finite)

    return decorate


def one_sided(overlap, raw):
    """Zero out of contact and never tensile."""
    return np.where(np.asarray(overlap) > 0, np.maximum(raw, 0.0), 0.0)


# The ``_*_raw`` formulas and :func:`signed_power` use operators only, so they take Python floats
# as well as arrays: the adaptive solver calls them on floats thousands of times per
# impact, where a numpy call per operation would cost more than the arithmetic. Public
# functions convert their array_like inputs first.
def signed_power(x, p):
    """Signed power ``sign(x) |x|**p`` for ``p >= 1``: the odd extension keeps a zero
    crossing visible."""
    return x * abs(x) ** (p - 1.0)


def with_history(overlap, max_overlap):
    overlap = np.asarray(overlap, dtype=float)
    if max_overlap is None:
        return overlap, overlap
    return overlap, np.maximum(np.asarray(max_overlap, dtype=float), overlap)


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


def rate_turns(target):
    """Exit when the overlap stops growing (largest overlap reached)."""
    return Exit(0.0, 1.0, 0.0, -1, target)


def overlap_reaches(level, target):
    """Exit when the overlap rises through ``level`` [m]."""
    return Exit(1.0, 0.0, -level, +1, target)


@dataclass(frozen=True)
class PowerForm:
    """A force of the form ``a sign(d) |d|**p + b D(d) d'`` with ``D(d) = |d|**q``
    (``sign(d) |d|**q`` when ``signed_damping``), the raw formula of every Hertz-family law.

    The solvers compile this one formula (:mod:`contactlab.kernels.power`) instead of
    calling the law's Python function at every stage of every step.

    Attributes
    ----------
    stiffness : float
        ``a`` [N/m**p].
    exponent : float
        ``p`` [-].
    damping : float
        ``b`` [N*s/m**(1+q)].
    damping_exponent : float
        ``q`` [-].
    signed_damping : bool
        Whether the damping term carries the sign of the overlap (Hunt-Crossley).
    """

    stiffness: float
    exponent: float
    damping: float = 0.0
    damping_exponent: float = 0.0
    signed_damping: bool = False


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
    power : PowerForm or None
        The formula as a :class:`PowerForm` when it is one (compiled adaptive solver).
    """

    name: str
    force: Callable
    linear: tuple | None = None
    exits: tuple = ()
    loading: bool = True
    power: PowerForm | None = None


class ContactLaw(KeywordChecked, ABC):
    """Base class of normal contact laws.

    A law needs :meth:`_force` (the vectorised force from overlap, rate and history) and
    :meth:`branch` (how the solvers see it); the work along a path follows here. Its
    impact on a wall is :mod:`contactlab.solver.wall`'s.

    Everything else the toolkit needs to know about a law, the law states once, on its
    class (its name in :data:`contactlab.laws.LAWS` is the only other line):

    * ``name``, :attr:`units` (checked by the constructor through :meth:`_keep`, the
      study's column units), :attr:`typical` and :meth:`_from_typical` (the test
      strategies), :attr:`stiffness_parameters` (the study's scatter);
    * ``power_form()`` (the compiled solver) or branches (the Python pieces);
    * ``_closed_forms(mass, velocity)``: its wall impact in closed form, a tuple of
      :class:`~contactlab.laws.closed_form.ClosedForm` (the testing plug-in, the audit
      matrix, the study's contact time);
    * optional: ``_batch_contact()`` (its batch solver and columns), ``_lammps_model(m*,
      R*)`` or a ``lammps_refusal`` reason (:mod:`contactlab.laws.lammps`),
      ``_kratos_model(m*, R*, wall)`` or a ``kratos_refusal`` reason
      (:mod:`contactlab.laws.kratos`), ``dem_export``
      (the DEM exporters' family), ``_damping_ratio(m*)`` (Kratos' tied tangential
      damping), ``from_material`` and ``_resized(mass, grain, velocity)`` (a study whose
      law follows the grain size).

    What a law does not state is refused by name where it is asked for. These are read
    from the law's own class only (:func:`stated`): a subclass may change the force, so it
    states them again.

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
    units: ClassVar[MappingProxyType]
    """Parameter name -> SI unit (the constructor's checks and the study's columns)."""
    typical: ClassVar[MappingProxyType]
    """Ranges real grains span: name -> ``(low, high, scale)``, ``scale`` "log" for a
    range of decades, else "linear"; the test strategies draw laws from them
    (:func:`contactlab.testing.strategies.laws`) through :meth:`_from_typical`."""
    stiffness_parameters: ClassVar[tuple[str, ...]] = ()
    """Parameters that make up "the contact stiffness" a study's scatter multiplies (all
    by the same factor, so that e.g. Walton-Braun keeps its restitution)."""

    @classmethod
    def _from_typical(cls, **drawn):
        """The law from values drawn over :attr:`typical` (by default its parameters)."""
        return cls(**drawn)

    @abstractmethod
    def _force(self, overlap, rate, max_overlap):
        """Force formula (may be negative) for arrays of overlap, rate and history."""

    @abstractmethod
    def branch(self, name, max_overlap=0.0):
        """The :class:`Branch` called ``name`` given the largest overlap so far [m]."""

    def _keep(self, **checked):
        """Check each parameter, ``name=(check, value)``, in its unit (:attr:`units`) with
        ``check(name, value, unit=...)`` and keep it as an attribute and in
        :meth:`parameters`."""
        for name, (check, value) in checked.items():
            setattr(self, name, check(name, value, unit=self.units[name]))
        self._params = {name: getattr(self, name) for name in checked}

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
        overlap = check_samples("overlap", overlap, ndim=None, unit="m")
        rate = check_samples("rate", rate, ndim=None, unit="m/s")
        if max_overlap is not None:
            max_overlap = check_samples("max_overlap", max_overlap, ndim=None, unit="m")
        return one_sided(overlap, self._force(overlap, rate, max_overlap))

    initial_branch: ClassVar[str] = "load"

    def reentry(self, max_overlap):
        """Overlap [m] at which a separated grain touches again, and the branch it enters."""
        return 0.0, self.initial_branch

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
        d = check_samples("overlap", overlap, min_size=2, unit="m")
        rate = np.zeros_like(d) if rate is None else check_samples("rate", rate, unit="m/s")
        if rate.shape != d.shape:
            raise ParameterError(
                f"rate must have the overlap path's shape {d.shape}; got {rate.shape}"
            )
        d_max = np.maximum.accumulate(np.maximum(d, 0.0)) if self.has_history else None
        return float(np.trapezoid(self.force(d, rate, d_max), d))


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

    def power_form(self):
        """The formula as a :class:`PowerForm`, or None if it is not of that form."""
        return None

    def _force(self, overlap, rate, max_overlap):
        return self._raw(overlap, rate)

    def branch(self, name, max_overlap=0.0):
        return Branch(
            "load", self._raw, linear=self._linear(), loading=False, power=self.power_form()
        )
