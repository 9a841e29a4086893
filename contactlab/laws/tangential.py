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
``"force"`` history (:class:`Mindlin` ``history="incremental"`` or
``"incremental_rescaled"``)
    ``h`` is the elastic tangential force [N]; ``h' = -kt(d) s`` while the contact sticks
    (plus ``h d'/(2 d)`` while the overlap shrinks, for ``"incremental_rescaled"``) and
    ``F = h - eta s``.

``eta`` [N*s/m] is the tangential damping coefficient: a constant for
:class:`TangentialSpring`, ``2 gamma sqrt(m* kt(d))`` for :class:`Mindlin`
``damping="tied"`` (``gamma`` the normal law's damping ratio, bound by the solver through
:meth:`TangentialLaw.for_contact`), zero otherwise.

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

from contactlab.analytic.materials import RIGID_FLAT, Material
from contactlab.analytic.tangential import (
    effective_shear_modulus,
    mindlin_stiffness_coefficient,
)
from contactlab.entry_checks import check_instance
from contactlab.errors import ParameterError
from contactlab.laws.base import ContactLaw, stated
from contactlab.laws.tangential_form import TangentialForm
from contactlab.validation import KeywordChecked, check_choice, check_number, numbers_checked

__all__ = [
    "COULOMB_CAPS",
    "DAMPING_FORMS",
    "HISTORY_FORMS",
    "Mindlin",
    "TangentialForm",
    "TangentialLaw",
    "TangentialSpring",
    "damping_ratio",
    "mindlin_stiffness",
]

HISTORY_FORMS = ("total", "incremental", "incremental_rescaled")
"""Values of ``Mindlin(history=...)``: LAMMPS' ``mindlin``, ``mindlin/force`` and
``mindlin_rescale/force`` (Kratos' ``DEM_D_Hertz_viscous_Coulomb``)."""

DAMPING_FORMS = ("none", "tied")
"""Values of ``Mindlin(damping=...)``: no tangential damping (LAMMPS ``xgamma_t = 0``), or
``2 gamma sqrt(m* kt)`` with the normal law's damping ratio ``gamma`` (Kratos, EDEM)."""

COULOMB_CAPS = ("total", "elastic")
"""Values of ``Mindlin(coulomb_cap=...)``: the total force (elastic + viscous) scaled to
``mu N`` and the history rescaled to match (LAMMPS), or the elastic force alone capped at
``mu N`` with the viscous part cut to what is left (Kratos)."""


@numbers_checked()
def mindlin_stiffness(overlap, k_mindlin):
    """Mindlin tangential stiffness ``kt = k_mindlin sqrt(d) = 8 G* a`` [N/m] (0 for d <= 0).

    Parameters
    ----------
    overlap : array_like
        Normal overlap ``d`` [m].
    k_mindlin : float
        ``8 G* sqrt(R*)`` [N/m**1.5].
    """
    return _mindlin_stiffness(np.asarray(overlap, dtype=float), k_mindlin)


def _mindlin_stiffness(overlap, k_mindlin):
    return k_mindlin * np.sqrt(np.maximum(overlap, 0.0))


def check_contact(normal_law, mass):
    """Check the arguments of :meth:`TangentialLaw.for_contact`: a normal contact law and a
    grain mass [kg]."""
    if not isinstance(normal_law, ContactLaw):
        raise ParameterError(
            f"normal_law must be a contact law of contactlab.laws; got {type(normal_law).__name__}"
        )
    check_number("mass", mass, low=0.0, unit="kg")


class TangentialLaw(KeywordChecked):
    """Base class of tangential laws (see the module docstring for the conventions).

    Subclasses set ``friction`` [-], ``damping`` [N*s/m], ``history_kind`` and define
    :meth:`stiffness` and :meth:`stiffness_slope`; the rest follows here. The solver calls
    these methods with Python floats.
    """

    history_kind: ClassVar[str] = "displacement"
    """``"displacement"`` [m] or ``"force"`` [N]: what the history variable holds."""

    coulomb_cap = "total"
    """What ``mu N`` caps (:data:`COULOMB_CAPS`); ``"total"`` unless a law says otherwise."""

    def stiffness(self, overlap):
        """Tangential stiffness ``kt`` [N/m] at overlap ``d`` [m]."""
        raise NotImplementedError

    def stiffness_slope(self, overlap):
        """``dkt/dd`` [N/m**2] at overlap ``d`` [m]."""
        raise NotImplementedError

    def damping_coefficient(self, overlap):
        """Tangential damping coefficient ``eta`` [N*s/m] at overlap ``d`` [m]."""
        return self.damping

    def damping_slope(self, overlap):
        """``d eta / dd`` [N*s/m**2] at overlap ``d`` [m]."""
        return 0.0

    def for_contact(self, normal_law, mass):
        """This law as the solver applies it beside ``normal_law`` on a grain of ``mass``
        [kg] (a law whose damping is tied to the normal law binds it here)."""
        check_contact(normal_law, mass)
        return self

    def elastic_force(self, history, overlap):
        """The elastic part of the tangential force [N] at history ``h``, overlap ``d`` [m]."""
        if self.history_kind == "force":
            return history
        return -self.stiffness(overlap) * history

    def history_of(self, elastic, overlap):
        """The history whose elastic force is ``elastic`` [N] at overlap ``d`` [m] (zero
        where the stiffness vanishes, at the touch of a Mindlin contact)."""
        if self.history_kind == "force":
            return elastic
        kt = self.stiffness(overlap)
        return 0.0 if kt == 0.0 else -elastic / kt

    def trial_force(self, history, overlap, slip):
        """Tangential force [N] before the Coulomb cap."""
        return self.elastic_force(history, overlap) - self.damping_coefficient(overlap) * slip

    def history_rate(self, history, overlap, overlap_rate, slip):
        """``h'`` [m/s or N/s] while the contact sticks, at history ``h``, overlap ``d``
        [m], overlap rate ``d'`` [m/s] and slip ``s`` [m/s]."""
        if self.history_kind == "force":
            return -self.stiffness(overlap) * slip
        return slip

    def elastic_force_rate(self, history, overlap, overlap_rate, slip):
        """Time derivative of :meth:`elastic_force` along a sticking path [N/s]."""
        if self.history_kind == "force":
            return self.history_rate(history, overlap, overlap_rate, slip)
        kt_rate = self.stiffness_slope(overlap) * overlap_rate
        return -self.stiffness(overlap) * slip - kt_rate * history

    def trial_force_rate(self, history, overlap, overlap_rate, slip, slip_rate):
        """Time derivative of :meth:`trial_force` along a sticking path [N/s]."""
        elastic = self.elastic_force_rate(history, overlap, overlap_rate, slip)
        damping = self.damping_coefficient(overlap) * slip_rate
        damping += self.damping_slope(overlap) * overlap_rate * slip
        return elastic - damping

    def form(self):
        """This law as a :class:`TangentialForm` (bound laws only: :meth:`for_contact`)."""
        raise NotImplementedError

    def history_on_cap(self, force, overlap, slip):
        """History that makes the trial force equal ``force`` [N] (LAMMPS' rescaling).

        Zero where the stiffness vanishes (at the touch of a Mindlin contact).
        """
        return self.history_of(force + self.damping_coefficient(overlap) * slip, overlap)

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

    def form(self):
        return TangentialForm(self.friction, self.k, 0.0, self.damping, 0.0, False, False)


class Mindlin(TangentialLaw):
    """Mindlin tangential contact ``kt = 8 G* a``, ``a = sqrt(R* d)``, capped at ``mu N``.

    Parameters
    ----------
    k_mindlin : float
        ``8 G* sqrt(R*)`` [N/m**1.5], so that ``kt = k_mindlin sqrt(d)`` [N/m].
    friction : float
        Coulomb friction coefficient ``mu`` [-], >= 0.
    history : {"total", "incremental", "incremental_rescaled"}
        ``"total"``: ``F = -kt(d) h`` on the total elastic displacement ``h`` (``h' = s``),
        so the force follows the contact radius at once when the overlap changes: LAMMPS'
        ``tangential mindlin`` and EDEM's Hertz-Mindlin (no slip). ``"incremental"``:
        ``F = h``, ``h' = -kt(d) s``, so only new displacement is loaded with the current
        stiffness: LAMMPS' ``tangential mindlin/force`` (Thornton et al. 2013, Eq. 18).
        ``"incremental_rescaled"``: the incremental form whose stored force is scaled by
        the ratio of contact radii ``sqrt(d / d_prev)`` while the overlap shrinks, i.e.
        ``h' = -kt(d) s + h d' / (2 d)`` while ``d' < 0``: LAMMPS'
        ``mindlin_rescale/force`` and Kratos' ``DEM_D_Hertz_viscous_Coulomb``
        (``minoring_factor`` in ``CalculateTangentialForceWithNeighbour``).
        In every form, a trial force above ``mu N`` is scaled down to ``mu N`` and the
        history rescaled to match (LAMMPS' ``gran_sub_mod_tangential.cpp``).
    damping : {"none", "tied"}
        ``"none"``: no tangential damping (LAMMPS' ``xgamma_t = 0``). ``"tied"``: a viscous
        force ``-2 gamma sqrt(m* kt(d)) s`` whose ratio ``gamma`` is the normal law's
        (:func:`damping_ratio`; Kratos' ``CalculateViscoDampingForceWithFEM``, EDEM's
        ``2 sqrt(5/6) beta sqrt(S_t m*)``). The solver binds ``gamma`` and ``m*`` through
        :meth:`for_contact`; it is zero beside an elastic normal law. With
        ``history="total"`` it is refused beside a damped normal law (``gamma > 0``): the
        sliding history ``-(mu N + eta s) / kt`` is unbounded at the touch and the solver
        cannot decide the phase there (LIGGGHTS' ``tangential history`` with
        ``tangential_damping on``; not run here).
    coulomb_cap : {"total", "elastic"}
        What ``mu N`` caps once the trial force exceeds it; the two differ only with a
        tangential damping. ``"total"``: the total force (elastic + viscous) is scaled to
        ``mu N`` and the history rescaled so that the trial force equals it (LAMMPS'
        ``gran_sub_mod_tangential.cpp``). ``"elastic"``: the force is ``mu N``, the elastic
        part is kept while it is below ``mu N`` (the viscous part takes the rest) and held
        at ``mu N`` once it reaches it (the viscous part dropped): Kratos'
        ``CalculateTangentialForceWithNeighbour`` (``if (dot_product >= 0.0)`` and its
        ``else``, ``DEM_D_Hertz_viscous_Coulomb_CL.cpp``), taken to a vanishing step.

    Notes
    -----
    Neither form is exactly Mindlin-Deresiewicz partial slip (an annulus slipping inside
    the contact); all are the single-spring simplifications DEM codes use, whose rebounds
    Chung & Ooi (2011) compare with Maw et al. (1976). Which DEM code uses which form:
    ``docs/dem-conventions.md``.

    References
    ----------
    Mindlin R.D. (1949) J. Appl. Mech. 16, 259-268.
    Thornton C., Cummins S.J., Cleary P.W. (2013) Powder Technol. 233, 30-46.
    DOI 10.1016/j.powtec.2012.08.012
    LAMMPS pair_style granular documentation and src/GRANULAR/gran_sub_mod_tangential.cpp
    (GranSubModTangentialMindlin::calculate_forces).
    Kratos DEMApplication, custom_constitutive/DEM_D_Hertz_viscous_Coulomb_CL.cpp.
    """

    name = "mindlin"

    def __init__(self, k_mindlin, friction, history="total", damping="none", coulomb_cap="total"):
        self.k_mindlin = check_number("k_mindlin", k_mindlin, low=0.0, unit="N/m**1.5")
        self.friction = _friction(friction)
        self.history = check_choice("history", history, HISTORY_FORMS)
        self.damping_form = check_choice("damping", damping, DAMPING_FORMS)
        self.coulomb_cap = check_choice("coulomb_cap", coulomb_cap, COULOMB_CAPS)
        self.history_kind = "displacement" if self.history == "total" else "force"
        self._params = {
            "k_mindlin": self.k_mindlin,
            "friction": self.friction,
            "history": self.history,
        }
        if self.damping_form != "none":  # the parameters of the untied law stay as they were
            self._params["damping"] = self.damping_form
        if self.coulomb_cap != "total":
            self._params["coulomb_cap"] = self.coulomb_cap
        self._tied = 0.0  # 2 gamma sqrt(m* k_mindlin) [N*s/m**1.25], bound by for_contact

    def for_contact(self, normal_law, mass):
        """This law with its tied damping bound to ``normal_law`` and the grain's ``mass``
        [kg] (itself when ``damping="none"``).

        Raises
        ------
        ParameterError
            If ``damping="tied"`` and the normal law has no damping ratio
            (:func:`damping_ratio`), or with ``history="total"`` beside a damped normal
            law (see the class docstring).
        """
        check_contact(normal_law, mass)
        if self.damping_form == "none":
            return self
        bound = Mindlin(
            self.k_mindlin, self.friction, self.history, self.damping_form, self.coulomb_cap
        )
        gamma = damping_ratio(normal_law, mass)
        if self.history == "total" and gamma > 0.0:
            raise ParameterError(
                f"tangential_law history='total' with damping='tied' beside a damped normal "
                f"law (gamma = {gamma:.3g}) is not supported: the law is defined (LIGGGHTS' "
                "tangential history with tangential_damping on), but its sliding history "
                "-(mu N + eta s)/kt grows without bound at the touch (kt ~ d**0.5 while eta s "
                "and N ~ d**0.25), so the solver cannot decide the phase there; use "
                "history='incremental' or 'incremental_rescaled' with damping='tied', or an "
                "elastic normal law (gamma = 0: no tangential damping)"
            )
        bound._tied = 2.0 * gamma * math.sqrt(mass * self.k_mindlin)
        return bound

    def damping_coefficient(self, overlap):
        """``2 gamma sqrt(m* kt(d))`` [N*s/m] once bound (:meth:`for_contact`), else 0."""
        if self._tied == 0.0:
            return 0.0
        if isinstance(overlap, float):
            return self._tied * math.sqrt(math.sqrt(overlap)) if overlap > 0.0 else 0.0
        return self._tied * np.sqrt(np.sqrt(np.maximum(overlap, 0.0)))

    def damping_slope(self, overlap):
        if self._tied == 0.0 or overlap <= 0.0:
            return 0.0
        return 0.25 * self._tied * overlap**-0.75

    def history_rate(self, history, overlap, overlap_rate, slip):
        if self.history == "total":
            return slip
        rate = -self.stiffness(overlap) * slip
        if self.history == "incremental_rescaled" and overlap_rate < 0.0 and overlap > 0.0:
            rate += history * overlap_rate / (2.0 * overlap)
        return rate

    @classmethod
    def from_material(
        cls,
        material,
        friction,
        other=RIGID_FLAT,
        history="total",
        damping="none",
        coulomb_cap="total",
    ):
        """Mindlin law of a sphere on a flat from material data; a rigid flat by default.

        Parameters
        ----------
        material : contactlab.analytic.Material
            The grain's Young's modulus [Pa], Poisson ratio [-] and radius [m] (``R*`` on
            a flat; :meth:`contactlab.Grain.material`).
        friction : float
            Coulomb friction coefficient [-].
        other : contactlab.analytic.Material, default RIGID_FLAT
            The flat's Young's modulus [Pa] (``inf`` is rigid) and Poisson ratio [-]; its
            radius must be ``inf``.
        history : {"total", "incremental", "incremental_rescaled"}
            See the class docstring.
        damping : {"none", "tied"}
            See the class docstring.
        coulomb_cap : {"total", "elastic"}
            See the class docstring.

        Raises
        ------
        ParameterError
            For a curved second body (``other.radius`` not ``inf``), or bad numbers.
        """
        grain = check_instance("material", material, Material, "Grain.material")
        flat = check_instance("other", other, Material)
        if flat.radius != math.inf:
            raise ParameterError(
                f"Mindlin.from_material is for a sphere on a flat: other.radius must be inf; "
                f"got {flat.radius!r}"
            )
        g_eff = effective_shear_modulus(*grain[:2], *flat[:2])
        radius = check_number("radius", grain.radius, low=0.0, unit="m")
        return cls(
            mindlin_stiffness_coefficient(g_eff, radius), friction, history, damping, coulomb_cap
        )

    def stiffness(self, overlap):
        if isinstance(overlap, float):  # the solver's scalar path
            return self.k_mindlin * math.sqrt(overlap) if overlap > 0.0 else 0.0
        return _mindlin_stiffness(overlap, self.k_mindlin)

    def stiffness_slope(self, overlap):
        return 0.5 * self.k_mindlin / math.sqrt(overlap) if overlap > 0.0 else 0.0

    def form(self):
        return TangentialForm(
            self.friction,
            self.k_mindlin,
            0.5,
            self._tied,
            0.25,
            self.history_kind == "force",
            self.history == "incremental_rescaled",
        )


def damping_ratio(normal_law, mass):
    """Damping ratio ``gamma`` [-] of a normal law on a grain of ``mass`` [kg] (``m*`` at a
    rigid wall), as Kratos defines it: the normal damping force is ``2 gamma sqrt(m* Kn)
    d'`` with ``Kn`` the normal tangent stiffness.

    Each law whose ratio is constant through the contact states it
    (``normal_law._damping_ratio(mass)``: Hertz, HertzDamped, LinearViscoelastic), so the
    tied tangential damping ``2 gamma sqrt(m* kt)`` is exactly Kratos'.

    Raises
    ------
    ParameterError
        For another normal law (its damping is not a constant ratio).
    """
    mass = check_number("mass", mass, low=0.0, unit="kg")
    ratio = stated(normal_law, "_damping_ratio")
    if ratio is None:
        from contactlab.laws import LAWS  # the registry imports this module

        have = ", ".join(cls.__name__ for cls in LAWS.values() if "_damping_ratio" in vars(cls))
        raise ParameterError(
            f"normal_law: tangential_law damping='tied' needs a normal law with a constant "
            f"damping ratio ({have}); got {type(normal_law).__name__}"
        )
    return ratio(mass)


TANGENTIAL_LAWS = {cls.name: cls for cls in (TangentialSpring, Mindlin)}
"""Registry: tangential law name -> class."""
