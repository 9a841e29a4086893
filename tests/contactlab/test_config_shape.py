"""ImpactConfig is the one set-up shape: the study makes it, the batch reads its row."""

import math
from dataclasses import replace

import pandas as pd
import pytest

import contactlab as cl
from contactlab import analytic
from contactlab.batch import hertz_impacts, linear_impacts
from contactlab.config import load_preset
from contactlab.errors import ParameterError
from contactlab.study import StudySetup


def test_a_linear_row_on_a_wall_gives_the_closed_forms():
    config = replace(load_preset("fig6"), sensor=cl.Sensor.rigid())
    law, mass = config.law, config.grain.mass
    got = linear_impacts(pd.DataFrame([config.batch_row()])).iloc[0]
    # events located to 4 eps; the closed forms add a few ulps of their own
    assert got["contact_time [s]"] == pytest.approx(
        analytic.linear_contact_time(law.stiffness, law.damping, mass, "force"), rel=1e-12
    )
    assert got["restitution [-]"] == pytest.approx(
        analytic.linear_restitution(law.stiffness, law.damping, mass, "force"), rel=1e-12
    )


def test_a_hertz_row_on_a_wall_gives_the_closed_form():
    grain = cl.Grain(diameter=5e-3, density=765.0)
    law = cl.laws.Hertz(k_hertz=2e8)
    config = cl.config.ImpactConfig(grain, cl.Sensor.rigid(), law, {"velocity": 2.0})
    got = hertz_impacts(pd.DataFrame([config.batch_row()])).iloc[0]
    # the compiled stepper runs at rtol 1e-10; the closed form is exact
    assert got["contact_time [s]"] == pytest.approx(
        analytic.hertz_contact_time(law.k_hertz, grain.mass, 2.0), rel=1e-8
    )
    assert got["restitution [-]"] == pytest.approx(1.0, rel=1e-8)  # elastic: same bound


def test_a_law_without_a_batch_solver_is_refused_by_name():
    with pytest.raises(ParameterError, match="PlasticTrapezoid has no batch solver"):
        load_preset("fig9").batch_row()


def test_study_points_are_impact_configs():
    setup = StudySetup.paper()
    config = setup.config({"grain.diameter": 4e-3})
    assert isinstance(config, cl.config.ImpactConfig)
    assert config.grain.diameter == 4e-3 and math.isfinite(config.velocity)
    assert config.velocity == setup.velocity and config.law == setup.law
    assert not hasattr(setup, "at")  # the 4-tuple shape is gone
