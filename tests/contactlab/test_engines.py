"""contactlab finds DEM engines through the ``contactlab.engines`` entry points."""

import pytest

import dem_check.engines
from contactlab.engines import engine_names, load_engine
from contactlab.errors import ParameterError


def test_dem_check_registers_its_engines():
    assert {"bullet", "lammps", "kratos"} <= set(engine_names())
    assert set(engine_names()) == set(dem_check.engines.ENGINES)  # one registry, not two


def test_load_engine_returns_the_engine_module():
    import dem_check.engines.bullet as bullet

    engine = load_engine("bullet")
    assert engine is bullet
    assert engine.drop_test is bullet.drop_test
    assert callable(engine.base_case_check)


@pytest.mark.parametrize("name", ["lammps", "kratos"])
def test_optional_engines_provide_the_interface(name):
    """Loading the module needs no engine library; ``load`` is what raises without it."""
    engine = load_engine(name)
    assert callable(engine.drop_test) and callable(engine.oblique_impact)
    assert callable(engine.load)


def test_unknown_engine_names_the_registered_ones():
    with pytest.raises(ParameterError, match=r"'lamps' \(did you mean 'lammps'\?\).*bullet"):
        load_engine("lamps")
    with pytest.raises(ParameterError, match="unknown engine"):
        load_engine(None)
