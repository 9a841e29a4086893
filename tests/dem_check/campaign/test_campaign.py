"""A whole campaign on synthetic long records with a known truth (see conftest.campaign).

Seven good records (the hard grain in five formats at 1, 2 and 5 MHz, in volts and in
newtons, plus a soft linear grain and a damped-Hertz grain), three impacts each, with
about 1 % noise; and four bad inputs that must be listed while the rest is analysed.
"""

import os
import re

import numpy as np
import pandas as pd
import pytest

from contactlab.errors import ParameterError
from dem_check.campaign import run_campaign
from dem_check.campaign.statistics import QUANTILES


def _matched(campaign):
    """(file name, impacts of that file, truth) for every good record."""
    result = campaign["result"]
    for name, truth in campaign["truth"].items():
        rows = result.impacts[result.impacts["file"] == str(campaign["folder"] / name)]
        yield name, rows.reset_index(drop=True), truth


def test_every_impact_is_found_and_none_invented(campaign):
    for name, rows, truth in _matched(campaign):
        assert len(rows) == len(truth), name
        assert (rows["status"] == "ok").all(), rows[["status", "reason"]]


def test_onsets_within_10_us(campaign):
    errors = np.concatenate(
        [rows["onset [s]"] - truth["onset [s]"] for _, rows, truth in _matched(campaign)]
    )
    # the requirement; measured: within 2.5 us at 1-5 MHz and 0.3-6 % noise
    assert np.abs(errors).max() < 10e-6


def test_peak_sensor_force_within_2_percent(campaign):
    for name, rows, truth in _matched(campaign):
        error = rows["peak_sensor_force [N]"] / truth["peak_sensor_force [N]"] - 1.0
        # the requirement (the flat Butterworth pass leaves 0.1 %, noise the rest)
        assert np.abs(error).max() < 0.02, (name, error.tolist())


def test_reconstruction_within_5_percent_where_the_raw_signal_is_far_off(campaign):
    hard = [m for m in _matched(campaign) if m[0].startswith("hard")]
    truth = pd.concat([t for _, _, t in hard])
    rows = pd.concat([r for _, r, _ in hard])
    raw_error = truth["peak_sensor_force [N]"] / truth["peak_contact_force [N]"] - 1.0
    # the set-up the issue asks for: a grain whose raw peak is 30-45 % off
    assert ((raw_error > 0.30) & (raw_error < 0.45)).all()
    for column in ("peak_contact_force [N]", "contact_time [s]"):
        error = rows[column].to_numpy() / truth[column].to_numpy() - 1.0
        # the requirement; measured up to 2.5 % (docs/campaign.md)
        assert np.abs(error).max() < 0.05, (column, error)


def test_impulse_and_velocity_change(campaign, hard_setup):
    grain = hard_setup[0]
    for name, rows, truth in _matched(campaign):
        error = rows["impulse [N*s]"] / truth["impulse [N*s]"] - 1.0
        # noise integrated over the ~1 ms segment and the local baseline's mean: ~1 %
        assert np.abs(error).max() < 0.03, (name, error.tolist())
        change = truth["velocity [m/s]"] * (1.0 + truth["restitution [-]"])
        # impulse / mass = (1 + e) v: the same 3 % as the impulse
        np.testing.assert_allclose(rows["velocity_change [m/s]"], change, rtol=0.03)
        np.testing.assert_allclose(  # the same division: equal to rounding
            rows["velocity_change [m/s]"], rows["impulse [N*s]"] / grain.mass, rtol=1e-12
        )


def test_bad_inputs_are_listed_and_the_others_analysed(campaign):
    files = campaign["result"].files.set_index("file")
    for path, status in campaign["bad"].items():
        assert files.loc[path, "status"] == status
        assert os.path.basename(path) in files.loc[path, "reason"]
    good = files.drop(index=list(campaign["bad"]))
    assert (good["status"] == "ok").all()
    assert (good["impacts_ok"] == 3).all()
    volts = files.loc[str(campaign["folder"] / "scope2.csv"), "reason"]
    assert "sensitivity" in volts
    unknown = files.loc[str(campaign["folder"] / "notes.bin"), "reason"]
    assert "not a readable oscilloscope binary" in unknown


def test_units_and_formats_of_each_file(campaign):
    files = campaign["result"].files.set_index("file")
    tdms = files.loc[str(campaign["folder"] / "hard_daq.tdms")]
    assert tdms["unit"] == "N" and pd.isna(tdms["sensitivity [V/N]"])
    rigol = files.loc[str(campaign["folder"] / "hard_rigol.csv")]
    assert rigol["unit"] == "V" and rigol["format"] == "rigol-sequence"
    assert rigol["sample_rate [Hz]"] == pytest.approx(5e6, rel=1e-9)  # read from the file


def test_statistics_are_those_of_the_ok_impacts(campaign):
    result = campaign["result"]
    stats = result.statistics.set_index(["group", "quantity"])
    for group, frame in [("all", result.ok), *result.ok.groupby("file")]:
        for quantity in ("peak_contact_force [N]", "contact_time [s]", "impulse [N*s]"):
            values = frame[quantity].to_numpy()
            row = stats.loc[(group, quantity)]
            assert row["count"] == values.size
            # the same numbers computed by numpy: equal to rounding
            assert row["mean"] == pytest.approx(values.mean(), rel=1e-12)
            assert row["std"] == pytest.approx(values.std(ddof=1), rel=1e-12)
            assert row["median"] == pytest.approx(np.quantile(values, 0.5), rel=1e-12)
            assert row["q95"] == pytest.approx(np.quantile(values, QUANTILES[-1]), rel=1e-12)


def test_regression_finds_the_linear_laws_proportionality(campaign):
    """For a linear contact law the peak force is proportional to the impact velocity."""
    result = campaign["result"]
    line = result.regressions.set_index(["response", "predictor"]).loc[
        ("peak_contact_force [N]", "velocity [m/s]")
    ]
    hard = pd.concat([t for n, _, t in _matched(campaign) if n.startswith("hard")])
    assert line["n"] == len(hard)  # the impacts with a metadata row
    ratio = (hard["peak_contact_force [N]"] / hard["velocity [m/s]"]).to_numpy()
    # the law's exact ratio is the same for every hard impact (a linear system)
    assert np.ptp(ratio) / ratio.mean() < 1e-6
    # slope and intercept of force = ratio * v, up to the reconstruction's scatter
    # (< 2.5 % per impact) over a 1.5-2.5 m/s spread: a few per cent of the slope
    assert line["slope"] == pytest.approx(ratio.mean(), rel=0.05)
    assert abs(line["intercept"]) < 0.05 * hard["peak_contact_force [N]"].mean()
    assert line["r"] > 0.98 and line["p_value"] < 1e-6  # 15 points on a line, 2 % scatter
    assert line["slope_unit"] == "N/(m/s)"
    assert any("soft.csv" in n for n in result.notes)
    assert any("day2.csv" in n for n in result.notes)


def test_outputs_read_back(campaign):
    out, result = campaign["out"], campaign["result"]
    impacts = pd.read_csv(out / "impacts.csv", keep_default_na=False, na_values=[""])
    assert list(impacts.columns) == list(result.impacts.columns)
    # pandas writes floats as their shortest repr: the round trip is exact
    np.testing.assert_allclose(impacts["onset [s]"], result.impacts["onset [s]"], rtol=1e-15)
    files = pd.read_csv(out / "files.csv", keep_default_na=False, na_values=[""])
    assert files["file"].tolist() == result.files["file"].tolist()
    assert files["status"].tolist() == result.files["status"].tolist()
    for name in ("statistics.csv", "regressions.csv", "settings.json", "report.html"):
        assert (out / name).stat().st_size > 0


def test_report_is_self_contained(campaign):
    page = (campaign["out"] / "report.html").read_text(encoding="utf-8")
    assert "<script" not in page
    assert not re.search(r"""(src|href)\s*=\s*["'](?!data:|#)""", page)  # nothing fetched
    assert not re.search(r"url\(\s*['\"]?(?!#|data:)", page)  # no stylesheet resource
    assert "@import" not in page and "@font-face" not in page
    assert page.count("<svg") >= 4  # distributions, regressions, gallery, records


def test_report_renders_in_chromium(campaign, open_in_chromium):
    result = campaign["result"]
    page = open_in_chromium(campaign["out"] / "report.html")
    assert page["errors"] == []
    assert page["resources"] == [] and page["scripts"] == 0
    assert page["ids"]["impact-count"] == str(len(result.impacts))
    assert page["ids"]["file-count"] == str(len(result.files))
    for file in result.files["file"]:
        assert file in page["ids"]["files"]  # every file, the failed ones too
    for path in campaign["bad"]:
        assert path in page["ids"]["failures"]
    assert page["svgs"] >= 4 and page["drawn"] == page["svgs"]
    assert page["uniqueIds"] == page["idCount"] > 100  # every id unique, the figures' too


def test_browser_check_catches_console_errors_and_missing_resources(tmp_path, open_in_chromium):
    """The check above can fail: a planted error, exception and missing image are seen."""
    page = tmp_path / "broken.html"
    page.write_text(
        '<!DOCTYPE html><html><head><meta charset="utf-8"><title>t</title></head><body>'
        '<img src="missing.png"><script>console.error("planted"); no_such_function();'
        "</script></body></html>",
        encoding="utf-8",
    )
    errors = open_in_chromium(page)["errors"]
    assert any("planted" in e for e in errors)
    assert any(e.startswith("exception") for e in errors)
    assert any("missing.png" in e for e in errors)


def test_campaign_of_nothing_raises(tmp_path, hard_setup):
    grain, sensor, _ = hard_setup
    with pytest.raises(ParameterError, match="holds no file"):
        run_campaign(tmp_path, sensor, grain)
    with pytest.raises(ParameterError, match="matches no file"):
        run_campaign(str(tmp_path / "*.csv"), sensor, grain)
    with pytest.raises(ParameterError, match="paths is empty"):
        run_campaign([], sensor, grain)
