"""Kratos Multiphysics' DEM application as an engine: the reduced model's impact in a second
DEM code, beside LAMMPS.

:func:`drop_test` drops the grain on the sensor in Kratos DEM and reads the impact as
:func:`contactlab.simulate_impact` does (an :class:`~dem_check.engines.result.EngineResult`,
so :func:`contactlab.compare` takes it). Kratos is the ``kratos`` extra (``pip install
'contactlab[kratos]'``); without it the functions raise ImportError naming the extra.

* :mod:`~dem_check.engines.kratos.session`: importing Kratos without its banner, on one
  thread;
* :mod:`contactlab.laws.kratos`: contactlab laws as Kratos DEM contact laws, as each law
  states it (:data:`ENGINE_LAWS`: linear, Hertz, damped Hertz with ``DAMPING_GAMMA`` set
  exactly), or a ParameterError quoting the law's reason why not;
* :mod:`~dem_check.engines.kratos.scene`: the case (model parts, materials, settings) in
  a temporary folder; the sensor a rigid wall or a sprung plate sphere;
* :mod:`~dem_check.engines.kratos.drop`: stepping it from Python and reading the steps;
* :mod:`~dem_check.engines.kratos.stage`: a Kratos analysis stepped from Python;
* :mod:`~dem_check.engines.kratos.check`: Kratos against the reduced model;
* :mod:`~dem_check.engines.kratos.oblique`: an oblique impact with friction and spin on a
  wall under Kratos' own tangential rules (:func:`kratos_oblique`).
"""

from contactlab.laws.kratos import ENGINE_LAWS, KratosContact, kratos_contact
from dem_check.engines.kratos.check import convergence_study, engine_check
from dem_check.engines.kratos.drop import default_time_step, drop_test
from dem_check.engines.kratos.oblique import kratos_oblique
from dem_check.engines.kratos.session import EXTRA, kratos_version, load_kratos

__all__ = [
    "ENGINE_LAWS",
    "EXTRA",
    "KratosContact",
    "convergence_study",
    "default_time_step",
    "drop_test",
    "engine_check",
    "kratos_contact",
    "kratos_oblique",
    "kratos_version",
    "load",
    "load_kratos",
    "oblique_impact",
]

# the plug-in interface's names (contactlab.engines): contactlab finds Kratos through them
oblique_impact = kratos_oblique
load = load_kratos
