"""One unsolvable row costs no other row its numbers (issue 24): named, marked, NaN."""

import numpy as np
import pandas as pd
import pytest

from contactlab.batch import linear_impacts
from contactlab.batch.rows import ERROR_COLUMN, RESULT_COLUMNS
from contactlab.errors import RowFailedWarning

GOOD = {"m1 [kg]": 1e-3, "k1 [N/m]": 7.9e7, "c1 [N*s/m]": 1.0, "m2 [kg]": 5e-5,
        "k2 [N/m]": 1e5, "c2 [N*s/m]": 1.0, "v0 [m/s]": 2.0}  # fmt: skip
UNSOLVABLE = {**GOOD, "k2 [N/m]": 1e300}  # the system matrix overflows to inf


@pytest.mark.parametrize("threads", [1, 2])
def test_the_failing_row_is_named_marked_and_the_others_solved(threads):
    rows = [GOOD, {**GOOD, "v0 [m/s]": 1.0}, UNSOLVABLE, {**GOOD, "m2 [kg]": 1e-4}]
    frame = pd.DataFrame(rows, index=["a", "b", "bad", "d"])
    with pytest.warns(RowFailedWarning, match=r"1 of 4 rows .* row 2 \(index 'bad'\)"):
        out = linear_impacts(frame, chunk=2, threads=threads)
    good = frame.drop(index="bad")
    expected = linear_impacts(good)
    # the same rows solved without the bad one: the same numbers, bit for bit
    np.testing.assert_array_equal(
        out.loc[good.index, list(RESULT_COLUMNS)].to_numpy(),
        expected[list(RESULT_COLUMNS)].to_numpy(),
    )
    assert out.loc["bad", list(RESULT_COLUMNS)].isna().all()
    assert out[ERROR_COLUMN].ne("").tolist() == [False, False, True, False]
    assert "overflow" in out.loc["bad", ERROR_COLUMN]


def test_a_batch_without_failures_has_no_error_column():
    assert ERROR_COLUMN not in linear_impacts(pd.DataFrame([GOOD]))
