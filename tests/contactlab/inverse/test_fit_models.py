"""FIT_MODELS stays a table of the inverse problem (docs/architecture.md): each entry is
keyed by a registered law's name and builds that law from its fit coordinates."""

import pytest

import contactlab as cl
from contactlab.inverse.fit_models import FIT_MODELS, TRANSFORMS
from contactlab.laws import LAWS

GRAIN = cl.Grain(diameter=5e-3, density=765.0)


@pytest.mark.parametrize("name", sorted(FIT_MODELS))
def test_an_entry_builds_the_law_it_is_named_after(name):
    model = FIT_MODELS[name]
    assert model.law == name and name in LAWS
    assert len(model.parameters) == len(model.units) == len(model.transforms)
    assert set(model.transforms) <= set(TRANSFORMS)
    # the paper's grain: a 70 us contact at 2 m/s rebounding at 0.8
    guess = model.guess(GRAIN, 2.0, 70e-6, 0.8)
    assert sorted(guess) == sorted(model.parameters)
    law = model.build(guess, GRAIN)
    assert type(law) is LAWS[name]
