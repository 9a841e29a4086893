"""The pytest plugin, run as a user would: fixtures, golden flag and ini option, the docs."""

import re
import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).parents[3] / "docs" / "testing.md"

GOLDEN_TEST = """
import contactlab as cl

def test_impact(paper_grain, paper_sensor, golden):
    law = cl.laws.LinearViscoelastic(1e5, DAMPING)
    golden.check("hard_grain", cl.simulate_impact(paper_grain, paper_sensor, law, 2.0))
"""


@pytest.fixture
def project(pytester, monkeypatch):
    """A fresh folder with a pytest.ini; no bytecode cache, so rewritten files are reread."""
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    pytester.makeini("[pytest]\naddopts = --strict-markers\nfilterwarnings = error\n")
    return pytester


def golden_test(pytester, damping):
    pytester.makepyfile(test_golden=GOLDEN_TEST.replace("DAMPING", damping))


def test_fixtures_are_the_papers(project):
    project.makepyfile(
        """
        def test_fixtures(paper_grain, paper_grain_small, paper_sensor, rigid_sensor):
            assert round(paper_grain.mass * 1e5, 3) == 5.007
            assert paper_grain_small.diameter == 2.5e-3
            assert paper_grain_small.youngs_modulus == paper_grain.youngs_modulus == 21.6e6
            assert abs(paper_sensor.resonance - 40e3) < 1e-9  # k1 = m1 (2 pi f)**2: rounding
            assert round(paper_sensor.mass * 1e3, 3) == 1.233
            assert rigid_sensor.is_rigid
        """
    )
    # a subprocess, as a user runs it: the plugin comes from the installed entry point
    project.runpytest_subprocess().assert_outcomes(passed=1)


def test_golden_is_written_only_on_request(project):
    golden_test(project, "1.0")
    first = project.runpytest()
    first.assert_outcomes(failed=1)
    first.stdout.fnmatch_lines(["*golden reference 'hard_grain' not found*"])
    assert "--contactlab-update-golden" in first.stdout.str()
    assert not (project.path / "tests" / "golden").exists()

    update = project.runpytest("--contactlab-update-golden")
    update.assert_outcomes(passed=1)
    update.stdout.fnmatch_lines(
        [
            "contactlab: updating golden references in *tests/golden",
            "*contactlab golden references written*",
            "created */tests/golden/hard_grain.json and hard_grain.npz (it did not exist)",
        ]
    )
    assert sorted(p.name for p in (project.path / "tests" / "golden").iterdir()) == [
        "hard_grain.json",
        "hard_grain.npz",
    ]
    again = project.runpytest()
    again.assert_outcomes(passed=1)
    assert "golden references written" not in again.stdout.str()

    golden_test(project, "1.02")
    perturbed = project.runpytest()
    perturbed.assert_outcomes(failed=1)
    perturbed.stdout.fnmatch_lines(
        [
            "*impact differs from golden reference 'hard_grain'*",
            "*restitution *-*NO*",
            "*law_parameters.damping: 1.0 -> 1.02*",
        ]
    )


def test_golden_marker_and_directory_option(project):
    project.makeini("[pytest]\ncontactlab_golden_dir = refs\naddopts = --strict-markers\n")
    golden_test(project, "1.0")
    project.makepyfile(test_other="def test_other():\n    pass\n")
    project.runpytest("-m", "golden", "--contactlab-update-golden").assert_outcomes(
        passed=1, deselected=1
    )
    assert (project.path / "refs" / "hard_grain.json").is_file()
    project.runpytest("-m", "not golden").assert_outcomes(passed=1, deselected=1)


def doc_files():
    """The files the docs' worked example is made of: blocks starting ``# file: name``."""
    text = DOCS.read_text(encoding="utf-8")
    return dict(re.findall(r"```(?:python|ini)\n# file: (\S+)\n(.*?)```", text, re.S))


def test_docs_example_runs_as_written(pytester, monkeypatch):
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    files = doc_files()
    assert set(files) == {"hertz_dashpot.py", "pytest.ini", "test_hertz_dashpot.py"}
    for name, text in files.items():
        (pytester.path / name).write_text(text, encoding="utf-8")
    created = pytester.runpytest("--contactlab-update-golden")
    created.assert_outcomes(passed=3)
    created.stdout.fnmatch_lines(["created */golden/hertz_dashpot_40khz.json*"])
    pytester.runpytest().assert_outcomes(passed=3)

    law = pytester.path / "hertz_dashpot.py"
    source = law.read_text(encoding="utf-8")
    assert source.count("self.damping * rate") == 1
    law.write_text(source.replace("self.damping * rate", "1.02 * self.damping * rate"))
    perturbed = pytester.runpytest()
    perturbed.assert_outcomes(passed=2, failed=1)
    perturbed.stdout.fnmatch_lines(["*impact differs from golden reference 'hertz_dashpot_40khz'*"])
