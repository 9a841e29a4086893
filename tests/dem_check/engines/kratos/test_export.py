"""The Kratos export realised: Kratos reads the exported MaterialsDEM.json itself (its own
restitution-to-gamma rules) and the grain rebounds as the fitted law.

``export_dem(fit, "kratos")`` (and ``contactlab export-dem FIT.json --to kratos``) is run
through :func:`dem_check.engines.kratos.drop_test` with ``materials=`` the exported file and
the exported time step, and set against the fitted law's exact wall impact
(:func:`contactlab.solver.wall_impact`), within the limits of the LAMMPS export's test
(``tests/dem_check/engines/lammps/test_realise.py``).
"""

import json

import pytest
from documents import E_STAR, GRAIN, VELOCITY, fit_document

import contactlab as cl
from contactlab import analytic
from contactlab.cli import main
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError
from contactlab.inverse import export_dem
from contactlab.solver import wall_impact
from dem_check.engines.kratos import drop_test

pytestmark = pytest.mark.kratos


def _fits(restitution):
    k_hertz = analytic.hertz_stiffness(E_STAR, GRAIN.radius)
    hertz_damped = cl.laws.HertzDamped(
        k_hertz, analytic.tsuji_damping_coefficient(k_hertz, GRAIN.mass, restitution)
    )
    damping = analytic.linear_damping_from_restitution(1e5, restitution, GRAIN.mass)
    linear = cl.laws.LinearViscoelastic(1e5, damping)
    return {
        "linear": (
            linear,
            fit_document(
                "linear", linear, {"stiffness": (1e5, "N/m"), "damping": (damping, "N*s/m")}
            ),
        ),
        "hertz_damped": (
            hertz_damped,
            fit_document(
                "hertz_damped",
                hertz_damped,
                {"effective_modulus": (E_STAR, "Pa"), "restitution": (restitution, "-")},
            ),
        ),
        "hertz": (
            cl.laws.Hertz(k_hertz),
            fit_document("hertz", cl.laws.Hertz(k_hertz), {"effective_modulus": (E_STAR, "Pa")}),
        ),
    }


def _realise(path, law):
    document = json.loads(path.read_text(encoding="utf-8"))
    step = document["contactlab_export"]["MaxTimeStep [s]"]
    return drop_test(
        ImpactConfig(GRAIN, cl.Sensor.rigid(), law, {"velocity": VELOCITY}),
        time_step=step,
        materials=path,
    )


CASES = [(name, e) for name in ("linear", "hertz_damped") for e in (0.2, 0.5, 0.9)]


@pytest.mark.parametrize(("name", "restitution"), [*CASES, ("hertz", 1.0)])
def test_export_realises_the_fitted_law_on_a_rigid_plate(tmp_path, name, restitution):
    law, fit = _fits(restitution)[name]
    path = tmp_path / "MaterialsDEM.json"
    path.write_text(export_dem(fit, "kratos"), encoding="utf-8")
    exact = wall_impact(law, GRAIN.mass, VELOCITY)
    impact = _realise(path, law)
    # 200 steps per contact, damping first order in symplectic Euler: measured <= 0.26 %
    # (e = 0.2), 0.08 % (e = 0.5); Thornton's polynomial inverted exactly, Kratos' linear
    # bisection within 6e-5 in gamma. The LAMMPS export's bound is 1 %
    assert impact.restitution == pytest.approx(exact.restitution, rel=0.01)
    # measured <= 0.34 % (contact time), 0.48 % (peak): the LAMMPS export's 3 %
    assert impact.contact_time == pytest.approx(exact.contact_time, rel=0.03)
    assert impact.peak_contact_force == pytest.approx(exact.peak_contact_force, rel=0.03)
    assert impact.contact_force.min() >= 0.0  # Kratos clips the normal force at zero


def test_the_command_line_writes_the_same_file(tmp_path):
    law, fit = _fits(0.5)["hertz_damped"]
    fit_path = tmp_path / "FIT.json"
    fit_path.write_text(json.dumps(fit), encoding="utf-8")
    out = tmp_path / "MaterialsDEM.json"
    assert main(["export-dem", str(fit_path), "--to", "kratos", "--out", str(out)]) == 0
    assert json.loads(out.read_text(encoding="utf-8")) == json.loads(export_dem(fit, "kratos"))
    impact = _realise(out, law)
    exact = wall_impact(law, GRAIN.mass, VELOCITY)
    # as above (e = 0.5: measured 0.08 %)
    assert impact.restitution == pytest.approx(exact.restitution, rel=0.01)


def test_thornton_gamma_is_kratos_own_function():
    """The writer's copy of GammaForHertzThornton against the installed Kratos' one."""
    from dem_check.engines.kratos import load_kratos

    load_kratos()
    from KratosMultiphysics.DEMApplication.sphere_strategy import ExplicitStrategy

    from contactlab.inverse.export.kratos import thornton_gamma

    for e in (0.0005, 0.01, 0.2, 0.5, 0.77, 0.98, 0.9995):
        # the same arithmetic in the same order: equal to the last bit
        assert thornton_gamma(e) == ExplicitStrategy.GammaForHertzThornton(None, e)


def test_a_materials_file_needs_a_rigid_sensor_and_must_exist(tmp_path, paper_sensor):
    law, fit = _fits(0.5)["hertz_damped"]
    path = tmp_path / "MaterialsDEM.json"
    path.write_text(export_dem(fit, "kratos"), encoding="utf-8")
    with pytest.raises(ParameterError, match="materials"):
        drop_test(ImpactConfig(GRAIN, paper_sensor, law, {"velocity": VELOCITY}), materials=path)
    with pytest.raises(ParameterError, match="materials: no such file"):
        drop_test(
            ImpactConfig(GRAIN, cl.Sensor.rigid(), law, {"velocity": VELOCITY}),
            materials=tmp_path / "none.json",
        )
