"""Closed forms of one impact on an immovable wall, per contact law: a registry.

:data:`CLOSED_FORMS` maps each law class of :mod:`contactlab.laws` to a function
``(law, mass, velocity) -> tuple of ClosedForm`` giving what is known in closed form for
that law: contact time, restitution and peak contact force where they exist, each with
the formula and its published source. All values assume the contact ends when the force
returns to zero (the convention of :func:`contactlab.simulate_impact`).

The lookup is by exact class: a subclass may change the force, so it does not inherit its
parent's closed forms. Register your own with :func:`register_closed_form`.
"""

import math
from collections.abc import Callable
from dataclasses import dataclass

from contactlab import analytic, laws
from contactlab.errors import ParameterError
from contactlab.quantities import QUANTITIES
from contactlab.validation import check_choice, check_number

__all__ = [
    "CLOSED_FORMS",
    "CLOSED_FORM_QUANTITIES",
    "ClosedForm",
    "NoClosedFormError",
    "closed_forms_for",
    "register_closed_form",
]

CLOSED_FORM_QUANTITIES = ("contact_time", "restitution", "peak_contact_force")
"""Quantities a closed form may give (attribute names of ImpactResult)."""

SCHWAGER_2007 = (
    "Schwager & Poeschel, Granular Matter 9, 465-469 (2007), DOI 10.1007/s10035-007-0065-z"
)
JOHNSON_1985 = (
    "Johnson, Contact Mechanics, Cambridge (1985), Sec. 11.1, DOI 10.1017/CBO9781139171731"
)
ANTYPOV_2011 = "Antypov & Elliott, EPL 94, 50004 (2011), DOI 10.1209/0295-5075/94/50004"
RAMIREZ_1999 = "Ramirez et al., Phys. Rev. E 60, 4465-4472 (1999), DOI 10.1103/PhysRevE.60.4465"
HUNT_CROSSLEY_1975 = "Hunt & Crossley, J. Appl. Mech. 42, 440-445 (1975), DOI 10.1115/1.3423596"
WALTON_BRAUN_1986 = "Walton & Braun, J. Rheol. 30, 949-980 (1986), DOI 10.1122/1.549893"
THORNTON_1997 = "Thornton, J. Appl. Mech. 64, 383-386 (1997), DOI 10.1115/1.2787319"
KESKA_2021 = "Keska et al., Appl. Sci. 11, 466 (2021), Eqs. (7)-(8), DOI 10.3390/app11020466"
ENERGY_BALANCE = "energy balance of the capped spring (contactlab.analytic, linear_plastic_*)"


@dataclass(frozen=True)
class ClosedForm:
    """One value known in closed form, with where it comes from.

    Attributes
    ----------
    quantity : str
        One of :data:`CLOSED_FORM_QUANTITIES`.
    value : float
        The closed-form value in SI units (s, -, N).
    formula : str
        The expression or function call that gives it, with its arguments.
    reference : str
        Published source (authors, journal, DOI).
    atol : float, default 0
        Absolute allowance the closed form needs on top of a relative tolerance, in the
        quantity's unit: the remainder of a truncated series, or a floor for an exact zero.
    atol_reason : str, default ""
        One line saying why ``atol`` is that size (required when ``atol > 0``).
    """

    quantity: str
    value: float
    formula: str
    reference: str
    atol: float = 0.0
    atol_reason: str = ""

    def __post_init__(self):
        check_choice("quantity", self.quantity, CLOSED_FORM_QUANTITIES)
        unit = QUANTITIES[self.quantity].unit
        object.__setattr__(self, "value", check_number("value", self.value, unit=unit))
        atol = check_number("atol", self.atol, low=0.0, low_open=False, unit=unit)
        object.__setattr__(self, "atol", atol)
        if atol > 0.0 and not self.atol_reason:
            raise ParameterError(f"ClosedForm({self.quantity}): atol = {atol:g} needs atol_reason")


class NoClosedFormError(ParameterError):
    """The law's class has no closed form registered; the message lists the ones that do."""


def _arguments(arguments):
    return ", ".join(
        f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v!r}" for k, v in arguments.items()
    )


def _analytic(quantity, function, reference, *, atol=0.0, atol_reason="", **arguments):
    """A ClosedForm from a function of :mod:`contactlab.analytic` called with ``arguments``."""
    value = function(**arguments)
    formula = f"contactlab.analytic.{function.__name__}({_arguments(arguments)})"
    return ClosedForm(quantity, value, formula, reference, atol, atol_reason)


def _linear_viscoelastic(law, mass, velocity):
    args = dict(stiffness=law.stiffness, damping=law.damping, mass=mass, convention="force")
    return (
        _analytic("contact_time", analytic.linear_contact_time, SCHWAGER_2007, **args),
        _analytic("restitution", analytic.linear_restitution, SCHWAGER_2007, **args),
    )


def _hertz(law, mass, velocity):
    args = dict(k_hertz=law.k_hertz, mass=mass, velocity=velocity)
    return (
        _analytic("contact_time", analytic.hertz_contact_time, JOHNSON_1985, **args),
        _analytic("peak_contact_force", analytic.hertz_max_force, JOHNSON_1985, **args),
        ClosedForm("restitution", 1.0, "1 (elastic: no dissipation)", JOHNSON_1985),
    )


def _hertz_damped(law, mass, velocity):
    alpha = law.damping / math.sqrt(mass * law.k_hertz)
    return (
        _analytic(
            "restitution",
            analytic.tsuji_restitution,
            ANTYPOV_2011,
            alpha=alpha,
            convention="force",
        ),
    )


def _kuwabara_kono(law, mass, velocity):
    args = dict(k_hertz=law.k_hertz, dissipation=law.dissipation, mass=mass, velocity=velocity)
    x = analytic.kuwabara_kono_parameter(**args)
    return (
        _analytic(
            "restitution",
            analytic.kuwabara_kono_restitution,
            RAMIREZ_1999,
            atol=0.5 * x**2.5,
            atol_reason=(
                f"0.5 x**2.5 (x = {x:.4g}): the two-term series leaves an O(x**2.5) "
                "remainder at the force-zero end (measured 0.24 x**2.5)"
            ),
            **args,
        ),
    )


def _hunt_crossley(law, mass, velocity):
    return (
        _analytic(
            "restitution",
            analytic.hunt_crossley_restitution,
            HUNT_CROSSLEY_1975,
            damping=law.damping,
            velocity=velocity,
        ),
    )


def _walton_braun(law, mass, velocity):
    args = dict(
        loading_stiffness=law.loading_stiffness, unloading_stiffness=law.unloading_stiffness
    )
    return (
        _analytic("restitution", analytic.walton_braun_restitution, WALTON_BRAUN_1986, **args),
        _analytic(
            "contact_time",
            analytic.walton_braun_contact_time,
            WALTON_BRAUN_1986,
            mass=mass,
            **args,
        ),
    )


def _linear_plastic(law, mass, velocity):
    args = dict(stiffness=law.stiffness, yield_force=law.yield_force, mass=mass, velocity=velocity)
    elastic_peak = velocity * math.sqrt(law.stiffness * mass)
    return (
        _analytic("restitution", analytic.linear_plastic_restitution, ENERGY_BALANCE, **args),
        _analytic("contact_time", analytic.linear_plastic_contact_time, ENERGY_BALANCE, **args),
        ClosedForm(
            "peak_contact_force",
            min(law.yield_force, elastic_peak),
            f"min(Fy, v sqrt(k m*)) = min({law.yield_force:.6g}, {elastic_peak:.6g})",
            ENERGY_BALANCE,
        ),
    )


def _thornton(law, mass, velocity):
    return (
        _analytic(
            "restitution",
            analytic.thornton_restitution,
            THORNTON_1997,
            effective_modulus=law.effective_modulus,
            effective_radius=law.effective_radius,
            yield_pressure=law.yield_pressure,
            mass=mass,
            velocity=velocity,
        ),
    )


def _plastic_trapezoid(law, mass, velocity):
    return (
        _analytic(
            "peak_contact_force",
            analytic.plastic_trapezoid_amplitude,
            KESKA_2021,
            mass=mass,
            velocity=velocity,
            contact_time=law.contact_time,
            ramp_time=law.ramp_time,
        ),
        ClosedForm("contact_time", law.contact_time, "t_k (the prescribed duration)", KESKA_2021),
        ClosedForm(
            "restitution",
            0.0,
            "0 (the impulse equals the grain's momentum m v)",
            KESKA_2021,
            atol=1e-12,
            atol_reason="an exact zero has no relative scale; 1e-12 is 1e4 times the roundoff",
        ),
    )


CLOSED_FORMS: dict[type, Callable] = {
    laws.LinearViscoelastic: _linear_viscoelastic,
    laws.Hertz: _hertz,
    laws.HertzDamped: _hertz_damped,
    laws.KuwabaraKono: _kuwabara_kono,
    laws.HuntCrossley: _hunt_crossley,
    laws.WaltonBraun: _walton_braun,
    laws.LinearPlastic: _linear_plastic,
    laws.Thornton: _thornton,
    laws.PlasticTrapezoid: _plastic_trapezoid,
}
"""Registry: law class -> ``function(law, mass [kg], velocity [m/s]) -> tuple of ClosedForm``."""


def register_closed_form(law_class, function):
    """Register the closed forms of a law class (e.g. your own law) for the assertions.

    Parameters
    ----------
    law_class : type
        The law's class; lookup is by exact class, so subclasses need their own entry.
    function : callable
        ``function(law, mass, velocity)`` returning an iterable of :class:`ClosedForm`
        for an impact of a grain of ``mass`` [kg] at ``velocity`` [m/s] on an immovable
        wall, contact ending when the force returns to zero.

    Returns
    -------
    callable
        ``function``, unchanged.
    """
    if not isinstance(law_class, type):
        raise ParameterError(f"law_class must be a class; got {law_class!r}")
    if not callable(function):
        raise ParameterError(f"function must be callable; got {function!r}")
    CLOSED_FORMS[law_class] = function
    return function


def closed_forms_for(law, mass, velocity):
    """Closed forms of an impact of ``law`` on an immovable wall.

    Parameters
    ----------
    law : ContactLaw or PlasticTrapezoid
        A law whose class is in :data:`CLOSED_FORMS`.
    mass : float
        Grain mass [kg] (the effective mass on an immovable wall).
    velocity : float
        Impact speed [m/s].

    Returns
    -------
    tuple of ClosedForm

    Raises
    ------
    NoClosedFormError
        If no closed form is registered for the law's class, or the function gave none.
    """
    check_number("mass", mass, low=0.0, unit="kg")
    check_number("velocity", velocity, low=0.0, unit="m/s")
    function = CLOSED_FORMS.get(type(law))
    if function is None:
        known = ", ".join(sorted(cls.__name__ for cls in CLOSED_FORMS))
        raise NoClosedFormError(
            f"no closed form is registered for {type(law).__name__} (closed forms are not "
            f"inherited: a subclass may change the force). Laws with closed forms: {known}. "
            "Register one with contactlab.testing.register_closed_form(law_class, function), "
            "or give the expected values to assert_restitution / assert_contact_time."
        )
    forms = tuple(function(law, mass, velocity))
    if not forms:
        raise NoClosedFormError(
            f"the closed-form function of {type(law).__name__} gave no closed form for {law!r}"
        )
    return forms
