"""What a law's impact on an immovable wall gives in closed form: :class:`ClosedForm`.

A law states its own closed forms (``law._closed_forms(mass, velocity)``, each a value of
:mod:`contactlab.analytic` with its formula and published source); the testing plug-in
(:func:`contactlab.testing.closed_forms_for`), the audit matrix and the study read them
there. All values assume the contact ends when the force returns to zero (the convention
of :func:`contactlab.simulate_impact`).
"""

from dataclasses import dataclass

from contactlab.errors import ParameterError
from contactlab.laws.base import stated
from contactlab.quantities import QUANTITIES
from contactlab.validation import check_choice, check_number

__all__ = ["CLOSED_FORM_QUANTITIES", "ClosedForm"]

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


def _arguments(arguments):
    return ", ".join(
        f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v!r}" for k, v in arguments.items()
    )


def closed_form(quantity, function, reference, *, atol=0.0, atol_reason="", **arguments):
    """A :class:`ClosedForm` from a function of :mod:`contactlab.analytic` called with
    ``arguments`` (its formula names the function and the arguments)."""
    value = function(**arguments)
    formula = f"contactlab.analytic.{function.__name__}({_arguments(arguments)})"
    return ClosedForm(quantity, value, formula, reference, atol, atol_reason)


def closed_value(law, quantity, mass, velocity):
    """The law's closed-form ``quantity`` on a wall (exact, no ``atol``), or None.

    Only the law's own class counts (a subclass may change the force); a series with a
    remainder (``atol > 0``) is not exact and gives None.
    """
    own = stated(law, "_closed_forms")
    forms = own(mass, velocity) if own is not None else ()
    exact = [f.value for f in forms if f.quantity == quantity and f.atol == 0.0]
    return exact[0] if exact else None
