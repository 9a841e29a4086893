"""Which contact laws a DEM engine holds exactly: one refusal rule for every engine, and
the fields every engine's mapping of a law shares."""

from dataclasses import dataclass

from contactlab.errors import ParameterError
from contactlab.laws.base import stated
from contactlab.validation import check_positive

__all__ = ["EngineContact", "engine_mapping", "refuse_unsupported", "stated_support"]


@dataclass(frozen=True, kw_only=True)
class EngineContact:
    """A law mapped exactly onto a DEM engine's contact model for a contact of given
    ``m*`` and ``R*`` (each engine's mapping adds its model's own fields).

    Attributes
    ----------
    law : ContactLaw
        The contactlab law.
    effective_mass : float
        ``m*`` the mapping assumed [kg].
    effective_radius : float
        ``R*`` the mapping assumed [m].
    """

    law: object
    effective_mass: float
    effective_radius: float


def refuse_unsupported(law, supported, refused, engine, models):
    """Raise unless ``law`` is an instance of one of the ``supported`` law classes.

    Parameters
    ----------
    law : contactlab.laws.ContactLaw
        The law to run in the engine.
    supported : tuple of type
        Law classes the engine holds exactly (its ``ENGINE_LAWS``).
    refused : dict
        Law class -> why the engine cannot hold it (its ``REFUSED``), quoted in the error.
    engine : str
        The engine's name in messages, e.g. ``"LAMMPS"``.
    models : str
        What holds the laws there, for a law without a reason in ``refused``, e.g.
        ``"LAMMPS' granular models"``.

    Raises
    ------
    ParameterError
        Naming the law, the reason, and the laws the engine does hold; nothing is
        approximated.
    """
    kind = type(law)
    if kind in supported:
        return
    reason = refused.get(kind, f"it is not one of the laws {models} hold")
    names = ", ".join(cls.__name__ for cls in supported)
    raise ParameterError(
        f"law {kind.__name__} cannot be represented in {engine}: {reason}. "
        f"Supported exactly: {names}"
    )


def stated_support(laws, mapping, refusal):
    """Which of ``laws`` an engine holds, as each law's own class states it.

    Parameters
    ----------
    laws : iterable of type
        The registered law classes (``contactlab.laws.LAWS.values()``).
    mapping, refusal : str
        The class attributes naming the engine's mapping method (``"_lammps_model"``)
        and its refusal reason (``"lammps_refusal"``).

    Returns
    -------
    supported : tuple of type
        The classes that state ``mapping`` (an engine's ``ENGINE_LAWS``).
    refused : dict
        Class -> the reason it states (an engine's ``REFUSED``).
    """
    laws = tuple(laws)
    supported = tuple(cls for cls in laws if mapping in vars(cls))
    refused = {cls: vars(cls)[refusal] for cls in laws if refusal in vars(cls)}
    return supported, refused


def engine_mapping(law, mapping, support, engine, models, effective_mass, effective_radius, *more):
    """``law`` mapped onto an engine's contact model by the law's own ``mapping`` method.

    Parameters
    ----------
    law : ContactLaw
        The law (its own class must state ``mapping``: a subclass may change the force).
    mapping : str
        The mapping method's name, called as ``mapping(m*, R*, *more)``.
    support : tuple
        ``(supported, refused)`` of :func:`stated_support`.
    engine, models : str
        As for :func:`refuse_unsupported`.
    effective_mass, effective_radius : float
        ``m*`` [kg] and ``R*`` [m] the engine uses for the contact.
    *more
        Further arguments of the mapping (Kratos: whether the contact is with a wall).

    Raises
    ------
    ParameterError
        For ``m*`` or ``R*`` not > 0, or a law the engine does not hold (its reason quoted).
    """
    mass = check_positive("effective_mass", effective_mass, "kg")
    radius = check_positive("effective_radius", effective_radius, "m")
    refuse_unsupported(law, *support, engine, models)
    return stated(law, mapping)(mass, radius, *more)
