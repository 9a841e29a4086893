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
  The same tolerance grades every DEM engine on the normal tests (Kratos: symplectic
  Euler at 1000 steps per contact, first order with damping; measured below 6e-4).

Engines (:data:`ENGINES`) have two columns each, the value and its error. An engine's
number is *graded* (it counts in ``passed``) when the engine runs the same model as
contactlab; Kratos' oblique test 4 is only *reported* (``not_graded``): Kratos applies
its own tangential rules, not contactlab's Mindlin law (``docs/dem-conventions.md``).
"""

import contactlab as cl
from contactlab.plausibility import internal

__all__ = ["ENGINES", "LAMMPS_TOLERANCE", "TOLERANCE", "engine_row", "grain", "rebound", "row"]

ENGINES = ("lammps", "kratos")
"""DEM engines with a column in the table (each: value and error)."""

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


def row(case, material, quantity, ours, theory, *, scale=None, lammps=None, engines=None):
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
        LAMMPS' value, when LAMMPS ran the same model (graded).
    engines : dict, optional
        ``{engine: (value, graded)}`` for engines of :data:`ENGINES`; ``graded`` False
        reports the value and its error without grading it.

    Returns
    -------
    dict
        test, material, quantity, contactlab, theory, ``<engine>`` and ``<engine>_error``
        for each of :data:`ENGINES` (None when not run), relative_error, tolerance,
        lammps_tolerance (every engine's), not_graded (engines only reported, comma
        separated), passed (contactlab and every graded engine within their tolerances).
    """
    scale = abs(theory) if scale is None else scale
    error = _error(ours, theory, scale)
    runs = {"lammps": (lammps, True), **(engines or {})}
    columns, passed, not_graded = {}, error <= TOLERANCE, []
    for name in ENGINES:
        value, graded = runs.get(name, (None, True))
        columns[name], columns[f"{name}_error"] = value, _error(value, theory, scale)
        if value is not None and not graded:
            not_graded.append(name)
        elif columns[f"{name}_error"] is not None:
            passed = passed and columns[f"{name}_error"] <= LAMMPS_TOLERANCE
    return {
        "test": case.number,
        "material": material.name,
        "quantity": quantity,
        "contactlab": ours,
        "theory": theory,
        **columns,
        "relative_error": error,
        "tolerance": TOLERANCE,
        "lammps_tolerance": LAMMPS_TOLERANCE,
        "not_graded": ",".join(not_graded),
        "passed": bool(passed),
    }


def engine_row(case, material, quantity, ours, lammps, scale):
    """A number without a closed form, graded as contactlab against LAMMPS.

    The theory column is None; ``relative_error`` is ``|ours - lammps| / scale`` against
    :data:`LAMMPS_TOLERANCE` (two independent integrations of the same model).
    """
    error = abs(ours - lammps) / scale
    others = {key: None for name in ENGINES for key in (name, f"{name}_error")}
    return {
        "test": case.number,
        "material": material.name,
        "quantity": quantity,
        "contactlab": ours,
        "theory": None,
        **others,
        "lammps": lammps,
        "relative_error": error,
        "tolerance": LAMMPS_TOLERANCE,
        "lammps_tolerance": LAMMPS_TOLERANCE,
        "not_graded": "",
        "passed": bool(error <= LAMMPS_TOLERANCE),
    }
