"""YADE input: a Python script fragment (ViscElMat or FrictMat with MindlinPhys)."""

import math

from contactlab.bodies import STEEL_DENSITY
from contactlab.inverse.export.contact import number

__all__ = ["write"]


YADE_PWAVE_FRACTION = 0.5
"""YADE Hertz: ``O.dt = 0.5 * PWaveTimeStep()``, ``PWaveTimeStep = R sqrt(rho / E)``."""

YADE_VISCEL_FRACTION = 0.05
"""YADE ViscElMat: ``O.dt = 0.05 * tc``, as YADE's viscoelastic example scripts set it."""


def _engines(physics, law):
    """``O.engines``: sphere and facet geometry, then the contact's ``Ip2_*`` physics and
    ``Law2_*`` law functors, under gravity."""
    return [
        "O.engines = [",
        "    ForceResetter(),",
        "    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),",
        "    InteractionLoop(",
        "        [Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],",
        f"        [{physics}],",
        f"        [{law}],",
        "    ),",
        "    NewtonIntegrator(gravity=(0, 0, -9.81)),",
        "]",
    ]


def write(c):
    """YADE lines for an :class:`~contactlab.inverse.export.contact.ExportContact`."""
    friction = f"atan({number(c.friction)})"
    if c.family == "linear":
        step = YADE_VISCEL_FRACTION * c.contact_time
        why = f"{YADE_VISCEL_FRACTION:g} x contact time (YADE's ViscElMat examples)"
        body = [
            "# Law2_ScGeom_ViscElPhys_Basic: the contact's kn is 1/(1/kn1 + 1/kn2) of the",
            "# two materials (likewise cn), so one material on grain and plate carries 2 k, 2 c",
            f"# frictionAngle: {c.friction_note()}; ks, cs NOT FITTED (ks = 2/7 kn, cs = 0)",
            "viscel = O.materials.append(",
            f"    ViscElMat(kn={number(2.0 * c.stiffness)}, cn={number(2.0 * c.damping)}, "
            f"ks={number(2.0 * 2.0 / 7.0 * c.stiffness)}, cs=0.0,",
            f"              density={number(c.density)}, frictionAngle={friction}, "
            'label="grain_and_plate")',
            ")",
            *_engines("Ip2_ViscElMat_ViscElMat_ViscElPhys()", "Law2_ScGeom_ViscElPhys_Basic()"),
        ]
    else:
        pwave = c.radius * math.sqrt(c.density / c.youngs_modulus)
        step = YADE_PWAVE_FRACTION * pwave
        fraction = f"{YADE_PWAVE_FRACTION:g}"
        why = f"{fraction} x PWaveTimeStep() = {fraction} x {number(pwave)} s"
        body = [
            "# Hertz-Mindlin with Tsuji damping from en (Ip2_FrictMat_FrictMat_MindlinPhys)",
            f"# frictionAngle: {c.friction_note()}",
            "grain = O.materials.append(",
            f"    FrictMat(young={number(c.youngs_modulus)}, poisson={number(c.poisson_ratio)}, "
            f"density={number(c.density)},",
            f'             frictionAngle={friction}, label="grain")',
            ")",
            "plate = O.materials.append(",
            f"    FrictMat(young={number(c.plate_youngs_modulus)}, "
            f"poisson={number(c.plate_poisson_ratio)}, density={number(STEEL_DENSITY)},",
            f'             frictionAngle={friction}, label="sensor_plate")',
            ")",
            *_engines(
                "Ip2_FrictMat_FrictMat_MindlinPhys(en=MatchMaker(algo='val', "
                f"val={number(c.restitution)}))",
                "Law2_ScGeom_MindlinPhys_Mindlin()",
            ),
        ]
    return [
        *c.header("YADE", "#", why, step),
        "from math import atan",
        "",
        *body,
        f"O.dt = {number(step)}",
    ]
