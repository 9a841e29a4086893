"""Closed forms of one impact on an immovable wall, per contact law: a registry.

Each law states its own closed forms (``law._closed_forms(mass, velocity)``, in its module
of :mod:`contactlab.laws`: contact time, restitution and peak contact force where they
exist, each with the formula and its published source). :data:`CLOSED_FORMS` is the view
the assertions look up: law class -> ``function(law, mass, velocity)``, filled from every
law of :data:`contactlab.laws.LAWS` that defines them, and extended for your own laws with
:func:`register_closed_form`. All values assume the contact ends when the force returns to
zero (the convention of :func:`contactlab.simulate_impact`).

The lookup is by exact class: a subclass may change the force, so it does not inherit its
parent's closed forms.
"""

from collections.abc import Callable

from contactlab.errors import ParameterError
from contactlab.laws import LAWS
from contactlab.laws.closed_form import CLOSED_FORM_QUANTITIES, ClosedForm
from contactlab.validation import check_number

__all__ = [
    "CLOSED_FORMS",
    "CLOSED_FORM_QUANTITIES",
    "ClosedForm",
    "NoClosedFormError",
    "closed_forms_for",
    "register_closed_form",
]


class NoClosedFormError(ParameterError):
    """The law's class has no closed form registered; the message lists the ones that do."""


CLOSED_FORMS: dict[type, Callable] = {
    cls: cls._closed_forms for cls in LAWS.values() if "_closed_forms" in vars(cls)
}
"""Registry: law class -> ``function(law, mass [kg], velocity [m/s]) -> tuple of ClosedForm``
(the law's own ``closed_forms`` for every registered law that states them)."""


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
