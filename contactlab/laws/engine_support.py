"""Which contact laws a DEM engine holds exactly: one refusal rule for every engine, and
the fields every engine's mapping of a law shares."""

from dataclasses import dataclass

from contactlab.errors import ParameterError

__all__ = ["EngineContact", "refuse_unsupported"]


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
