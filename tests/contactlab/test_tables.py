"""CSV tables safe for spreadsheets (issue 24): ``contactlab.tables.spreadsheet_safe``."""

import ast
from pathlib import Path

import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from contactlab.errors import ParameterError
from contactlab.tables import FORMULA_STARTS, spreadsheet_safe

ROOT = Path(__file__).resolve().parents[2]

UNSAFE_WRITERS = {
    "contactlab/traces/textwrite.py": "oscilloscope layouts: pre-formatted numbers such as "
    "'-1.5e-03' are the format and must stay as they are",
    "contactlab/study/paper.py": "calls SweepResult.to_csv, which writes spreadsheet_safe tables",
}
"""Source files allowed to call ``.to_csv`` on a table that did not pass through
``spreadsheet_safe``, with the reason."""


def test_formula_cells_get_a_quote_and_numbers_stay():
    table = pd.DataFrame({"file": ["=1+1", "+A1", "-2", "@x", "\tx", "plain"], "v": range(-3, 3)})
    safe = spreadsheet_safe(table)
    assert list(safe["file"]) == ["'=1+1", "'+A1", "'-2", "'@x", "'\tx", "plain"]
    assert list(safe["v"]) == list(range(-3, 3))  # negative numbers stay numbers
    assert table["file"].iloc[0] == "=1+1"  # the caller's table is untouched


def test_column_names_are_neutralised_too():
    safe = spreadsheet_safe(pd.DataFrame({"=HYPERLINK(1)": [1.0], "v [m/s]": [-1.0]}))
    assert list(safe.columns) == ["'=HYPERLINK(1)", "v [m/s]"]


@given(
    st.lists(st.text(max_size=6), min_size=1, max_size=8),
    st.floats(allow_nan=False),
)
def test_every_text_cell_is_kept_or_quoted_and_numbers_are_kept(cells, number):
    table = pd.DataFrame({"text": cells, "number [m]": [number] * len(cells)})
    safe = spreadsheet_safe(table)
    for before, after in zip(cells, safe["text"], strict=True):
        risky = before.startswith(FORMULA_STARTS)
        assert after == ("'" + before if risky else before)
    assert safe["number [m]"].dtype == table["number [m]"].dtype
    assert (safe["number [m]"] == number).all()


def _unsafe_to_csv_calls(path):
    """Lines of ``path`` calling ``X.to_csv(...)`` where X is not ``spreadsheet_safe(...)``."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
            continue
        if node.func.attr != "to_csv":
            continue
        receiver = node.func.value
        safe = (
            isinstance(receiver, ast.Call)
            and isinstance(receiver.func, ast.Name)
            and receiver.func.id == "spreadsheet_safe"
        )
        if not safe:
            found.append(node.lineno)
    return found


def test_every_csv_table_the_packages_write_is_spreadsheet_safe():
    unsafe = [
        f"{path.relative_to(ROOT)}:{line}"
        for package in ("contactlab", "dem_check")
        for path in sorted((ROOT / package).rglob("*.py"))
        if str(path.relative_to(ROOT)) not in UNSAFE_WRITERS
        for line in _unsafe_to_csv_calls(path)
    ]
    assert not unsafe, f"write these through contactlab.tables.spreadsheet_safe: {unsafe}"


def test_a_table_that_is_not_a_dataframe_is_refused():
    with pytest.raises(ParameterError, match="table must be a DataFrame"):
        spreadsheet_safe([["=1+1"]])
