"""The reduced model's impact rebuilt in a rigid-body engine (pybullet): a drop bench.

:func:`drop_test` drops a sphere on a plate in pybullet and reads the result as
:func:`contactlab.simulate_impact` does, so the two can be compared number by number
(:func:`engine_check`, :func:`contactlab.compare`).

The scene (SI units, engine z axis up; the model's x axis points down, into the sensor):

* the **grain** is a free sphere of the grain's diameter and mass;
* the **sensor** is a disc (cylinder) of the sensor's diameter and thickness
  (:meth:`Sensor.from_disc`), or of :data:`DEFAULT_PLATE` when the sensor does not know
  them, with mass ``m1`` on a PRISMATIC joint of a fixed base. The measuring element
  (``k1``, ``c1``) is a joint force ``-(k1 x1 + c1 v1)`` applied before every step from
  the joint state, and the sensor signal is read from the same state,
  ``S1 = k1 x1 + c1 v1``. :meth:`Sensor.rigid` is a fixed plate (``S1 = S2``);
* the **contact** is the engine's soft contact with ``contactStiffness = k2`` and
  ``contactDamping = c2`` on the grain. The engine combines two bodies' values as springs
  in series and dampers in parallel, so the plate gets ``1e30`` and ``0``.

Which laws the engine can represent
-----------------------------------
pybullet's soft contact is a spring and a damper, linear in overlap and rate, that never
pulls: exactly :class:`~contactlab.laws.LinearViscoelastic`. Every other law (Hertz and
its damped variants, Hunt-Crossley, Walton-Braun, linear-plastic, Thornton, the prescribed
trapezoid) raises :class:`~contactlab.errors.ParameterError` naming it.

The engine's bias
-----------------
The engine solves the contact implicitly: the force at the end of a step is
``k2 d + c d'`` of the *end-of-step* state, which is the force of the start-of-step
overlap plus an extra damper ``k2 dt``. This numerical damping ``k2 * dt`` [N*s/m] is
reported (``result.numerical_damping``); ``compensate_damping=True`` passes
``contactDamping = c2 - k2 dt`` instead, which needs ``c2 >= k2 dt``. The sensor spring,
applied explicitly before each step, is symplectic and adds no damping.

Modules
-------
:mod:`~dem_check.engines.bullet.limits` (laws the engine holds, time steps),
:mod:`~dem_check.engines.bullet.scene` (:class:`DropScene`, :func:`drop_scene`),
:mod:`~dem_check.engines.bullet.run` (stepping the engine, reading its steps),
:mod:`~dem_check.engines.bullet.drop` (:func:`drop_test`) and
:mod:`~dem_check.engines.bullet.check` (:func:`engine_check`, :func:`convergence_study`,
:func:`base_case_check`: the engine against the reduced model).
"""

from dem_check.engines.bullet.check import base_case_check, convergence_study, engine_check
from dem_check.engines.bullet.drop import MAX_STEPS, TAIL, drop_test
from dem_check.engines.bullet.limits import ENGINE_LAWS, default_time_step
from dem_check.engines.bullet.scene import DEFAULT_PLATE, GRAVITY, DropScene, drop_scene

__all__ = [
    "DEFAULT_PLATE",
    "ENGINE_LAWS",
    "GRAVITY",
    "MAX_STEPS",
    "TAIL",
    "DropScene",
    "base_case_check",
    "convergence_study",
    "default_time_step",
    "drop_scene",
    "drop_test",
    "engine_check",
]
