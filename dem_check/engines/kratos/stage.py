"""One Kratos DEM analysis read from a folder and stepped from Python.

Kratos' ``DEMAnalysisStage`` reads the case from its main folder (:meth:`GetMainPath`,
here the folder given) and runs its own time loop; :class:`KratosRun` runs Kratos'
``Initialize`` quietly, writes ``DAMPING_GAMMA`` when asked, and then steps the solver
itself (``AdvanceInTime``, ``InitializeSolutionStep``, ``Predict``,
``SolveSolutionStep``, ``FinalizeSolutionStep``: the solver part of Kratos' loop,
without the analysis stage's per-step bookkeeping, which costs ~0.6 ms a step in Python
and does nothing for one grain).
"""

import json

from dem_check.engines.kratos.session import load_kratos, quiet_stdout

__all__ = ["KratosRun", "set_gamma"]


def set_gamma(dem, model_part, gamma):
    """Write ``DAMPING_GAMMA`` into every material and material relation of a model part.

    Kratos' Hertz law reads it from the contact's sub-properties, its linear law from the
    particles' properties (:mod:`contactlab.laws.kratos`); both are set.
    """
    for properties in model_part.Properties:
        properties[dem.DAMPING_GAMMA] = gamma
        for sub in properties.GetSubProperties():
            sub[dem.DAMPING_GAMMA] = gamma


class KratosRun:
    """A Kratos DEM analysis of the case in ``folder``, ready to step.

    Parameters
    ----------
    folder : str or pathlib.Path
        Holds the model part files and the materials file the settings name.
    settings : dict
        Kratos' project parameters.
    gamma : float, optional
        ``DAMPING_GAMMA`` written into every material relation after ``Initialize``
        (``None``: Kratos' own, from the restitution in the materials file).

    Attributes
    ----------
    KM, DEM : module
        Kratos and its DEM application.
    spheres : ModelPart
        Kratos' ``SpheresPart``.
    time : float
        Simulated time [s].
    """

    def __init__(self, folder, settings, gamma=None):
        kratos = load_kratos()
        self.KM, self.DEM = kratos.KM, kratos.DEM

        class Stage(kratos.stage):
            def GetMainPath(self):  # Kratos' name: the folder it reads the case from
                return str(folder)

        parameters = kratos.KM.Parameters(json.dumps(settings))
        with quiet_stdout():
            self.stage = Stage(kratos.KM.Model(), parameters)
            self.stage.Initialize()
        self.spheres = self.stage.spheres_model_part
        if gamma is not None:
            for part in (self.spheres, self.stage.rigid_face_model_part):
                set_gamma(kratos.DEM, part, gamma)
        self.solver = self.stage._GetSolver()
        self.time = 0.0

    def step(self):
        """One time step of Kratos' DEM solver."""
        solver = self.solver
        self.time = solver.AdvanceInTime(self.time)
        solver.InitializeSolutionStep()
        solver.Predict()
        solver.SolveSolutionStep()
        solver.FinalizeSolutionStep()

    def close(self):
        """Kratos' ``Finalize`` (quietly)."""
        with quiet_stdout():
            self.stage.Finalize()
