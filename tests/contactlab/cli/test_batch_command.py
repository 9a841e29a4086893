"""The ``contactlab batch`` command: a CSV table through the batch solvers."""

import csv
import re

import numpy as np
import pandas as pd
import pytest

from contactlab.batch import RESULT_COLUMNS, hertz_impacts, linear_impacts
from contactlab.cli import main

LINEAR = {
    "m1 [kg]": [1.233e-3, np.inf],
    "k1 [N/m]": [7.79e7, np.inf],
    "c1 [N*s/m]": [12.4, 0.0],
    "m2 [kg]": [5e-5, 5e-5],
    "k2 [N/m]": [1e5, 2e5],
    "c2 [N*s/m]": [1.0, 0.5],
    "v0 [m/s]": [2.0, 1.5],
}


def write(path, columns, extra=None):
    frame = pd.DataFrame({**columns, **(extra or {})})
    frame.to_csv(path, index=False)
    return frame


def test_a_linear_table_gets_the_batch_solvers_numbers(tmp_path):
    frame = write(tmp_path / "in.csv", LINEAR, {"label": ["disc", "wall"]})
    assert (
        main(
            [
                "batch",
                str(tmp_path / "in.csv"),
                "--law",
                "linear",
                "--out",
                str(tmp_path / "out.csv"),
            ]
        )
        == 0
    )
    got = pd.read_csv(tmp_path / "out.csv")
    assert got["label"].tolist() == ["disc", "wall"]  # other columns are kept
    want = linear_impacts(frame)[list(RESULT_COLUMNS)]
    # CSV keeps 17 significant digits: the numbers come back exactly
    np.testing.assert_array_equal(got[list(RESULT_COLUMNS)].to_numpy(), want.to_numpy())


def test_a_hertz_table_with_its_tolerance_goes_to_stdout(tmp_path, capsys):
    columns = {k: v for k, v in LINEAR.items() if not k.startswith(("k2", "c2"))}
    columns.update({"k_hertz [N/m**1.5]": [5.6e6, 5.6e6], "damping [N*s/m**1.25]": [0.05, 0.0]})
    frame = write(tmp_path / "in.csv", columns)
    assert main(["batch", str(tmp_path / "in.csv"), "--law", "hertz", "--rtol", "1e-10"]) == 0
    got = pd.read_csv(pd.io.common.StringIO(capsys.readouterr().out))
    want = hertz_impacts(frame, rtol=1e-10)[list(RESULT_COLUMNS)]
    np.testing.assert_array_equal(got[list(RESULT_COLUMNS)].to_numpy(), want.to_numpy())


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("200000.0", "2e5x", r"in.csv, line 3: column 'k2 \[N/m\]' holds '2e5x'"),
        ("\n", "\n\n", r"in.csv: column 'm1 \[kg\]' .* \(index 'line 2'\) holds nan"),
        ("v0 [m/s]", "v0 [km/h]", r"no column\(s\) \['v0 \[m/s\]'\]"),
    ],
    ids=["bad cell", "blank line", "missing column"],
)
def test_a_bad_table_is_named_by_file_and_line(tmp_path, capsys, old, new, message):
    path = tmp_path / "in.csv"
    write(path, LINEAR)
    path.write_text(path.read_text().replace(old, new, 1))  # "\n": a blank line after the header
    assert main(["batch", str(path), "--law", "linear"]) == 2
    assert re.search(message, capsys.readouterr().err)


def test_missing_file_and_misplaced_options_are_refused(tmp_path, capsys):
    assert main(["batch", str(tmp_path / "none.csv"), "--law", "linear"]) == 2
    assert "table file not found" in capsys.readouterr().err
    write(tmp_path / "in.csv", LINEAR)
    assert main(["batch", str(tmp_path / "in.csv"), "--law", "linear", "--rtol", "1e-8"]) == 2
    assert "--rtol applies to --law hertz only" in capsys.readouterr().err


def test_a_table_with_an_unsolvable_row_is_written_and_exits_1(tmp_path, capsys):
    columns = {name: [values[0]] * 3 for name, values in LINEAR.items()}
    columns["k2 [N/m]"] = [1e5, 1e300, 2e5]  # the middle row's system matrix overflows
    write(tmp_path / "in.csv", columns)
    argv = ["batch", str(tmp_path / "in.csv"), "--law", "linear", "--out", str(tmp_path / "o.csv")]
    assert main(argv) == 1
    got = pd.read_csv(tmp_path / "o.csv", keep_default_na=False)
    assert got["error"].ne("").tolist() == [False, True, False]  # the failing row is marked
    assert (got.loc[[0, 2], "restitution [-]"].astype(float) > 0).all()  # the others solved
    err = capsys.readouterr().err
    assert "1 of 3 rows could not be solved" in err and "2 impacts solved" in err
    assert "Traceback" not in err


HOSTILE = ["=cmd|' /C calc'!A0", "+1", "-2+3", "@SUM(1)", "\tx", "\rx", "plain", "a=b"]


def test_formula_cells_of_the_users_columns_are_neutralised(tmp_path):
    rows = len(HOSTILE)
    columns = {name: [values[0]] * rows for name, values in LINEAR.items()}
    offsets = [-1.5, -2.0, 0.0, 3.25, -1e-9, 7.0, -0.5, 2.0]
    frame = pd.DataFrame({**columns, "label": HOSTILE, "offset [m]": offsets})
    frame.to_csv(tmp_path / "in.csv", index=False, quoting=csv.QUOTE_NONNUMERIC)  # "\rx" quoted
    out = tmp_path / "out.csv"
    assert main(["batch", str(tmp_path / "in.csv"), "--law", "linear", "--out", str(out)]) == 0
    with out.open(newline="", encoding="utf-8") as fh:  # raw cells, not pandas' reading
        header, *body = csv.reader(fh)
    label, offset = header.index("label"), header.index("offset [m]")
    want = [("'" + cell if cell[0] in "=+-@\t\r" else cell) for cell in HOSTILE]
    assert [row[label] for row in body] == want
    # a negative number is a number: written bare, read back exactly
    assert [float(row[offset]) for row in body] == offsets
    assert not any(row[offset].startswith("'") for row in body)
    assert len(body) == rows and "error" not in header  # every row solved
