"""Two free spheres in an oblique impact as one sphere on a rigid plane (exact reduction).

Spheres 1 and 2 (masses ``m1, m2``, radii ``R1, R2``, moments of inertia ``I = kappa m R**2``
with the same ``kappa``) meet along a fixed contact normal ``n`` (from 1 to 2). Take the
tangential axis ``t`` in the plane of the relative motion and angular velocities ``w1, w2``
about ``n x t``. The contact point of sphere 1 moves at ``v1t + R1 w1`` along ``t``, that of
sphere 2 at ``v2t - R2 w2``, so the contact slips at::

    s = (v1t - v2t) + (R1 w1 + R2 w2).

A tangential force ``F`` on sphere 1 (``-F`` on sphere 2) acts through both lever arms::

    d(v1t - v2t)/dt = F (1/m1 + 1/m2) = F / m*,
    d(R1 w1 + R2 w2)/dt = F (R1**2/I1 + R2**2/I2) = F / (kappa m*),

with ``m* = m1 m2 / (m1 + m2)``: the slip obeys ``s' = F (1 + 1/kappa) / m*``, which is the
slip equation of one sphere of mass ``m*`` and the same ``kappa`` on a rigid plane. The normal
overlap obeys ``m* d'' = -N`` likewise. So a pair impact *is* the impact of a sphere of mass
``m*`` (:func:`~contactlab.analytic.effective_mass`) on a rigid plane, with the pair's
contact laws (``E*``, ``G*``, ``R*``: :func:`~contactlab.analytic.effective_modulus`,
:func:`~contactlab.analytic.effective_shear_modulus`,
:func:`~contactlab.analytic.effective_radius`)
and the relative velocities, for any normal law and any Coulomb-capped tangential law; the
plane sphere's tangential velocity is ``v1t - v2t`` and its ``R spin`` is
``-(R1 w1 + R2 w2)`` (``spin`` signed as in :func:`contactlab.simulate_oblique`, slip
``vt - R spin``). Each sphere's velocities follow from the normal and tangential impulses of
the equivalent impact (:func:`pair_rebound`).

Two identical spheres meeting symmetrically are the special case ``m* = m/2``; their
contact plane does not move, and one sphere against its mirror image equals a sphere of
mass ``m`` on a rigid plane of twice the pair's ``E*`` and ``G*`` at radius ``R``.

Exact within impact theory's fixed contact normal: the line of centres of real spheres
turns by about ``|v1t - v2t| t_c / (R1 + R2)`` during a contact of duration ``t_c`` (a
rigid plane does not turn), which the reduction, like Maw et al. (1976), leaves out.

References
----------
Maw N., Barber J.R., Fawcett J.N. (1976) Wear 38, 101-114 (the equivalent-sphere form).
Chung Y.C., Ooi J.Y. (2011) Granular Matter 13, 643-656 (tests 1, 7, 8, 9 are pairs).
"""

from dataclasses import dataclass

from contactlab.analytic.tangential import SOLID_SPHERE_INERTIA
from contactlab.errors import ParameterError
from contactlab.validation import check_number

__all__ = ["PairRebound", "pair_rebound"]


def _pair(name, values, unit):
    """Two positive numbers (``inf`` allowed: an immovable body), checked."""
    if not isinstance(values, (tuple, list)) or len(values) != 2:
        raise ParameterError(f"{name} must be two numbers [{unit}]; got {values!r}")
    return tuple(
        check_number(f"{name}[{i}]", v, low=0.0, unit=unit, allow_inf=True)
        for i, v in enumerate(values)
    )


@dataclass(frozen=True)
class PairRebound:
    """Velocities of both spheres after a pair impact (axes of :mod:`contactlab.analytic.pair`).

    ``normal1``, ``normal2`` [m/s] are the centres' velocities along ``n`` (from 1 to 2),
    ``tangential1``, ``tangential2`` [m/s] along ``t``, ``spin1``, ``spin2`` [rad/s] about
    ``n x t``.
    """

    normal1: float
    normal2: float
    tangential1: float
    tangential2: float
    spin1: float
    spin2: float


def pair_rebound(
    masses,
    radii,
    before,
    normal_impulse,
    tangential_impulse,
    inertia_factor=SOLID_SPHERE_INERTIA,
):
    """Both spheres' velocities after the impact, from the equivalent impact's impulses.

    Parameters
    ----------
    masses, radii : (float, float)
        ``(m1, m2)`` [kg] and ``(R1, R2)`` [m].
    before : PairRebound
        The velocities before the impact (same fields).
    normal_impulse : float
        Normal impulse on sphere 1, pushing it back along ``-n`` [N*s]: ``m*`` times the
        equivalent sphere's normal velocity change.
    tangential_impulse : float
        Tangential impulse on sphere 1 along ``t`` [N*s]: ``m*`` times the equivalent
        sphere's tangential velocity change.
    inertia_factor : float, default 0.4
        ``kappa = I / (m R**2)`` of both spheres [-].

    Returns
    -------
    PairRebound
    """
    m1, m2 = _pair("masses", masses, "kg")
    r1, r2 = _pair("radii", radii, "m")
    if not isinstance(before, PairRebound):
        raise ParameterError(
            f"before must be a PairRebound (the velocities before the impact); got {before!r}"
        )
    kappa = check_number("inertia_factor", inertia_factor, low=0.0)
    jn = check_number("normal_impulse", normal_impulse, unit="N*s")
    jt = check_number("tangential_impulse", tangential_impulse, unit="N*s")
    return PairRebound(
        normal1=before.normal1 - jn / m1,
        normal2=before.normal2 + jn / m2,
        tangential1=before.tangential1 + jt / m1,
        tangential2=before.tangential2 - jt / m2,
        spin1=before.spin1 + jt / (kappa * m1 * r1),
        spin2=before.spin2 + jt / (kappa * m2 * r2),
    )
