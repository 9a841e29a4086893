"""Contact-end conventions of damped laws, and the checks the closed forms share.

Damped laws need a rule for when contact ends; ``convention`` selects it:

``"overlap"``
    Contact ends when the overlap returns to zero. The damper may pull (tensile force)
    near the end. This is the textbook result and the one most DEM mappings assume.
``"force"``
    Contact ends when the force returns to zero; the force is never tensile. This is what
    a one-sided contact does and what :func:`contactlab.simulate_impact` computes. It gives
    a shorter contact and a larger restitution than ``"overlap"``.
"""

from contactlab.validation import check_choice, check_number

__all__ = ["CONVENTIONS", "check_convention", "check_restitution"]


#: Contact-end conventions accepted by the ``convention`` arguments.
CONVENTIONS = ("overlap", "force")


def check_restitution(value):
    """Check a coefficient of restitution in [0, 1] [-]; return it as float."""
    return check_number("restitution", value, low=0.0, high=1.0, unit="-")


def check_convention(value):
    """Check a contact-end convention (one of :data:`CONVENTIONS`)."""
    return check_choice("convention", value, CONVENTIONS)
