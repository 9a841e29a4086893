"""Population statistics, the metadata join and the regressions, on hand-made tables."""

import numpy as np
import pandas as pd
import pytest

from contactlab.errors import ParameterError
from dem_check.campaign.statistics import (
    join_metadata,
    numeric_predictors,
    population_statistics,
    regressions,
)


@pytest.fixture
def impacts():
    rng = np.random.default_rng(3)
    rows = []
    for file in ("a.csv", "b.csv"):
        for k in range(6):
            rows.append(
                {
                    "file": f"/lab/{file}",
                    "impact": k,
                    "status": "ok" if k < 5 else "overlap",
                    "peak_contact_force [N]": rng.uniform(1.0, 3.0),
                    "contact_time [s]": rng.uniform(90e-6, 110e-6),
                    "fit_stiffness [N/m]": rng.uniform(3e4, 5e4),
                    "fit_stiffness_low [N/m]": 1.0,
                    "fit_stiffness_identifiable": True,
                }
            )
    return pd.DataFrame(rows)


def test_statistics_per_file_and_overall(impacts):
    stats = population_statistics(impacts).set_index(["group", "quantity"])
    assert set(stats.index.get_level_values("group")) == {"/lab/a.csv", "/lab/b.csv", "all"}
    # the fitted value is described, its interval and flag are not
    quantities = set(stats.index.get_level_values("quantity"))
    assert "fit_stiffness [N/m]" in quantities
    assert not {"fit_stiffness_low [N/m]", "fit_stiffness_identifiable"} & quantities
    ok = impacts[impacts["status"] == "ok"]
    values = ok.loc[ok["file"] == "/lab/b.csv", "contact_time [s]"].to_numpy()
    row = stats.loc[("/lab/b.csv", "contact_time [s]")]
    assert row["count"] == 5  # the overlap row is not described
    # the same numbers computed by numpy: equal to rounding
    assert row["mean"] == pytest.approx(values.mean(), rel=1e-12)
    assert row["q05"] == pytest.approx(np.quantile(values, 0.05), rel=1e-12)
    assert row["min"] == values.min() and row["max"] == values.max()


def test_regression_recovers_a_planted_line(impacts):
    meta = pd.DataFrame({"file": ["a.csv", "b.csv"], "moisture [%]": [10.0, 14.0]})
    joined, notes = join_metadata(impacts, meta)
    assert notes == []
    joined["drop_height [m]"] = np.linspace(0.1, 1.0, len(joined))
    joined["peak_contact_force [N]"] = 0.5 + 2.0 * joined["drop_height [m]"]
    lines = regressions(joined, ["drop_height [m]", "moisture [%]"]).set_index(
        ["response", "predictor"]
    )
    line = lines.loc[("peak_contact_force [N]", "drop_height [m]")]
    # an exact line: slope and intercept to rounding, r = 1
    assert line["slope"] == pytest.approx(2.0, rel=1e-12)
    assert line["intercept"] == pytest.approx(0.5, rel=1e-12)
    assert line["r"] == pytest.approx(1.0, rel=1e-12) and line["n"] == 10
    assert line["slope_unit"] == "N/m"
    assert lines.loc[("contact_time [s]", "moisture [%]"), "n"] == 10


def test_regression_says_why_a_line_is_missing(impacts):
    joined = impacts.assign(**{"height [m]": 0.5, "few [-]": np.nan})
    joined.loc[:2, "few [-]"] = [1.0, 2.0, 3.0]
    lines = regressions(joined, ["height [m]", "few [-]"]).set_index(["response", "predictor"])
    assert "constant" in lines.loc[("contact_time [s]", "height [m]"), "note"]
    assert lines.loc[("contact_time [s]", "few [-]"), "note"] == ""  # three points suffice
    joined.loc[2, "few [-]"] = np.nan
    lines = regressions(joined, ["few [-]"])
    assert (lines["note"] == "fewer than 3 ok impacts with both values").all()


def test_metadata_join_per_impact_and_notes(impacts):
    meta = pd.DataFrame(
        {"file": ["/lab/a.csv", "a.csv", "c.csv"], "impact": [0, 1, 0], "batch": ["x", "y", "z"]}
    )
    joined, notes = join_metadata(impacts, meta)
    a = joined[joined["file"] == "/lab/a.csv"].set_index("impact")
    assert a.loc[0, "batch"] == "x" and a.loc[1, "batch"] == "y" and pd.isna(a.loc[2, "batch"])
    assert notes == [
        "metadata: no row for /lab/b.csv",
        "metadata: c.csv names no record of the campaign",
    ]
    assert numeric_predictors(joined, ["batch"]) == []


def test_bad_metadata_is_refused(impacts, tmp_path):
    with pytest.raises(ParameterError, match="no 'file' column"):
        join_metadata(impacts, pd.DataFrame({"name": ["a.csv"]}))
    with pytest.raises(ParameterError, match="two rows"):
        join_metadata(impacts, pd.DataFrame({"file": ["a.csv", "a.csv"], "x": [1, 2]}))
    with pytest.raises(ParameterError, match="replace the impacts' own columns"):
        join_metadata(impacts, pd.DataFrame({"file": ["a.csv"], "status": ["dry"]}))
    with pytest.raises(ParameterError, match="cannot read"):
        join_metadata(impacts, tmp_path / "missing.csv")
