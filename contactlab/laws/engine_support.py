"""Which contact laws a DEM engine holds exactly: one refusal rule for every engine."""

from contactlab.errors import ParameterError

__all__ = ["refuse_unsupported"]


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
