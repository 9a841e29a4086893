"""One vocabulary: every table and result names its quantities as contactlab.quantities."""

import re

import pytest

import contactlab as cl
from contactlab.batch.rows import RESULT_COLUMNS
from contactlab.compare import QUANTITIES as COMPARED
from contactlab.errors import ParameterError
from contactlab.quantities import DEPRECATED, QUANTITIES, column, columns, quantity
from contactlab.result import HEADLINE, SIGNALS
from dem_check.campaign.api import IMPACT_COLUMNS
from dem_check.campaign.synthetic import TRUTH_COLUMNS

COLUMN = re.compile(r"^(\w+) \[(.+)\]$")


def _in_vocabulary(name):
    """A ``"name [unit]"`` column that the vocabulary defines with that unit."""
    match = COLUMN.match(name)
    return (
        bool(match)
        and QUANTITIES.get(match[1], None) is not None
        and (QUANTITIES[match[1]].unit == match[2])
    )


def test_column_is_name_and_unit():
    assert column("contact_time") == "contact_time [s]"
    assert columns("impulse", "restitution") == ("impulse [N*s]", "restitution [-]")
    assert quantity("peak_sensor_force").unit == "N"


@pytest.mark.parametrize(("old", "new"), sorted(DEPRECATED.items()))
def test_old_names_warn_and_read_the_new_quantity(old, new):
    with pytest.warns(DeprecationWarning, match=f"{old!r} is now called {new!r}"):
        assert column(old) == column(new)


def test_unknown_name_is_a_parameter_error_with_a_hint():
    with pytest.raises(ParameterError, match=r"'contact_tim' \(did you mean 'contact_time'"):
        column("contact_tim")


def test_no_old_name_is_in_the_vocabulary():
    assert not set(DEPRECATED) & set(QUANTITIES)
    assert set(DEPRECATED.values()) <= set(QUANTITIES)


@pytest.mark.parametrize(
    "table",
    [RESULT_COLUMNS, TRUTH_COLUMNS, [c for c in IMPACT_COLUMNS if "[" in c]],
    ids=["batch", "campaign truth", "campaign impacts"],
)
def test_tables_write_vocabulary_columns(table):
    assert [c for c in table if not _in_vocabulary(c)] == []


def test_results_and_comparisons_use_the_vocabulary():
    law = cl.laws.LinearViscoelastic(1e5, 1.0)
    grain = cl.Grain(diameter=5e-3, density=765.0)
    res = cl.simulate_impact(grain, cl.Sensor.from_resonance(40e3, mass=1e-3), law, 2.0)
    summary = res.summary()
    for name in HEADLINE:
        assert summary[column(name)] == getattr(res, name), name
    assert tuple(res.to_frame().columns) == columns(*SIGNALS)
    for name, compared in COMPARED.items():
        assert compared.unit == QUANTITIES[name].unit, name
