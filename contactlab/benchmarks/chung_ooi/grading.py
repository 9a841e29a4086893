"""Graded rows of the Chung & Ooi benchmark: one compared number, its tolerances and verdict.

Tolerances (on the error defined in :func:`row`):

* :data:`TOLERANCE` (contactlab against theory): 1e-6. The solvers run at rtol 1e-9 to
  1e-10 and every graded theory is exact for the model (Hertz, the restitution mapping
  with the force-zero end, the impulse closed form in gross sliding, the pair reduction);
  measured errors are 1e-13 to 1e-8.
* :data:`LAMMPS_TOLERANCE` (LAMMPS against theory): 1e-3. LAMMPS integrates with
  velocity Verlet at a fixed step (:data:`dem_check.engines.lammps.oblique` uses the
  contact time over 2000); its incremental Mindlin form converges to first order in the
  step (about 3e-5 of the impact speed at that step), every other form to second order.
  1e-3 leaves room for that step error and still catches any model mismatch (LAMMPS'
  wall mixing of ``mindlin NULL`` alone would be a factor of 2 in the stiffness).
"""

import contactlab as cl
from contactlab.plausibility import internal

__all__ = ["LAMMPS_TOLERANCE", "TOLERANCE", "engine_row", "grain", "rebound", "row"]

TOLERANCE = 1e-6
"""Largest error of contactlab against theory (see the module docstring)."""

LAMMPS_TOLERANCE = 1e-3
"""Largest error of LAMMPS against theory (see the module docstring)."""


def grain(material, radius):
    """A :class:`contactlab.Grain` of ``material`` and ``radius`` [m].

    The benchmark's spheres (radius 0.1 m, alumina and aluminium alloy) are far larger
    and heavier than grains: built without a plausibility warning.
    """
    with internal():
        return cl.Grain(
            diameter=2 * radius,
            density=material.density,
            youngs_modulus=material.youngs_modulus,
            poisson_ratio=material.poisson_ratio,
        )


def rebound(result):
    """``(normal speed away, tangential velocity, spin)`` after an impact [m/s, m/s, rad/s].

    Works for :class:`contactlab.ObliqueResult` and LAMMPS' oblique result alike.
    """
    return result.rebound_normal_velocity, result.tangential_velocity, result.angular_velocity


def _error(value, theory, scale):
    return None if value is None else abs(value - theory) / scale


def row(case, material, quantity, ours, theory, *, scale=None, lammps=None):
    """One graded number.

    Parameters
    ----------
    case : Case
        The test.
    material : Material
        The sphere material.
    quantity : str
        What is compared, with its unit.
    ours, theory : float
        contactlab's value and the theory's.
    scale : float, optional
        What the error is relative to; default ``|theory|`` (give it where the theory
        can be zero).
    lammps : float, optional
        LAMMPS' value, when LAMMPS ran the same model.

    Returns
    -------
    dict
        test, material, quantity, contactlab, theory, lammps, relative_error,
        lammps_error, tolerance, lammps_tolerance, passed (contactlab and, when run,
        LAMMPS within their tolerances).
    """
    scale = abs(theory) if scale is None else scale
    error, lammps_error = _error(ours, theory, scale), _error(lammps, theory, scale)
    passed = error <= TOLERANCE and (lammps_error is None or lammps_error <= LAMMPS_TOLERANCE)
    return {
        "test": case.number,
        "material": material.name,
        "quantity": quantity,
        "contactlab": ours,
        "theory": theory,
        "lammps": lammps,
        "relative_error": error,
        "lammps_error": lammps_error,
        "tolerance": TOLERANCE,
        "lammps_tolerance": LAMMPS_TOLERANCE,
        "passed": bool(passed),
    }


def engine_row(case, material, quantity, ours, lammps, scale):
    """A number without a closed form, graded as contactlab against LAMMPS.

    The theory column is None; ``relative_error`` is ``|ours - lammps| / scale`` against
    :data:`LAMMPS_TOLERANCE` (two independent integrations of the same model).
    """
    error = abs(ours - lammps) / scale
    return {
        "test": case.number,
        "material": material.name,
        "quantity": quantity,
        "contactlab": ours,
        "theory": None,
        "lammps": lammps,
        "relative_error": error,
        "lammps_error": None,
        "tolerance": LAMMPS_TOLERANCE,
        "lammps_tolerance": LAMMPS_TOLERANCE,
        "passed": bool(error <= LAMMPS_TOLERANCE),
    }
