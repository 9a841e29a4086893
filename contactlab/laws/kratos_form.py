"""A law as one Kratos DEM contact law: what a law's ``_kratos_model`` returns.

Each law that Kratos' DEM application holds exactly states its mapping beside its force
(``_kratos_model(effective_mass, effective_radius, wall)``), and each one it cannot hold
says why (``kratos_refusal``); :func:`contactlab.laws.kratos.kratos_contact` asks the law.
The Kratos laws and their forces are in :mod:`contactlab.laws.kratos`'s docstring.
"""

import math
from dataclasses import dataclass

from contactlab.laws.engine_support import EngineContact

__all__ = [
    "DAMPING_FORMS",
    "HERTZ_LAW",
    "LINEAR_LAW",
    "KratosContact",
    "kratos_hertz",
    "kratos_model",
    "linear_kn_factor",
]

HERTZ_LAW = "DEM_D_Hertz_viscous_Coulomb"
"""Kratos' Hertz law with viscous damping and Coulomb friction."""

LINEAR_LAW = "DEM_D_Linear_viscous_Coulomb"
"""Kratos' linear law with viscous damping and Coulomb friction."""

_LINEAR_RADIUS_FACTOR = 0.31225
"""``Kn = pi * 0.31225 * E* * R`` (``DEM_D_Linear_viscous_Coulomb_CL.cpp``,
``modified_radius``)."""

_LINEAR_SPHERE_FACTOR = 1.432
"""Extra factor ``beta`` of the linear stiffness between two spheres (not at a wall)."""

DAMPING_FORMS = (
    "Kratos' viscous damping is 2 gamma sqrt(m* Kn) d', which scales as d**0 (linear) or "
    "d**0.25 (Hertz)"
)
"""What Kratos' damping can hold, quoted in refusals."""


def linear_kn_factor(wall):
    """``Kn / (E* R*)`` of Kratos' linear law: ``pi 0.31225`` at a wall, ``1.432`` times
    that between two spheres."""
    factor = math.pi * _LINEAR_RADIUS_FACTOR
    return factor if wall else _LINEAR_SPHERE_FACTOR * factor


@dataclass(frozen=True, kw_only=True)
class KratosContact(EngineContact):
    """A law as a Kratos DEM contact law for a contact of given ``m*`` and ``R*``.

    Attributes
    ----------
    name : str
        Kratos' law name (:data:`HERTZ_LAW` or :data:`LINEAR_LAW`).
    young : float
        Young's modulus of both bodies [Pa] (``2 E*``, Poisson ratio 0).
    gamma : float
        ``DAMPING_GAMMA`` [-].

    and ``law``, ``effective_mass``, ``effective_radius`` of
    :class:`~contactlab.laws.engine_support.EngineContact`.
    """

    name: str
    young: float
    gamma: float

    @property
    def what(self):
        """The law and its parameters, for messages."""
        return (
            f"law {self.law!r} as {self.name} (E = {self.young:.6g} Pa, gamma = {self.gamma:.6g})"
        )


def kratos_model(law, name, e_star, effective_mass, effective_radius):
    """``law`` as Kratos' law ``name`` with effective modulus ``e_star`` [Pa] (both bodies
    ``E = 2 E*``, Poisson ratio 0) and ``DAMPING_GAMMA = law._damping_ratio(m*)``, the
    law's constant damping ratio."""
    return KratosContact(
        name=name,
        young=2.0 * e_star,
        gamma=law._damping_ratio(effective_mass),
        law=law,
        effective_mass=effective_mass,
        effective_radius=effective_radius,
    )


def kratos_hertz(law, effective_mass, effective_radius):
    """A Hertz-family law (``kH``, a constant damping ratio) as Kratos' Hertz law:
    ``E* = 3 kH / (4 sqrt(R*))`` (at a wall and between spheres alike)."""
    e_star = 3.0 * law.k_hertz / (4.0 * math.sqrt(effective_radius))
    return kratos_model(law, HERTZ_LAW, e_star, effective_mass, effective_radius)
