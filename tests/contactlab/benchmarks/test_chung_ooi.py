"""The Chung & Ooi benchmark runs all nine tests, grades them against theory, cites its inputs."""

import pytest

from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.benchmarks.chung_ooi.cases import CASES
from contactlab.cli import main


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("chung_ooi")
    return out, run_chung_ooi(out)


def test_every_test_runs_and_every_graded_number_passes(report):
    out, got = report
    assert {r["test"] for r in got["rows"]} == set(range(1, 10))
    assert all(r["passed"] for r in got["rows"]), [r for r in got["rows"] if not r["passed"]]
    assert got["not_run"] == {}
    assert len(got["figures"]) == 9 and all(p.exists() for p in got["figures"])
    assert (out / "chung_ooi.csv").exists()


def test_graded_numbers_per_test(report):
    counts = {n: sum(r["test"] == n for r in report[1]["rows"]) for n in range(1, 10)}
    # gross-sliding angles of tests 4 and 5, invariants of 6 and 8, every angle of test 7:
    # a change in the solver's sliding decision or in the cases shows up here
    assert counts == {1: 4, 2: 4, 3: 10, 4: 44, 5: 40, 6: 6, 7: 70, 8: 6, 9: 10}


def test_the_lammps_column_is_empty_without_an_engine(report):
    assert all(r["lammps"] is None and r["lammps_error"] is None for r in report[1]["rows"])
    assert "not run" in report[1]["markdown"]


def test_every_case_cites_its_sources():
    for case in CASES:
        assert case.sources and all(m.source.startswith("[") for m in case.materials)


def test_command_line(tmp_path, capsys):
    assert main(["benchmark", "chung-ooi", "--out", str(tmp_path)]) == 0
    assert "0 failed" in capsys.readouterr().out
