"""Hostile and broken campaign inputs (issues 23, 24): every path a row, no good file lost."""

import os
import shutil
from pathlib import Path

import pandas as pd
import pytest

from contactlab.config import load_config
from contactlab.errors import ParameterError
from dem_check import run_campaign
from dem_check.campaign.inputs import expand_paths

TRACES = Path(__file__).resolve().parents[3] / "data" / "traces"
SENSITIVITY = 0.01124  # [V/N], data/traces/README.md


def _statuses(problems):
    return {Path(p.file).name: p.status for p in problems}


def test_every_odd_entry_of_a_folder_is_a_row(tmp_path):
    folder = tmp_path / "day"
    folder.mkdir()
    record = folder / "a.csv"
    shutil.copy(TRACES / "generic.csv", record)
    (folder / "a.csv.json").write_text("{}", encoding="utf-8")
    (folder / "setup.toml").write_text("", encoding="utf-8")
    (folder / "sub").mkdir()
    (folder / "broken.csv").symlink_to(folder / "gone.csv")
    (folder / "loop.csv").symlink_to(folder / "loop.csv")
    (folder / "same.csv").symlink_to(record)
    os.mkfifo(folder / "pipe.csv")
    files, problems = expand_paths([folder, record, tmp_path / "day" / "." / "a.csv"])
    assert files == [str(record)]
    assert _statuses(problems) == {
        "a.csv.json": "skipped",
        "setup.toml": "skipped",
        "sub": "sub-folder",
        "broken.csv": "broken link",
        "loop.csv": "link loop",
        "same.csv": "duplicate",
        "pipe.csv": "not a file",
        "a.csv": "duplicate",  # the same file named twice more; listed once each
    }
    assert sum(p.status == "duplicate" for p in problems) == 3


def test_an_unreadable_folder_is_a_row_not_an_abort(tmp_path, monkeypatch):
    locked = tmp_path / "locked"
    locked.mkdir()
    listing = Path.iterdir

    def refuse(path):  # chmod 0 does not stop root, who runs CI: the OS's answer instead
        if path == locked:
            raise PermissionError(13, "Permission denied", str(path))
        return listing(path)

    monkeypatch.setattr(Path, "iterdir", refuse)
    files, problems = expand_paths([locked, TRACES / "generic.csv"])
    assert files == [str(TRACES / "generic.csv")]
    assert _statuses(problems) == {"locked": "unreadable folder"}


def test_out_holding_a_record_is_refused(tmp_path):
    setup = load_config(TRACES / "model_hard.toml")
    shutil.copy(TRACES / "generic.csv", tmp_path / "files.csv")  # a record named files.csv
    with pytest.raises(ParameterError, match=r"out = .* holds the input"):
        run_campaign(tmp_path, setup.sensor, setup.grain, out=tmp_path)
    assert (tmp_path / "files.csv").read_bytes() == (TRACES / "generic.csv").read_bytes()


def test_a_damaged_file_costs_no_other_file_its_rows(tmp_path, monkeypatch):
    records = tmp_path / "records"
    records.mkdir()
    hostile = records / "=HYPERLINK(1).csv"
    shutil.copy(TRACES / "generic.csv", hostile)
    whole = (TRACES / "daq.h5").read_bytes()
    (records / "daq.h5").write_bytes(whole[: len(whole) // 2])  # cut short in a copy
    (records / "no\rtes.md").write_text("# notes\n", encoding="utf-8")  # a line break in a name
    setup = load_config(TRACES / "model_hard.toml")
    out = tmp_path / "out"
    monkeypatch.chdir(records)  # file names as given: relative, starting with "="
    result = run_campaign(
        ".", setup.sensor, setup.grain, sensitivity=SENSITIVITY, gallery=0, out=out
    )
    status = dict(
        zip(result.files["file"].map(lambda f: Path(f).name), result.files["status"], strict=True)
    )
    assert status == {"=HYPERLINK(1).csv": "ok", "daq.h5": "unreadable", "no\rtes.md": "skipped"}
    assert result.summary()["files_skipped"] == 1
    written = pd.read_csv(out / "files.csv")
    assert len(written) == 3  # every row written, the good file's among them, none split
    assert written["file"].map(lambda f: Path(f).name).tolist().count("no\rtes.md") == 1
    assert not written["file"].str.startswith("=").any()
    assert written["file"].str.startswith("'=").sum() == 1
    assert (pd.read_csv(out / "impacts.csv")["file"].str.startswith("'=")).all()
