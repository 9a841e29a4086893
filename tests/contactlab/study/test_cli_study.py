"""Command line: ``contactlab study`` and ``contactlab advise``."""

import json
import os

import pytest

from contactlab.cli import _build_parser, main


@pytest.mark.parametrize("command", ["study", "advise"])
def test_help(command, capsys):
    with pytest.raises(SystemExit) as info:
        main([command, "--help"])
    assert info.value.code == 0
    assert "usage:" in capsys.readouterr().out


def test_study_paper_quick_json(tmp_path, capsys):
    assert main(["study", "--paper", "--quick", "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert {c["number"] for c in summary["conclusions"]} == {2, 3, 4, 5}
    assert summary["impacts"] > 0
    for name in ("error_vs_frequency.csv", "error_vs_diameter.csv", "summary.md", "fig12.svg"):
        assert (tmp_path / name).exists()


def test_study_needs_paper(tmp_path, capsys):
    assert main(["study", "--out", str(tmp_path)]) == 2
    assert "--paper" in capsys.readouterr().err


def test_advise_species_text_and_json(capsys):
    args = ["advise", "rapeseed", "--cases", "centre", "--target", "5", "--resonance", "70e3"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "lowest sensor resonance" in text and "a 70 kHz sensor" in text
    assert main([*args, "--json"]) == 0
    advice = json.loads(capsys.readouterr().out)
    assert advice["lowest_resonance [Hz]"] > 70e3  # rapeseed: about 120 kHz for 5 %
    assert advice["worst_error_at_resonance [%]"] > 5.0


def test_advise_explicit_grain_and_list(capsys):
    args = [
        "advise",
        "--diameter",
        "2e-3,2.5e-3",
        "--density",
        "1100",
        "--youngs-modulus",
        "1.5e8",
        "--cases",
        "centre",
        "--json",
    ]
    assert main(args) == 0
    advice = json.loads(capsys.readouterr().out)
    assert advice["species"]["diameter [m]"] == [2e-3, 2.5e-3]
    assert main(["advise", "--list"]) == 0
    assert "wheat" in capsys.readouterr().out.split()


def test_advise_errors_are_named(capsys):
    assert (
        main(
            ["advise", "wheat", "--diameter", "3e-3", "--density", "1e3", "--youngs-modulus", "1e8"]
        )
        == 2
    )
    assert "not both" in capsys.readouterr().err
    # a preset carries its own Poisson ratio: a second one would be silently ignored
    assert main(["advise", "wheat", "--poisson-ratio", "0.4"]) == 2
    assert "not both" in capsys.readouterr().err
    assert main(["advise", "wheet"]) == 2
    assert "Did you mean 'wheat'" in capsys.readouterr().err
    assert main(["advise", "wheat", "--target", "-1"]) == 2
    assert "target" in capsys.readouterr().err
    with pytest.raises(SystemExit) as info:
        main(["advise", "--diameter", "2 mm", "--density", "1e3", "--youngs-modulus", "1e8"])
    assert info.value.code == 2
    assert "--diameter: give a number or LOW,HIGH; got '2 mm'" in capsys.readouterr().err


@pytest.mark.parametrize("command", [["study", "--paper"], ["demo"]])
def test_study_and_demo_use_every_core_by_default(command):
    """Issue 15: the study runs on every core unless --workers says otherwise."""
    parser = _build_parser()
    assert parser.parse_args(command).workers == (os.cpu_count() or 1)
    assert parser.parse_args([*command, "--workers", "1"]).workers == 1
