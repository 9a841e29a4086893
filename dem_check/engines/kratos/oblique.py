"""Oblique impacts of a spinning sphere on a rigid wall in Kratos DEM (``simulate_oblique``'s
and :func:`~dem_check.engines.lammps.oblique.lammps_oblique`'s twin).

One sphere (z up) starts a few steps above a rigid triangle in ``z = 0`` with velocity
``(vt, 0, -vn)`` and angular velocity ``(0, spin, 0)``: its contact point moves at ``vt -
R spin`` along x, the sign convention of :func:`contactlab.simulate_oblique`. The contact
law is Kratos' ``DEM_D_Hertz_viscous_Coulomb`` with the normal law mapped exactly
(:mod:`contactlab.laws.kratos`) and the material's Poisson ratio chosen so that
Kratos' tangential stiffness ``Kt = 4 G* Kn / E* = 8 G* sqrt(R d)``
(``InitializeContactWithFEM``) is the Mindlin law's ``k sqrt(d)``: with both bodies of
the same ``E, nu``, Kratos' wall mixing gives ``G*/E* = (1 - nu) / (2 (2 - nu))``, so
``nu = (1 - 4 r) / (1 - 2 r)`` for ``r = G*/E*`` and ``E = 2 E* (1 - nu**2)``.

What Kratos does *not* share with contactlab's Mindlin law are its hard-wired tangential
rules (``DEM_D_Hertz_viscous_Coulomb_CL.cpp``, ``CalculateTangentialForceWithNeighbour``;
``docs/dem-conventions.md``): the incremental force ``F_old - Kt ds`` rescaled by
``sqrt(d / d_prev)`` while the overlap shrinks, a tangential viscous force ``-2 gamma
sqrt(m* Kt) s'`` tied to the normal damping, and the lever arm of the contact point.
So its rebound is reported beside contactlab's and LAMMPS', not graded against them.
"""

import json
import math
import tempfile
from pathlib import Path

from contactlab.errors import ParameterError
from contactlab.laws import Mindlin
from contactlab.laws.kratos import HERTZ_LAW, kratos_contact
from dem_check.engines.kratos.scene import (
    GRAIN_PART,
    MATERIALS,
    PROBLEM,
    materials,
    plane_lines,
    project_parameters,
    sphere_density,
    sphere_lines,
)
from dem_check.engines.kratos.stage import KratosRun
from dem_check.engines.rebound import ObliqueRebound, oblique_start

__all__ = ["STEPS_PER_CONTACT", "kratos_oblique", "mindlin_poisson_ratio"]

STEPS_PER_CONTACT = 2000
"""Default steps per (wall) contact time, as LAMMPS' oblique impact."""

_FIRST = 1.05
"""Contact times run (after the approach) before the rebound is first read."""

_CHUNK = 0.05
"""Contact times run between later reads (Kratos steps from Python: no step is wasted)."""

_MAX_CHUNKS = 60
"""Later chunks after which the contact is declared not to end (four contact times)."""


def mindlin_poisson_ratio(k_hertz, k_mindlin):
    """The Poisson ratio giving Kratos' ``Kt`` the Mindlin stiffness (module docstring).

    ``r = G*/E* = k_mindlin / (6 k_hertz)`` (``k_mindlin = 8 G* sqrt(R)``, ``k_hertz =
    (4/3) E* sqrt(R)``); returns ``nu = (1 - 4 r) / (1 - 2 r)``.
    """
    ratio = k_mindlin / (6.0 * k_hertz)
    nu = (1.0 - 4.0 * ratio) / (1.0 - 2.0 * ratio)
    if not -1.0 < nu < 0.5:
        raise ParameterError(
            f"tangential_law: k_mindlin / k_hertz = {k_mindlin / k_hertz:.6g} needs a Poisson "
            f"ratio of {nu:.6g} in Kratos' mixing, outside (-1, 0.5)"
        )
    return nu


def kratos_oblique(grain, normal_law, tangential_law, velocity, angle, *, spin=0.0, time_step=None):
    """Run one oblique impact on a rigid wall in Kratos DEM.

    Parameters
    ----------
    grain : Grain
        The grain (mass, radius).
    normal_law : Hertz or HertzDamped
        Mapped exactly (:func:`contactlab.laws.kratos.kratos_contact`); the damping
        ratio also sets Kratos' tangential damping (its rule).
    tangential_law : Mindlin
        Its stiffness and friction; Kratos applies its own history rules (module
        docstring).
    velocity, angle, spin, time_step
        As for :func:`~dem_check.engines.lammps.lammps_oblique` (here Kratos' step [s];
        default the wall contact time over :data:`STEPS_PER_CONTACT`).

    Returns
    -------
    ObliqueRebound
        With ``time_step`` and ``steps``.

    Raises
    ------
    ParameterError
        For laws Kratos' Hertz law cannot hold, or bad numbers (named).
    ImportError
        Without the ``kratos`` extra.
    """
    start = oblique_start(grain, normal_law, velocity, angle, spin, time_step, STEPS_PER_CONTACT)
    if type(tangential_law) is not Mindlin:
        raise ParameterError(
            f"tangential_law must be Mindlin (Kratos' DEM_D_Hertz_viscous_Coulomb); got "
            f"{type(tangential_law).__name__}"
        )
    contact = kratos_contact(normal_law, grain.mass, grain.radius, wall=True)
    if contact.name != HERTZ_LAW:
        raise ParameterError("normal_law must be Hertz or HertzDamped for an oblique impact")
    nu = mindlin_poisson_ratio(normal_law.k_hertz, tangential_law.k_mindlin)
    young = contact.young * (1.0 - nu * nu)  # E = 2 E* (1 - nu**2)
    vn, vt, spin = start.vn, start.vt, start.spin
    contact_time, time_step, gap = start.contact_time, start.time_step, start.gap
    r = grain.radius
    with tempfile.TemporaryDirectory(prefix="contactlab-kratos-") as name:
        folder = Path(name)
        lines = sphere_lines(1, 1, r + gap, r, -vn, GRAIN_PART)
        (folder / f"{PROBLEM}DEM.mdpa").write_text("\n".join(lines) + "\n")
        (folder / f"{PROBLEM}DEM_FEM_boundary.mdpa").write_text(
            "\n".join(plane_lines(10.0 * r + 10.0 * vt * contact_time)) + "\n"
        )
        table = materials(
            sphere_density(grain.mass, r),
            young,
            HERTZ_LAW,
            poisson_ratio=nu,
            friction=tangential_law.friction,
        )
        (folder / MATERIALS).write_text(json.dumps(table) + "\n")
        run = KratosRun(folder, project_parameters(time_step), contact.gamma)
        km = run.KM
        node = run.spheres.GetNode(1)
        node.SetSolutionStepValue(km.VELOCITY_X, vt)
        node.SetSolutionStepValue(km.ANGULAR_VELOCITY_Y, spin)
        first = math.ceil((gap / vn + _FIRST * contact_time) / time_step)
        chunk = math.ceil(_CHUNK * contact_time / time_step)
        steps = 0
        try:
            for count in (first, *[chunk] * _MAX_CHUNKS):
                for _ in range(count):
                    run.step()
                steps += count
                if node.Z > r and node.GetSolutionStepValue(km.VELOCITY_Z) > 0.0:
                    break  # left the wall, moving away
            else:
                raise RuntimeError(f"the contact lasted more than {steps} steps")
            result = ObliqueRebound(
                velocity=start.velocity,
                angle=start.angle,
                spin=spin,
                radius=r,
                rebound_normal_velocity=node.GetSolutionStepValue(km.VELOCITY_Z),
                tangential_velocity=node.GetSolutionStepValue(km.VELOCITY_X),
                angular_velocity=node.GetSolutionStepValue(km.ANGULAR_VELOCITY_Y),
                time_step=time_step,
                steps=steps,
            )
        finally:
            run.close()
    return result
