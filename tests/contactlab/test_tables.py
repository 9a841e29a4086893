"""CSV tables safe for spreadsheets (issue 24): ``contactlab.tables.spreadsheet_safe``
and ``write_csv``."""

import ast
import csv
import io
from pathlib import Path

import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from contactlab.errors import ParameterError
from contactlab.tables import FORMULA_STARTS, spreadsheet_safe, write_csv

ROOT = Path(__file__).resolve().parents[2]

UNSAFE_WRITERS = {
    "contactlab/traces/textwrite.py": "oscilloscope layouts: pre-formatted numbers such as "
    "'-1.5e-03' are the format and must stay as they are",
    "contactlab/study/paper.py": "calls SweepResult.to_csv, which writes through write_csv",
    "contactlab/tables.py": "write_csv itself: spreadsheet_safe, then to_csv with text quoted",
}
"""Source files allowed to call ``.to_csv`` themselves instead of
``contactlab.tables.write_csv``, with the reason."""


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


def _to_csv_calls(path):
    """Lines of ``path`` calling ``X.to_csv(...)``."""
    return [
        node.lineno
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
        if isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr == "to_csv"
    ]


def test_every_csv_table_the_packages_write_is_spreadsheet_safe():
    unsafe = [
        f"{path.relative_to(ROOT)}:{line}"
        for package in ("contactlab", "dem_check")
        for path in sorted((ROOT / package).rglob("*.py"))
        if str(path.relative_to(ROOT)) not in UNSAFE_WRITERS
        for line in _to_csv_calls(path)
    ]
    assert not unsafe, f"write these through contactlab.tables.write_csv: {unsafe}"


def test_a_table_that_is_not_a_dataframe_is_refused():
    with pytest.raises(ParameterError, match="table must be a DataFrame"):
        spreadsheet_safe([["=1+1"]])


def _rows(text):
    """The rows of CSV ``text`` as Python's own csv module reads them (line breaks kept)."""
    return list(csv.reader(io.StringIO(text, newline="")))


def test_a_carriage_return_in_a_text_cell_does_not_split_its_row():
    table = pd.DataFrame(
        {"file": ["a\rb.csv", "c\r\nd", "e"], "peak [N]": [1.5, float("nan"), 2.0]}
    )
    out = io.StringIO(newline="")
    write_csv(table, out)
    rows = _rows(out.getvalue())
    assert len(rows) == 4  # header and three records: no row split at the line breaks
    assert [r[0] for r in rows[1:]] == ["a\rb.csv", "c\r\nd", "e"]
    back = pd.read_csv(io.StringIO(out.getvalue(), newline=""))
    assert list(back["file"]) == list(table["file"])
    assert back["peak [N]"].isna().tolist() == [False, True, False]  # NaN written "", read NaN


@given(
    st.lists(st.text(max_size=6), min_size=1, max_size=8),
    st.floats(allow_nan=True, allow_infinity=False),
)
def test_write_csv_keeps_every_row_and_every_text_cell(cells, number):
    table = pd.DataFrame({"text": cells, "number [m]": [number] * len(cells)})
    out = io.StringIO(newline="")
    write_csv(table, out)
    rows = _rows(out.getvalue())
    assert len(rows) == len(cells) + 1  # one line per record, whatever the text holds
    assert all(len(row) == 2 for row in rows)
    assert [row[0] for row in rows[1:]] == list(spreadsheet_safe(table)["text"])
