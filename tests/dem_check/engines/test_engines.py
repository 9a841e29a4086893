"""The engine interface: one ``drop_test`` dispatching by name through ``ENGINES``."""

import inspect

import numpy as np
import pytest

import contactlab as cl
import dem_check
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError
from dem_check import engines
from dem_check.engines import ENGINES, bullet, drop_test, engine_module
from dem_check.engines.bullet.check import TIME_STEPS
from dem_check.engines.config import UNSET, engine_config
from dem_check.engines.result import contact_crossings


@pytest.fixture(scope="module")
def case():
    """The paper's 5 mm grain on the rigid plate, undamped k2 = 1e5 N/m, 2 m/s."""
    grain = cl.Grain(diameter=5e-3, density=765.0)
    law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=0.0)
    return ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": 2.0})


def test_every_registered_engine_provides_drop_test():
    assert "bullet" in ENGINES
    for name in ENGINES:
        assert callable(engine_module(name).drop_test)
    assert dem_check.drop_test is engines.drop_test


@pytest.mark.parametrize("name", ["bulet", "pybullet", "", None, 3])
def test_unknown_engine_lists_the_valid_names(case, name):
    with pytest.raises(ParameterError, match=r"unknown engine .*valid names: bullet"):
        drop_test(case, engine=name)


def test_close_name_is_suggested(case):
    with pytest.raises(ParameterError, match=r"did you mean 'bullet'\?"):
        drop_test(case, engine="bulet")


def test_unknown_keyword_raises_type_error(case):
    with pytest.raises(TypeError, match="no_such_option"):
        drop_test(case, engine="bullet", no_such_option=1.0)


@pytest.mark.bullet
def test_dispatch_gives_the_engine_module_result(case):
    via_registry = drop_test(case, time_step=1e-7, engine="bullet", duration=100e-6)
    direct = bullet.drop_test(case, time_step=1e-7, duration=100e-6)
    assert via_registry.method == direct.method == "pybullet"
    # the engine is deterministic (deterministicOverlappingPairs=1): bit-identical runs
    np.testing.assert_array_equal(via_registry.contact_force, direct.contact_force)
    np.testing.assert_array_equal(via_registry.t, direct.t)


@pytest.mark.bullet
@pytest.mark.parametrize("entry", [drop_test, bullet.drop_test], ids=["registry", "engine"])
def test_the_positional_form_warns_and_runs_the_same_drop_test(case, entry):
    fields = (case.grain, case.sensor, case.law, case.velocity)
    from_config = entry(case, time_step=1e-7, duration=100e-6)
    with pytest.warns(DeprecationWarning, match=r"drop_test\(ImpactConfig\(grain, sensor") as w:
        from_fields = entry(*fields, 1e-7, duration=100e-6)
    assert w[0].filename == __file__  # the warning points at the caller's line
    # the engine is deterministic (deterministicOverlappingPairs=1): bit-identical runs
    np.testing.assert_array_equal(from_config.contact_force, from_fields.contact_force)


def test_the_checks_read_the_old_form_with_its_last_argument(case):
    fields = (case.grain, case.sensor, case.law, case.velocity)
    steps = (1e-7, 5e-8)
    new_call = (
        r"f\(ImpactConfig\(grain, sensor, law, \{'velocity': velocity\}\), time_steps=\.\.\.\)"
    )
    with pytest.warns(DeprecationWarning, match=new_call):
        config, read = engine_config(fields[0], (*fields[1:], steps), UNSET, "f", "time_steps")
    assert (config.grain, config.sensor, config.law, config.velocity) == fields
    assert read == steps
    assert engine_config(case, (), steps, "f", "time_steps") == (case, steps)


@pytest.mark.parametrize("last", ["time_step", "time_steps"])
def test_the_old_forms_fifth_argument_beside_the_keyword_is_refused(case, last):
    """The keyword was dropped silently in favour of the positional; now neither wins."""
    fields = (case.sensor, case.law, case.velocity, 1e-7)
    with pytest.raises(ParameterError, match=rf"{last} is given twice to f: .*\(1e-07\).*2e-07"):
        engine_config(case.grain, fields, 2e-7, "f", last)
    # the keyword's default tells "not given" from any value, None included
    with pytest.raises(ParameterError, match=f"{last} is given twice"):
        engine_config(case.grain, fields, None, "f", last)
    with pytest.warns(DeprecationWarning):
        assert engine_config(case.grain, fields, UNSET, "f", last)[1] == 1e-7


def test_the_entries_refuse_both_before_running_an_engine(case):
    fields = (case.grain, case.sensor, case.law, case.velocity, 1e-7)
    with pytest.raises(ParameterError, match=r"time_step is given twice to dem_check\.drop_test"):
        drop_test(*fields, time_step=2e-7)
    with pytest.raises(ParameterError, match="time_step is given twice"):
        bullet.drop_test(*fields, time_step=2e-7)
    with pytest.raises(ParameterError, match="time_steps is given twice"):
        bullet.convergence_study(*fields[:4], (1e-7, 5e-8), time_steps=(2e-7, 1e-7))


def test_an_omitted_keyword_gives_the_entrys_default(case):
    assert engine_config(case, (), UNSET, "f") == (case, None)
    steps = engine_config(case, (), UNSET, "f", "time_steps", default=TIME_STEPS)
    assert steps == (case, TIME_STEPS)
    assert inspect.signature(bullet.convergence_study).parameters["time_steps"].default is UNSET


@pytest.mark.parametrize("name", sorted(ENGINES))
def test_every_engine_takes_one_config(name):
    """The plug-in interface (contactlab/engines.py): ``drop_test(config, *, time_step)``."""
    parameters = inspect.signature(engine_module(name).drop_test).parameters
    assert next(iter(parameters)) == "config"
    assert parameters["time_step"].kind is inspect.Parameter.KEYWORD_ONLY


def test_positional_fields_after_a_config_are_refused(case):
    with pytest.raises(TypeError, match="takes time_step as a keyword"):
        drop_test(case, 1e-7)
    with pytest.raises(TypeError, match="got 3 positional arguments"):
        drop_test(case.grain, case.sensor, case.law)


@pytest.mark.parametrize("bad", [2.0, "fig6", [1, 2]])
def test_a_config_that_is_not_one_is_refused_by_name(bad):
    with pytest.raises(ParameterError, match=r"config must be a contactlab\.config\.ImpactConfig"):
        drop_test(bad)


def test_contact_crossings_interpolate_linearly():
    # piecewise-linear indicator: linear interpolation is exact at its zeros
    t = np.arange(8.0)
    indicator = np.array([-1.0, 1.0, 3.0, 1.0, -3.0, -1.0, 1.0, 2.0])
    rises, falls = contact_crossings(indicator, t)
    np.testing.assert_allclose(rises, [0.5, 5.5], rtol=0, atol=1e-15)  # exact up to rounding
    np.testing.assert_allclose(falls[:1], [3.25], rtol=0, atol=1e-15)  # exact up to rounding
    assert np.isnan(falls[-1])  # still in contact at the end


@pytest.mark.parametrize("name", ["bullet", "lammps"])
def test_engine_reachable_as_an_attribute_of_dem_check(name):
    """``dem_check.<engine>.drop_test`` is the engine's own drop test."""
    assert getattr(dem_check, name).drop_test is engine_module(name).drop_test


def test_unknown_attribute_of_dem_check_raises_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'pybullet'"):
        dem_check.pybullet  # noqa: B018
