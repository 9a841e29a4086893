"""Tangential contact laws: a history spring capped by Coulomb friction.

Sign convention (stated once)
-----------------------------
``slip`` ``s`` [m/s] is the velocity of the grain's contact point along the flat relative
to the flat (for a sphere, ``s = vt - R spin``). The tangential force ``F`` [N] acts on the
grain along the same axis; it opposes the accumulated slip and never exceeds the Coulomb
limit ``|F| <= mu N``, with ``N >= 0`` the normal contact force.

Each law keeps one history variable ``h`` per contact, reset to zero at every touch:

``"displacement"`` history (:class:`TangentialSpring`, :class:`Mindlin` ``history="total"``)
    ``h`` is the elastic tangential displacement [m]; ``h' = s`` while the contact sticks
    and ``F = -kt(d) h - eta s``.
``"force"`` history (:class:`Mindlin` ``history="incremental"``)
    ``h`` is the elastic tangential force [N]; ``h' = -kt(d) s`` while the contact sticks
    and ``F = h - eta s``.

When the trial force would exceed ``mu N`` the contact slides: ``F = +-mu N`` and the
history is rescaled so that the trial force equals it (:meth:`TangentialLaw.history_on_cap`).
These are the update rules of LAMMPS' GRANULAR package (``gran_sub_mod_tangential.cpp``:
history increment, then Coulomb rescaling of history and force), taken to the limit of a
vanishing time step; the solver (:func:`contactlab.simulate_oblique`) follows them exactly,
with the switches between sticking and sliding located as events.

References
----------
Cundall P.A., Strack O.D.L. (1979) Geotechnique 29, 47-65. DOI 10.1680/geot.1979.29.1.47
Mindlin R.D. (1949) J. Appl. Mech. 16, 259-268.
Thornton C., Cummins S.J., Cleary P.W. (2013) Powder Technol. 233, 30-46 (incremental form).
LAMMPS documentation, pair_style granular: tangential ``linear_history``, ``mindlin``,
``mindlin/force``. https://docs.lammps.org/pair_granular.html
"""

import math
from typing import ClassVar

import numpy as np

from contactlab.analytic.tangential import (
    effective_shear_modulus,
    mindlin_stiffness_coefficient,
)
from contactlab.validation import KeywordChecked, check_choice, check_number

__all__ = ["HISTORY_FORMS", "Mindlin", "TangentialLaw", "TangentialSpring", "mindlin_stiffness"]

HISTORY_FORMS = ("total", "incremental")
"""Values of ``Mindlin(history=...)``: LAMMPS' ``mindlin`` and ``mindlin/force``."""


def mindlin_stiffness(overlap, k_mindlin):
    """Mindlin tangential stiffness ``kt = k_mindlin sqrt(d) = 8 G* a`` [N/m] (0 for d <= 0).

    Parameters
    ----------
    overlap : array_like
        Normal overlap ``d`` [m].
    k_mindlin : float
        ``8 G* sqrt(R*)`` [N/m**1.5].
    """
    overlap = np.asarray(overlap, dtype=float)
    return k_mindlin * np.sqrt(np.maximum(overlap, 0.0))


class TangentialLaw(KeywordChecked):
    """Base class of tangential laws (see the module docstring for the conventions).

    Subclasses set ``friction`` [-], ``damping`` [N*s/m], ``history_kind`` and define
    :meth:`stiffness` and :meth:`stiffness_slope`; the rest follows here. The solver calls
    these methods with Python floats.
    """

    history_kind: ClassVar[str] = "displacement"
    """``"displacement"`` [m] or ``"force"`` [N]: what the history variable holds."""

    def stiffness(self, overlap):
        """Tangential stiffness ``kt`` [N/m] at overlap ``d`` [m]."""
        raise NotImplementedError

    def stiffness_slope(self, overlap):
        """``dkt/dd`` [N/m**2] at overlap ``d`` [m]."""
        raise NotImplementedError

    def trial_force(self, history, overlap, slip):
        """Tangential force [N] before the Coulomb cap."""
        if self.history_kind == "force":
            return history - self.damping * slip
        return -self.stiffness(overlap) * history - self.damping * slip

    def history_rate(self, overlap, slip):
        """``h'`` while the contact sticks [m/s or N/s]."""
        if self.history_kind == "force":
            return -self.stiffness(overlap) * slip
        return slip

    def trial_force_rate(self, history, overlap, overlap_rate, slip, slip_rate):
        """Time derivative of :meth:`trial_force` along a sticking path [N/s]."""
        elastic = -self.stiffness(overlap) * slip
        if self.history_kind == "displacement":
            elastic -= self.stiffness_slope(overlap) * overlap_rate * history
        return elastic - self.damping * slip_rate

    def history_on_cap(self, force, overlap, slip):
        """History that makes the trial force equal ``force`` [N] (LAMMPS' rescaling).

        Zero where the stiffness vanishes (at the touch of a Mindlin contact).
        """
        if self.history_kind == "force":
            return force + self.damping * slip
        kt = self.stiffness(overlap)
        return 0.0 if kt == 0.0 else -(force + self.damping * slip) / kt

    def parameters(self):
        """Parameters as a dict (name -> value)."""
        return dict(self._params)

    def __repr__(self):
        args = ", ".join(
            f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v!r}"
            for k, v in self._params.items()
        )
        return f"{type(self).__name__}({args})"

    def __eq__(self, other):
        return type(self) is type(other) and self._params == other._params

    def __hash__(self):
        return hash((type(self), tuple(self._params.items())))


def _friction(value):
    return check_number("friction", value, low=0.0, low_open=False)


class TangentialSpring(TangentialLaw):
    """Cundall-Strack tangential spring: ``F = -k h - eta s``, capped at ``mu N``.

    Parameters
    ----------
    stiffness : float
        Tangential stiffness ``k`` [N/m], > 0.
    friction : float
        Coulomb friction coefficient ``mu`` [-], >= 0.
    damping : float, default 0
        Tangential damping ``eta`` [N*s/m], >= 0.

    Notes
    -----
    ``h`` is the tangential displacement accumulated since the touch (``h' = s`` while
    sticking); when ``|F| > mu N`` the history is set to ``-(F_cap + eta s) / k``. This is
    LAMMPS' ``tangential linear_history k xgamma_t mu`` with a constant damping
    ``eta = xgamma_t * damp_prefactor``, and LIGGGHTS' ``tangential history``.

    References
    ----------
    Cundall P.A., Strack O.D.L. (1979) Geotechnique 29, 47-65. DOI 10.1680/geot.1979.29.1.47
    """

    name = "tangential_spring"

    def __init__(self, stiffness, friction, damping=0.0):
        self.k = check_number("stiffness", stiffness, low=0.0, unit="N/m")
        self.friction = _friction(friction)
        self.damping = check_number("damping", damping, low=0.0, low_open=False, unit="N*s/m")
        self._params = {"stiffness": self.k, "friction": self.friction, "damping": self.damping}

    def stiffness(self, overlap):
        return self.k

    def stiffness_slope(self, overlap):
        return 0.0


class Mindlin(TangentialLaw):
    """Mindlin tangential contact ``kt = 8 G* a``, ``a = sqrt(R* d)``, capped at ``mu N``.

    Parameters
    ----------
    k_mindlin : float
        ``8 G* sqrt(R*)`` [N/m**1.5], so that ``kt = k_mindlin sqrt(d)`` [N/m].
    friction : float
        Coulomb friction coefficient ``mu`` [-], >= 0.
    history : {"total", "incremental"}
        ``"total"``: ``F = -kt(d) h`` on the total elastic displacement ``h`` (``h' = s``),
        so the force follows the contact radius at once when the overlap changes: LAMMPS'
        ``tangential mindlin`` and EDEM's Hertz-Mindlin (no slip). ``"incremental"``:
        ``F = h``, ``h' = -kt(d) s``, so only new displacement is loaded with the current
        stiffness: LAMMPS' ``tangential mindlin/force`` (Thornton et al. 2013, Eq. 18).
        In both, a trial force above ``mu N`` is scaled down to ``mu N`` and the history
        rescaled to match (LAMMPS' ``gran_sub_mod_tangential.cpp``).

    Notes
    -----
    Neither form is exactly Mindlin-Deresiewicz partial slip (an annulus slipping inside
    the contact); both are the single-spring simplifications DEM codes use, whose rebounds
    Chung & Ooi (2011) compare with Maw et al. (1976). No tangential damping: LAMMPS'
    ``xgamma_t = 0``.

    References
    ----------
    Mindlin R.D. (1949) J. Appl. Mech. 16, 259-268.
    Thornton C., Cummins S.J., Cleary P.W. (2013) Powder Technol. 233, 30-46.
    DOI 10.1016/j.powtec.2012.08.012
    LAMMPS pair_style granular documentation and src/GRANULAR/gran_sub_mod_tangential.cpp
    (GranSubModTangentialMindlin::calculate_forces).
    """

    name = "mindlin"
    damping = 0.0

    def __init__(self, k_mindlin, friction, history="total"):
        self.k_mindlin = check_number("k_mindlin", k_mindlin, low=0.0, unit="N/m**1.5")
        self.friction = _friction(friction)
        self.history = check_choice("history", history, HISTORY_FORMS)
        self.history_kind = "displacement" if self.history == "total" else "force"
        self._params = {
            "k_mindlin": self.k_mindlin,
            "friction": self.friction,
            "history": self.history,
        }

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        friction,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        history="total",
    ):
        """Mindlin law of a sphere on a flat from material data; a rigid flat by default.

        Parameters
        ----------
        youngs_modulus, poisson_ratio : float
            The grain's Young's modulus [Pa] and Poisson ratio [-].
        radius : float
            The grain's radius [m] (``R*`` on a flat).
        friction : float
            Coulomb friction coefficient [-].
        other_youngs_modulus, other_poisson_ratio : float
            The flat's [Pa, -]; ``inf`` is rigid.
        history : {"total", "incremental"}
            See the class docstring.
        """
        g_eff = effective_shear_modulus(
            youngs_modulus, poisson_ratio, other_youngs_modulus, other_poisson_ratio
        )
        radius = check_number("radius", radius, low=0.0, unit="m")
        return cls(mindlin_stiffness_coefficient(g_eff, radius), friction, history)

    def stiffness(self, overlap):
        if isinstance(overlap, float):  # the solver's scalar path
            return self.k_mindlin * math.sqrt(overlap) if overlap > 0.0 else 0.0
        return mindlin_stiffness(overlap, self.k_mindlin)

    def stiffness_slope(self, overlap):
        return 0.5 * self.k_mindlin / math.sqrt(overlap) if overlap > 0.0 else 0.0


TANGENTIAL_LAWS = {cls.name: cls for cls in (TangentialSpring, Mindlin)}
"""Registry: tangential law name -> class."""
