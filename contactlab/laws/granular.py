"""A law as one LAMMPS ``granular`` model: what a law's ``lammps_model`` returns.

Each law that LAMMPS' GRANULAR package holds exactly states its mapping beside its force
(``lammps_model(effective_mass, effective_radius)``), and each one it cannot hold says why
(``lammps_refusal``); :func:`contactlab.laws.lammps.granular_model` asks the law. The
sub-models and their forces are in :mod:`contactlab.laws.lammps`'s docstring.
"""

from dataclasses import dataclass

from contactlab.laws.engine_support import EngineContact

__all__ = ["DAMPING_FORMS", "TANGENTIAL", "GranularModel"]

TANGENTIAL = "tangential linear_nohistory 0 0"
"""LAMMPS requires a tangential model: this one exerts no force."""

DAMPING_FORMS = (
    "LAMMPS' damping forces scale as d**0 (velocity, mass_velocity), d**0.25 "
    "(tsuji, coeff_restitution on hertz) or d**0.5 (viscoelastic)"
)
"""What LAMMPS' damping sub-models can hold, quoted in refusals."""


@dataclass(frozen=True, kw_only=True)
class GranularModel(EngineContact):
    """A law as one LAMMPS granular model for a contact of given ``m*`` and ``R*``.

    Attributes
    ----------
    normal : str
        LAMMPS normal sub-model (``"hooke"`` or ``"hertz"``).
    stiffness : float
        Its first coefficient: ``k`` [N/m] (hooke) or [N/m**2 = Pa] (hertz, ``F = k a d``).
    damping : str
        LAMMPS damping sub-model (``"velocity"``, ``"viscoelastic"``,
        ``"coeff_restitution"``).
    damping_coefficient : float
        The normal model's second coefficient as LAMMPS reads it for that damping: [N*s/m]
        (velocity), [1/(m*s)] (viscoelastic), a restitution [-] (coeff_restitution).

    and ``law``, ``effective_mass``, ``effective_radius`` of
    :class:`~contactlab.laws.engine_support.EngineContact`.
    """

    normal: str
    stiffness: float
    damping: str
    damping_coefficient: float

    def words(self, tangential=TANGENTIAL, number=repr):
        """The model as ``pair_coeff`` / ``fix wall/gran granular`` words (one-sided).

        ``tangential`` is the tangential sub-model's words (default: no tangential force);
        ``number`` writes a coefficient (default all 17 digits, so LAMMPS reads the very
        double; the DEM exporter writes 7).
        """
        return (
            f"{self.normal} {number(self.stiffness)} {number(self.damping_coefficient)} "
            f"damping {self.damping} {tangential} limit_damping"
        )

    @property
    def what(self):
        """The law and its parameters, for error messages."""
        return f"law {self.law!r} as {self.normal}/{self.damping}"
