"""A FIT.json written by today's fit (with its quality, baseline offset and rebound blocks)
passes the export schema, and a hostile value inside those blocks is refused by name."""

import copy
import json
from pathlib import Path

import pytest

from contactlab.errors import ParameterError
from contactlab.inverse.export import export_dem
from contactlab.inverse.export.schema import check_fit

TRACES = Path(__file__).resolve().parents[3] / "data" / "traces"
BLOCKS = ("quality", "baseline_offset", "rebound_on_wall")


@pytest.fixture(scope="module")
def fit_json(tmp_path_factory):
    """A real fit of the keysight sample trace (damped Hertz), as the command writes it."""
    from contactlab.cli import main

    out = tmp_path_factory.mktemp("fit") / "FIT.json"
    argv = [
        *("fit", str(TRACES / "keysight.csv"), "--law", "hertz_damped"),
        *("--model", str(TRACES / "model_hertz.toml"), "--sensitivity", "0.01124"),
        *("--out", str(out)),
    ]
    assert main(argv) in (0, None)
    return json.loads(out.read_text())


def test_a_fit_written_today_exports(fit_json):
    assert set(BLOCKS) <= set(fit_json)  # the blocks this test is about are really written
    check_fit(copy.deepcopy(fit_json), "FIT.json")
    assert "hertz/material" in export_dem(fit_json, "lammps")


@pytest.mark.parametrize(
    ("block", "path", "bad"),
    [
        ("quality", ("reasons",), ["ok\nshell touch /tmp/x"]),
        ("quality", ("whiteness", "test"), "a\rb"),
        ("quality", ("whiteness", "statistic [-]"), "17.9"),
        ("quality", ("consistent",), 1),
        ("quality", ("shell touch /tmp/x",), 1.0),
        ("rebound_on_wall", ("fitted_law [-]",), {"__import__": "os"}),
        ("baseline_offset", ("unit",), "N\nshell touch /tmp/x"),
        ("baseline_offset", ("value",), float("nan")),
    ],
)
def test_hostile_values_in_the_blocks_are_refused_by_name(fit_json, block, path, bad):
    data = copy.deepcopy(fit_json)
    target = data[block]
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = bad
    with pytest.raises(ParameterError, match=block):
        check_fit(data, "FIT.json")
