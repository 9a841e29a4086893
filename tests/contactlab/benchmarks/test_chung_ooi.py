"""The Chung & Ooi benchmark runs, grades against theory, and says what it did not run."""

from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.cli import main


def test_every_graded_number_passes(tmp_path):
    report = run_chung_ooi(tmp_path)
    assert {r["test"] for r in report["rows"]} == {1, 2, 3, 4, 6}
    assert all(r["passed"] for r in report["rows"]), [r for r in report["rows"] if not r["passed"]]
    assert set(report["not_run"]) == {5, 7, 8, 9}
    assert len(report["figures"]) == 5 and all(p.exists() for p in report["figures"])
    assert (tmp_path / "chung_ooi.csv").exists()


def test_command_line(tmp_path, capsys):
    assert main(["benchmark", "chung-ooi", "--out", str(tmp_path)]) == 0
    assert "0 failed" in capsys.readouterr().out
