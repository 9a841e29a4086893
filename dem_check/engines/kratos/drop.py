"""The Kratos DEM drop test: one impact of the reduced model run in Kratos' DEM application."""

import tempfile
import time
from pathlib import Path

import numpy as np

from contactlab.errors import ParameterError
from dem_check.engines.config import UNSET, engine_config
from dem_check.engines.kratos.scene import drop_scene
from dem_check.engines.kratos.session import kratos_version
from dem_check.engines.kratos.stage import KratosRun
from dem_check.engines.record import drop_plan, engine_result, run_until_over, step_limit
from dem_check.engines.steps import (  # noqa: F401 (handed on)
    DROP_STEP_NAMES,
    MIN_STEPS,
    STEPS_PER_CONTACT,
    STEPS_PER_PERIOD,
    default_time_step,
)

__all__ = ["CHUNK_STEPS", "MAX_STEPS", "drop_test", *DROP_STEP_NAMES]

MAX_STEPS = 200_000
"""Most steps one drop test runs (Kratos steps from Python, ~0.1 ms each: 20 s)."""

CHUNK_STEPS = 500
"""Steps between two looks for the end of the impact."""


class _Stepper:
    """A Kratos analysis of one :class:`DropScene`, stepped and recorded from Python."""

    def __init__(self, scene, folder, materials=None):
        scene.write(folder)
        settings = scene.parameters()
        gamma = scene.contact.gamma
        if materials is not None:  # the user's file, read by Kratos as it is
            if not scene.sensor.is_rigid:
                raise ParameterError(
                    "materials: a MaterialsDEM.json assigns its materials to SpheresPart and "
                    "RigidFacePart, a rigid sensor's parts; give sensor=Sensor.rigid()"
                )
            if not Path(materials).is_file():
                raise ParameterError(f"materials: no such file {str(materials)!r}")
            import_settings = settings["solver_settings"]["material_import_settings"]
            import_settings["materials_filename"] = str(Path(materials).resolve())
            gamma = None
        self.kratos = KratosRun(folder, settings, gamma)
        self.km, self.scene = self.kratos.KM, scene
        self.grain = self.kratos.spheres.GetNode(1)
        self.plate = None if scene.sensor.is_rigid else self.kratos.spheres.GetNode(2)
        self.rows = []

    def _plate_state(self):
        if self.plate is None:
            return 0.0, 0.0
        return self.plate.Z, self.plate.GetSolutionStepValue(self.km.VELOCITY_Z)

    def run(self, count):
        """Run ``count`` steps, recording each step's start state and its contact force."""
        km, grain, plate = self.km, self.grain, self.plate
        sensor, rest = self.scene.sensor, -self.scene.plate_radius
        for _ in range(count):
            z1, vz1 = self._plate_state()
            if plate is not None:
                spring = -sensor.stiffness * (z1 - rest) - sensor.damping * vz1
                plate.SetSolutionStepValue(km.EXTERNAL_APPLIED_FORCE, [0.0, 0.0, spring])
            row = [len(self.rows), grain.Z, grain.GetSolutionStepValue(km.VELOCITY_Z)]
            self.kratos.step()
            row += [grain.GetSolutionStepValue(km.TOTAL_FORCES_Z), z1, vz1]
            self.rows.append(row)

    def columns(self):
        """The recorded rows as ``(6, steps)`` columns (step, z2, vz2, fz2, z1, vz1)."""
        return np.array(self.rows, dtype=float).T

    def close(self):
        self.kratos.close()


def drop_test(
    config,
    *fields,
    time_step=UNSET,
    gap=None,
    duration=None,
    threshold=0.0,
    plate_radius=None,
    materials=None,
):
    """Drop the grain on the sensor in Kratos DEM and read the impact like the reduced model.

    The drop is planned, recorded and read as LAMMPS' (:mod:`dem_check.engines.record`).

    Parameters
    ----------
    config : contactlab.config.ImpactConfig
        The set-up, as for :func:`dem_check.engines.lammps.drop.drop_test` (the plate a
        Kratos sphere): ``sensor`` ``Sensor.rigid()`` is a rigid plane (a Kratos wall), a
        real sensor a plate sphere of mass ``m1`` on a spring ``k1`` and damper ``c1``
        (:mod:`~dem_check.engines.kratos.scene`); ``law`` one whose class states its
        Kratos mapping (LinearViscoelastic, Hertz, HertzDamped;
        :mod:`contactlab.laws.kratos`), other laws raise ParameterError.
    *fields
        Deprecated: ``drop_test(grain, sensor, law, velocity[, time_step])``
        (:func:`dem_check.engines.config.engine_config`).
    gap, duration, threshold, plate_radius
        As for :func:`dem_check.engines.lammps.drop.drop_test`.
    time_step : float, optional
        Kratos step [s]; default :func:`default_time_step`. At most 1/20 of the contact
        (on an immovable wall) and of the sensor period.
    materials : str or pathlib.Path, optional
        A ``MaterialsDEM.json`` (e.g. ``contactlab export-dem --to kratos``) to run instead
        of the exact mapping of ``law``, as Kratos reads it (its restitution turned into
        ``DAMPING_GAMMA`` by Kratos itself); for a rigid sensor, its materials assigned to
        ``SpheresPart`` and ``RigidFacePart``. ``law`` still marks the contact's end.

    Returns
    -------
    EngineResult
        ``method`` is ``"kratos"``; ``metadata`` holds the Kratos version, the step, the
        Kratos law, Young's modulus and ``DAMPING_GAMMA``, the steps run and their wall
        time. Kratos runs in a temporary folder, removed afterwards.

    Raises
    ------
    ParameterError
        For a law Kratos cannot hold, a time step too coarse, or bad numbers (each named).
    ImportError
        Without the ``kratos`` extra (``pip install 'contactlab[kratos]'``).
    """
    config, time_step = engine_config(config, fields, time_step, "dem_check.kratos.drop_test")
    grain, sensor, law = config.grain, config.sensor, config.law
    plan = drop_plan(config, time_step, duration, threshold, default_time_step, MIN_STEPS)
    velocity, dt, after, stop = plan.velocity, plan.time_step, plan.after, plan.stop
    scene = drop_scene(grain, sensor, law, velocity, dt, gap, plate_radius)
    limit = step_limit(scene, after, MAX_STEPS, "Kratos", start_states=True)
    with tempfile.TemporaryDirectory(prefix="contactlab-kratos-") as folder:
        clock = time.perf_counter()
        stepper = _Stepper(scene, folder, materials)
        try:
            columns, complete = run_until_over(
                scene, limit, CHUNK_STEPS, stepper.run, stepper.columns, stop
            )
        finally:
            stepper.close()
        wall = time.perf_counter() - clock
    return _result(scene, columns, plan.threshold, complete, wall)


def _result(scene, columns, threshold, complete, wall):
    """The :class:`EngineResult` of the recorded columns of a :class:`DropScene`."""
    contact = scene.contact
    metadata = {
        "engine": f"Kratos DEM {kratos_version()}",
        "time_step [s]": scene.time_step,
        "numerical_damping [N*s/m]": 0.0,
        "steps": int(columns[0][-1]) + 1,
        "kratos_law": contact.name,
        "young_modulus [Pa]": contact.young,
        "damping_gamma [-]": contact.gamma,
        "effective_mass [kg]": contact.effective_mass,
        "effective_radius [m]": contact.effective_radius,
        "plate_radius [m]": scene.plate_radius,
        "gap [m]": scene.gap,
        "wall_time [s]": wall,
    }
    return engine_result("kratos", "Kratos", scene, columns, threshold, complete, metadata)
