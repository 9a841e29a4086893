"""Physics audits of impact results: an energy ledger and the invariants a contact keeps.

Every result can say whether it obeys the physics its model promises. An audit holds

* an :class:`EnergyLedger` over the (first) contact: kinetic energy in (translation and
  spin), kinetic energy out in translation and in rotation, the energy left in the sensor
  (kinetic and elastic) and lost in its damper, the work of the normal contact's damper,
  the elastic energy the normal contact still held when the force reached zero (a damped
  law separates at a positive overlap), the work of the tangential force (friction and
  the tangential spring's hysteresis) and the residual (in minus the rest: zero up to the
  solver's and the quadrature's accuracy);
* :class:`Check` s, each a worst value over the contact in a stated scale and its
  tolerance: ``one_sided`` (the normal force never pulls), ``coulomb`` (``|T| <= mu N``),
  ``energy`` (the rebound carries no more energy than came in), ``damper`` (a damper
  never does positive work), ``momentum_*`` (the impulse of the contact force equals the
  grain's momentum change) and ``residual``.

The energy of the grain and sensor obeys, exactly, along any solution::

    d/dt (E_kin + E_sensor) = -N d' - c1 v1**2 + T s

(``N`` normal force, ``d'`` overlap rate, ``T`` tangential force on the grain, ``s`` slip), so
the ledger is the integral of these terms (Gauss-Legendre on the dense solution,
:mod:`contactlab.quadrature`), independent of the solver's bookkeeping.

Where a model itself allows a check to fail (Mindlin's stiffness changes with the overlap
under a held history, so both Mindlin forms can return more energy than they stored),
the check carries the reason in ``model_property`` and does not count as a failure; its
value is still reported. ``docs/verification.md`` lists every check, where it runs, and
the worst values measured over the whole parameter matrix.
"""

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from contactlab.errors import AuditWarning
from contactlab.quadrature import gauss_rule

__all__ = [
    "Audit",
    "Check",
    "EnergyLedger",
    "elastic_energy",
    "energy_check",
    "warn_if_broken",
]

LEDGER_KEYS = (
    "kinetic_in",
    "translation_out",
    "rotation_out",
    "sensor_left",
    "sensor_damper",
    "normal_damper",
    "normal_elastic_left",
    "friction",
    "residual",
)


@dataclass(frozen=True)
class EnergyLedger:
    """Where the impact energy went by the end of the contact [J].

    ``kinetic_in = translation_out + rotation_out + sensor_left + sensor_damper +
    normal_damper + normal_elastic_left + friction + residual``.

    Attributes
    ----------
    kinetic_in : float
        Grain's kinetic energy at the touch, translation and spin [J].
    translation_out, rotation_out : float
        Grain's kinetic energy after the contact, translation and spin [J].
    sensor_left : float
        Sensor's kinetic and elastic energy at the contact end [J] (0 on a flat).
    sensor_damper : float
        ``integral c1 v1**2 dt`` over the contact [J].
    normal_damper : float
        Work of the normal contact's rate-dependent (or hysteretic) part [J]:
        ``integral N d' dt`` minus ``normal_elastic_left``.
    normal_elastic_left : float
        Elastic energy of the normal law at the overlap where the force reached zero [J]
        (``integral_0^d N(x, 0) dx``; 0 for an elastic law, which separates at d = 0).
    friction : float
        Work absorbed by the tangential force, ``-integral T s dt`` [J]: Coulomb sliding and
        the tangential spring's hysteresis (negative where the model returns more than it
        stored).
    residual : float
        In minus the rest [J].
    """

    kinetic_in: float
    translation_out: float
    rotation_out: float = 0.0
    sensor_left: float = 0.0
    sensor_damper: float = 0.0
    normal_damper: float = 0.0
    normal_elastic_left: float = 0.0
    friction: float = 0.0
    residual: float = field(init=False)

    def __post_init__(self):
        spent = sum(getattr(self, k) for k in LEDGER_KEYS[1:-1])
        object.__setattr__(self, "residual", self.kinetic_in - spent)

    @property
    def kinetic_out(self):
        """Energy the bodies still hold after the contact (grain and sensor) [J]."""
        return self.translation_out + self.rotation_out + self.sensor_left

    def as_dict(self):
        """The ledger with unit-bearing keys (JSON-ready)."""
        return {f"{k} [J]": float(getattr(self, k)) for k in LEDGER_KEYS}


@dataclass(frozen=True)
class Check:
    """One invariant: its worst value over the contact against its tolerance.

    Attributes
    ----------
    name : str
        ``"one_sided"``, ``"coulomb"``, ``"energy"``, ``"damper"``, ``"momentum_normal"``,
        ``"momentum_tangential"``, ``"momentum_angular"`` or ``"residual"``.
    worst : float
        Worst violation in the scale ``scale`` names [-] (<= 0: none at all).
    tolerance : float
        Largest ``worst`` the solver's accuracy explains [-].
    scale : str
        What ``worst`` is relative to, e.g. ``"peak normal force"``.
    at : float
        Time of the worst value [s] (nan for a check on end states).
    model_property : str
        Non-empty when the model itself allows ``worst > tolerance`` (why).
    """

    name: str
    worst: float
    tolerance: float
    scale: str
    at: float = math.nan
    model_property: str = ""

    @property
    def passed(self):
        """Whether the worst value is within the tolerance."""
        return bool(self.worst <= self.tolerance)

    @property
    def failed(self):
        """Whether it broke beyond tolerance where the model does not allow it."""
        return not self.passed and not self.model_property

    def as_dict(self):
        """The check as a dict (JSON-ready)."""
        return {
            "worst [-]": float(self.worst),
            "tolerance [-]": float(self.tolerance),
            "scale": self.scale,
            "at [s]": None if math.isnan(self.at) else float(self.at),
            "passed": self.passed,
            "model_property": self.model_property,
        }

    def describe(self):
        """One line: name, worst value, tolerance, scale and time."""
        when = "" if math.isnan(self.at) else f" at t = {self.at:.6g} s"
        return (
            f"{self.name}: {self.worst:.3g} of the {self.scale} (tolerance "
            f"{self.tolerance:.3g}){when}"
        )


@dataclass(frozen=True)
class Audit:
    """An energy ledger (or None for the cheap audit) and the checks of one result."""

    ledger: EnergyLedger | None
    checks: tuple

    def __getitem__(self, name):
        """The check called ``name``."""
        for check in self.checks:
            if check.name == name:
                return check
        raise KeyError(f"no check {name!r}; this audit has {[c.name for c in self.checks]}")

    @property
    def failures(self):
        """Checks broken beyond tolerance that the model does not allow."""
        return [c for c in self.checks if c.failed]

    @property
    def ok(self):
        """Whether no check failed (:attr:`failures` is empty)."""
        return not self.failures

    def as_dict(self):
        """Ledger and checks as a dict (JSON-ready)."""
        return {
            "energy_ledger": None if self.ledger is None else self.ledger.as_dict(),
            "checks": {c.name: c.as_dict() for c in self.checks},
            "ok": self.ok,
        }


def energy_check(ledger, tolerance, model_property=""):
    """The ``energy`` check of a ledger: what the bodies hold after the contact over what
    came in, minus one [-] (> 0: energy created). No model allows a non-finite energy
    (an overflow in the solution): it always fails."""
    gain = (ledger.kinetic_out - ledger.kinetic_in) / ledger.kinetic_in
    allowed = model_property if math.isfinite(gain) else ""
    return Check(
        "energy",
        gain if math.isfinite(gain) else math.inf,
        tolerance,
        "impact energy",
        math.nan,
        allowed,
    )


def warn_if_broken(audit, what, stacklevel=3):
    """Issue one :class:`~contactlab.errors.AuditWarning` naming every failed check."""
    if audit.ok:
        return
    lines = "; ".join(c.describe() for c in audit.failures)
    warnings.warn(f"{what} breaks a physical invariant: {lines}", AuditWarning, stacklevel)


def elastic_energy(law, overlap):
    """Elastic energy ``integral_0^d N(x, 0) dx`` [J] of a law without history at overlap
    ``d`` [m] (0 for ``d <= 0`` and for laws with history, whose unloading branches end at
    zero force with nothing stored)."""
    if overlap <= 0.0 or law.has_history or law.prescribed:
        return 0.0
    nodes, weights = gauss_rule(0.0, overlap, graded=True)
    return float(weights @ law.force(nodes, 0.0))


def worst_of(values, times):
    """(largest value, its time) of an array on a matching time array (``-inf``, nan if
    empty)."""
    if values.size == 0:
        return -math.inf, math.nan
    i = int(np.argmax(values))
    return float(values[i]), float(times[i])
