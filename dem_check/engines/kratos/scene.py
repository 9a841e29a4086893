"""One Kratos DEM drop test as Kratos input: the model parts, the materials and the settings.

Kratos' ``DEMAnalysisStage`` reads a case from files in its main folder: the spheres
(``<problem>DEM.mdpa``), the rigid walls (``<problem>DEM_FEM_boundary.mdpa``) and the
materials (a ``MaterialsDEM.json``-style file, :func:`materials`). :meth:`DropScene.write`
writes them into a folder the caller owns (the drop test uses a temporary folder and
removes it), and :meth:`DropScene.parameters` gives the settings (no gravity, no output
files, one neighbour search per step, symplectic Euler, Kratos' default).

Axis z up; the grain is sphere 1, released at ``z = R2 + gap`` with velocity ``-v``:

* a **rigid sensor** is a triangle ``RigidFace3D3N`` in the plane ``z = 0`` (Kratos'
  DEM-FEM contact: ``m* = m2``, ``R* = R2``);
* a **real sensor** is sphere 2, the plate: radius ``PLATE_RADIUS_FACTOR`` grain radii,
  mass ``m1`` (its density so chosen), top at ``z = 0``. Kratos has no spring on a
  particle, so the drop test applies the sensor's spring and damper as the plate's
  ``EXTERNAL_APPLIED_FORCE``, ``-k1 u - c1 u'`` from its displacement ``u`` and velocity
  at the start of each step, the state the contact force is computed from. The
  grain-plate contact has ``m* = m1 m2 / (m1 + m2)`` and ``R* = R2 Rp / (R2 + Rp)``, and
  the law is mapped with these (:func:`contactlab.laws.kratos.kratos_contact`), as
  in the LAMMPS scene (:mod:`dem_check.engines.lammps.scene`).
"""

import json
import math
from dataclasses import dataclass
from pathlib import Path

from contactlab.inverse.export.kratos import material_relation
from contactlab.laws.kratos import kratos_contact
from dem_check.engines.record import DropCase, drop_geometry

__all__ = [
    "GRAIN_PART",
    "MATERIALS",
    "PLATE_PART",
    "PROBLEM",
    "DropScene",
    "drop_scene",
    "materials",
    "plane_lines",
    "project_parameters",
    "sphere_density",
    "sphere_lines",
]

PROBLEM = "drop"
"""Kratos problem name: the model part files are ``dropDEM.mdpa`` and
``dropDEM_FEM_boundary.mdpa``."""

MATERIALS = "MaterialsDEM.json"
"""Name of the materials file."""

GRAIN_PART = "grain"
"""Sub-model part of the spheres holding the grain (sphere 1)."""

PLATE_PART = "plate"
"""Sub-model part of the spheres holding the sensor plate (sphere 2)."""


def materials(
    grain_density,
    young,
    law_name,
    restitution=1.0,
    plate_density=None,
    poisson_ratio=0.0,
    friction=0.0,
):
    """A ``MaterialsDEM.json``-style dict: grain (id 1) and sensor (id 2), one relation each.

    Parameters
    ----------
    grain_density : float
        The grain's ``PARTICLE_DENSITY`` [kg/m**3].
    young : float
        ``YOUNG_MODULUS`` of both [Pa] (``POISSON_RATIO`` 0).
    law_name : str
        Kratos' ``DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME`` of every relation.
    restitution : float, default 1
        ``COEFFICIENT_OF_RESTITUTION`` Kratos turns into ``DAMPING_GAMMA`` (1: no damping;
        the drop test then writes the exact ``gamma``).
    plate_density : float, optional
        The plate sphere's density [kg/m**3]; ``None`` makes material 2 a rigid wall's.
    poisson_ratio : float, default 0
        ``POISSON_RATIO`` of both [-] (it enters only the tangential stiffness).
    friction : float, default 0
        ``STATIC_FRICTION`` and ``DYNAMIC_FRICTION`` of every relation [-].

    Returns
    -------
    dict
        Keys ``materials``, ``material_relations``, ``material_assignation_table``.
    """
    grain = {
        "PARTICLE_DENSITY": grain_density,
        "YOUNG_MODULUS": young,
        "POISSON_RATIO": poisson_ratio,
    }
    sensor = {"YOUNG_MODULUS": young, "POISSON_RATIO": poisson_ratio}
    if plate_density is None:
        sensor["COMPUTE_WEAR"] = False
    else:
        sensor["PARTICLE_DENSITY"] = plate_density
    pairs = [(("grain", "grain"), (1, 1)), (("grain", "sensor"), (1, 2))]
    if plate_density is not None:
        pairs.append((("sensor", "sensor"), (2, 2)))
    return {
        "materials": [
            {"material_name": "grain", "material_id": 1, "Variables": grain},
            {"material_name": "sensor", "material_id": 2, "Variables": sensor},
        ],
        "material_relations": [
            material_relation(names, ids, law_name, restitution, friction) for names, ids in pairs
        ],
        "material_assignation_table": [
            [f"SpheresPart.{GRAIN_PART}", "grain"],
            ["RigidFacePart" if plate_density is None else f"SpheresPart.{PLATE_PART}", "sensor"],
        ],
    }


def sphere_lines(node, props, z, radius, vz, part):
    """``.mdpa`` lines of one sphere (node and element ``node``, properties ``props``) at
    ``(0, 0, z)`` [m] of ``radius`` [m], velocity ``vz`` [m/s], in sub-model part ``part``."""
    return [
        f"Begin Properties {props}",
        "End Properties",
        "Begin Nodes",
        f" {node} 0.0 0.0 {z!r}",
        "End Nodes",
        "Begin Elements SphericParticle3D",
        f" {node} {props} {node}",
        "End Elements",
        "Begin NodalData RADIUS",
        f" {node} 0 {radius!r}",
        "End NodalData",
        "Begin NodalData VELOCITY_Z",
        f" {node} 0 {vz!r}",
        "End NodalData",
        f"Begin SubModelPart {part}",
        " Begin SubModelPartNodes",
        f"  {node}",
        " End SubModelPartNodes",
        " Begin SubModelPartElements",
        f"  {node}",
        " End SubModelPartElements",
        "End SubModelPart",
    ]


def plane_lines(size):
    """``.mdpa`` lines of a rigid triangle in ``z = 0`` (properties 2) covering a square of
    side ``size`` [m] around the origin."""
    return [
        "Begin Properties 2",
        "End Properties",
        "Begin Nodes",
        f" 3 {-size!r} {-size!r} 0.0",
        f" 4 {2.0 * size!r} {-size!r} 0.0",
        f" 5 {-size!r} {2.0 * size!r} 0.0",
        "End Nodes",
        "Begin Conditions RigidFace3D3N",
        " 1 2 3 4 5",
        "End Conditions",
        "Begin SubModelPart 1",
        " Begin SubModelPartData",
        "  RIGID_BODY_MOTION 0",
        "  IDENTIFIER sensor",
        " End SubModelPartData",
        " Begin SubModelPartNodes",
        "  3",
        "  4",
        "  5",
        " End SubModelPartNodes",
        " Begin SubModelPartConditions",
        "  1",
        " End SubModelPartConditions",
        "End SubModelPart",
    ]


def sphere_density(mass, radius):
    """Density [kg/m**3] of a sphere of ``mass`` [kg] and ``radius`` [m] (Kratos computes a
    particle's mass from its density)."""
    return mass / (4.0 / 3.0 * math.pi * radius**3)


def project_parameters(time_step):
    """Kratos' project parameters for a step [s]: a dict for ``KratosMultiphysics.Parameters``.

    No gravity, no output files, one neighbour search per step, symplectic Euler and
    direct rotational integration (Kratos' defaults), the materials from :data:`MATERIALS`.
    """
    return {
        "problem_name": PROBLEM,
        "do_print_results_option": False,
        "Dimension": 3,
        "BoundingBoxOption": False,
        "dem_inlet_option": False,
        "GravityX": 0.0,
        "GravityY": 0.0,
        "GravityZ": 0.0,
        "RotationOption": True,
        "solver_settings": {
            "RemoveBallsInitiallyTouchingWalls": False,
            "strategy": "sphere_strategy",
            "material_import_settings": {"materials_filename": MATERIALS},
        },
        "TranslationalIntegrationScheme": "Symplectic_Euler",
        "RotationalIntegrationScheme": "Direct_Integration",
        "ElementType": "SphericPartDEMElement3D",
        "MaxTimeStep": time_step,
        "FinalTime": 1.0,
        "NeighbourSearchFrequency": 1,
        "GraphExportFreq": 1.0,
        "VelTrapGraphExportFreq": 1.0,
        "OutputTimeStep": 1.0,
    }


@dataclass(frozen=True)
class DropScene(DropCase):
    """One drop test as Kratos input (build it with :func:`drop_scene`).

    Attributes
    ----------
    contact : KratosContact
        The law as a Kratos contact law for this contact's ``m*`` and ``R*``.
    grain, sensor, law, velocity, time_step, gap, plate_radius
        As for :class:`~dem_check.engines.record.DropCase`.
    """

    contact: object

    def write(self, folder):
        """Write the model parts and the materials into ``folder`` (an existing folder)."""
        folder = Path(folder)
        r2 = self.grain.radius
        spheres = sphere_lines(1, 1, r2 + self.gap, r2, -self.velocity, GRAIN_PART)
        rigid = self.sensor.is_rigid
        if rigid:
            (folder / f"{PROBLEM}DEM_FEM_boundary.mdpa").write_text(
                "\n".join(plane_lines(10.0 * r2)) + "\n"
            )
            plate_density = None
        else:
            rp = self.plate_radius
            spheres += sphere_lines(2, 2, -rp, rp, 0.0, PLATE_PART)
            plate_density = sphere_density(self.sensor.mass, rp)
        (folder / f"{PROBLEM}DEM.mdpa").write_text("\n".join(spheres) + "\n")
        table = materials(
            sphere_density(self.grain.mass, r2),
            self.contact.young,
            self.contact.name,
            plate_density=plate_density,
        )
        (folder / MATERIALS).write_text(json.dumps(table, indent=2) + "\n")

    def parameters(self):
        """Kratos' project parameters (:func:`project_parameters` of the step)."""
        return project_parameters(self.time_step)


def drop_scene(grain, sensor, law, velocity, time_step, gap=None, plate_radius=None):
    """The :class:`DropScene` of one drop test.

    Parameters
    ----------
    grain, sensor, law, velocity, time_step
        As for :func:`~dem_check.engines.kratos.drop.drop_test`; ``time_step`` already
        checked [s].
    gap, plate_radius : float, optional
        Release gap and plate radius [m] (:func:`~dem_check.engines.record.drop_geometry`).

    Returns
    -------
    DropScene

    Raises
    ------
    ParameterError
        For a law Kratos cannot hold, or a gap or plate radius not > 0.
    """
    geometry = drop_geometry(grain, sensor, velocity, time_step, gap, plate_radius)
    contact = kratos_contact(
        law, geometry.effective_mass, geometry.effective_radius, wall=sensor.is_rigid
    )
    return DropScene(
        grain, sensor, law, velocity, time_step, geometry.gap, geometry.plate_radius, contact
    )
