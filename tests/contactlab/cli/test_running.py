"""Both command lines: one-line warnings and errors, --strict, flags in messages, negative
numbers, strict JSON, quiet pipes, the first run's notice, init and presets --show."""

import json
import math
import subprocess
import sys

import pytest
from documents import PAPER_CASE, PAPER_SENSOR

from contactlab.cli import _build_parser
from contactlab.cli import main as contactlab_main
from contactlab.cli.running import in_flags
from contactlab.cli.setup import COMPILE_NOTICE, TEMPLATE, announce_compile
from contactlab.config import PRESET_DIR, load_config
from dem_check.cli import main as dem_check_main


def case(tmp_path, diameter=5e-3, velocity=2.0, rigid=False):
    """The paper's base case as a TOML file, with another grain diameter [m], impact speed
    [m/s] or a rigid sensor."""
    path = tmp_path / "case.toml"
    text = PAPER_CASE.replace("diameter = 5.0e-3", f"diameter = {diameter!r}")
    text = text.replace("velocity = 2.0", f"velocity = {velocity!r}")
    path.write_text(text.replace(PAPER_SENSOR, "rigid = true") if rigid else text)
    return path


def reject_constant(name):
    raise ValueError(f"not strict JSON: {name}")


def strict_loads(text):
    """json.loads that refuses NaN, Infinity and -Infinity (which json.loads accepts)."""
    return json.loads(text, parse_constant=reject_constant)


def test_a_warning_is_one_line_and_the_run_goes_on(tmp_path, capsys):
    assert contactlab_main(["simulate", str(case(tmp_path, velocity=200.0))]) == 0
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert lines == [
        "contactlab: warning: velocity = 200 m/s is outside what real grain impacts span "
        "(0.05 to 50 m/s); did you mean 2 m/s (200 given in cm/s) or 0.2 m/s (200 given in "
        "mm/s)? (docs/plausibility.md)"
    ]
    assert "ImpactResult" in captured.out


@pytest.mark.parametrize("where", ["before", "after"])
def test_strict_makes_the_warning_an_error(tmp_path, capsys, where):
    path = str(case(tmp_path, velocity=200.0))
    argv = ["--strict", "simulate", path] if where == "before" else ["simulate", path, "--strict"]
    assert contactlab_main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith("contactlab: error: velocity = 200 m/s")
    assert captured.err.rstrip().endswith("(--strict)")
    assert len(captured.err.strip().splitlines()) == 1


@pytest.mark.parametrize("main", [contactlab_main, dem_check_main])
def test_the_fifty_tonne_grain_ends_in_one_error_line_not_a_traceback(tmp_path, capsys, main):
    argv = ["simulate", str(case(tmp_path, diameter=5.0))]
    if main is dem_check_main:
        argv = ["compare", str(tmp_path / "none.csv"), "--model", argv[1]]
    code = main(argv)
    err = capsys.readouterr().err
    assert "Traceback" not in err and "IndexError" not in err
    assert code == 2
    assert err.splitlines()[-1].startswith(("contactlab: error:", "dem-check: error:"))


def test_messages_speak_in_flags():
    flags = {"window": "--window", "baseline": "--baseline", "damping_ratio": "--damping-ratio"}
    flags["baseline_window"] = "--baseline"
    assert in_flags("give window= after the pulse", flags) == "give --window after the pulse"
    assert in_flags("damping_ratio must be >= 0", flags) == "--damping-ratio must be >= 0"
    assert in_flags("baseline_window [s] is empty", flags) == "--baseline [s] is empty"
    # ordinary words stay words
    assert in_flags("the ringing window is short", flags) == "the ringing window is short"


def test_negative_numbers_are_values():
    args = _build_parser().parse_args(
        ["reconstruct", "t.csv", "--baseline", "-1e-4", "-5e-5", "--resonance", "4e4"]
    )
    assert args.baseline == [-1e-4, -5e-5]
    args = _build_parser().parse_args(["fit", "t.csv", "--law", "linear", "--model", "m.toml"])
    assert args.baseline is None


def test_simulate_json_is_strict_with_reasons_for_nulls(tmp_path, capsys):
    assert contactlab_main(["simulate", str(case(tmp_path, rigid=True)), "--json"]) == 0
    out = strict_loads(capsys.readouterr().out)
    nulls = out["null_reasons"]
    assert nulls, "a rigid sensor has an infinite resonance and mass: they must be null"
    for path, reason in nulls.items():
        node = out
        for part in path.split("."):
            node = node[part]
        assert node is None
        assert "inf" in reason or "NaN" in reason


def test_identify_sensor_labels_a_volt_trace_in_volts(tmp_path, capsys):
    import numpy as np

    from contactlab.traces import Trace
    from dem_check import write_trace

    t = np.arange(-50e-6, 600e-6, 2e-7)
    ring = np.where(t > 0, np.exp(-0.02 * 2 * math.pi * 40e3 * t), 0.0)
    volts = 0.03 * ring * np.sin(2 * math.pi * 40e3 * np.sqrt(1 - 0.02**2) * t)
    path = tmp_path / "ring.csv"
    write_trace(path, Trace(t, volts, "V"), "generic")
    assert contactlab_main(["identify-sensor", str(path), "--json"]) == 0
    out = strict_loads(capsys.readouterr().out)
    assert out["resonance [Hz]"] == pytest.approx(40e3, rel=1e-3)  # noise-free ringing
    assert "amplitude [V]" in out and "offset [V]" in out and "residual_rms [V]" in out
    assert not any(key.endswith("[N]") for key in out)


def test_dem_check_json_is_strict(tmp_path, capsys):
    import numpy as np

    from contactlab.traces import Trace
    from dem_check import write_trace

    config = load_config(PRESET_DIR / "fig6.toml")
    model = config.simulate()
    t = np.concatenate([model.t[:50] - model.t[50], model.t])
    signal = np.concatenate([np.zeros(50), model.sensor_force])
    path = tmp_path / "trace.csv"
    write_trace(path, Trace(t, signal, "N", metadata={"trigger_time": 0.0}), "generic")
    code = dem_check_main(["compare", str(path), "--preset", "fig6", "--json"])
    out = strict_loads(capsys.readouterr().out)
    assert code in (0, 1) and out["physics"] == []


def test_piping_into_head_ends_quietly(tmp_path):
    rows = "\n".join(f"1.233e-3,7.79e7,12.4,5e-5,1e5,1.0,{1 + i / 5000}" for i in range(5000))
    table = tmp_path / "rows.csv"
    table.write_text("m1 [kg],k1 [N/m],c1 [N*s/m],m2 [kg],k2 [N/m],c2 [N*s/m],v0 [m/s]\n" + rows)
    argv = ["batch", str(table), "--law", "linear"]
    code = f"from contactlab.cli import main; raise SystemExit(main({argv!r}))"
    run = subprocess.run(
        f'{sys.executable} -c "{code}" | head -n 2',
        shell=True,
        capture_output=True,
        text=True,
        check=False,
    )
    assert run.stdout.splitlines()[0].startswith('"m1 [kg]",')  # text is quoted
    assert "Traceback" not in run.stderr and "BrokenPipe" not in run.stderr, run.stderr


def test_init_writes_a_template_that_runs_without_a_warning(tmp_path, capsys):
    path = tmp_path / "mine.toml"
    assert contactlab_main(["init", str(path)]) == 0
    assert path.read_text() == TEMPLATE.read_text()
    assert contactlab_main(["--strict", "simulate", str(path)]) == 0  # no warning at all
    assert contactlab_main(["init", str(path)]) == 2  # not overwritten without --force
    assert "--force" in capsys.readouterr().err
    assert contactlab_main(["init", str(path), "--force"]) == 0


def test_presets_show_prints_the_preset(capsys):
    assert contactlab_main(["presets", "--show", "fig6"]) == 0
    assert capsys.readouterr().out == (PRESET_DIR / "fig6.toml").read_text()
    assert contactlab_main(["presets", "--show", "fig66"]) == 2
    assert "Did you mean 'fig6'?" in capsys.readouterr().err


def test_a_cold_cache_is_announced(monkeypatch, capsys):
    import contactlab.batch.warm_up as warm_up

    monkeypatch.setattr(warm_up, "cache_is_warm", lambda: False)
    assert announce_compile("contactlab") is True
    assert capsys.readouterr().err == f"contactlab: {COMPILE_NOTICE}\n"
    monkeypatch.setattr(warm_up, "cache_is_warm", lambda: True)
    assert announce_compile("contactlab") is False
    assert capsys.readouterr().err == ""


def test_batch_reports_compile_and_solve_times_apart(tmp_path, capsys):
    table = tmp_path / "rows.csv"
    table.write_text(
        "m1 [kg],k1 [N/m],c1 [N*s/m],m2 [kg],k2 [N/m],c2 [N*s/m],v0 [m/s]\n"
        "1.233e-3,7.79e7,12.4,5e-5,1e5,1.0,2.0\n"
    )
    assert contactlab_main(["batch", str(table), "--law", "linear"]) == 0
    err = capsys.readouterr().err
    assert "1 impacts solved in" in err and "compiled or loaded before, in" in err


def test_a_repeated_warning_is_printed_once(capsys):
    import warnings

    from contactlab.cli.running import Parser, add_strict, run
    from contactlab.errors import PlausibilityWarning

    def twice(args):
        for _ in range(2):  # a catch_warnings block between resets Python's own registry
            with warnings.catch_warnings():
                pass
            warnings.warn("sensitivity = 11.24 V/N is odd", PlausibilityWarning, stacklevel=1)

    parser = Parser(prog="demo")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("go").set_defaults(func=twice, compiles=False)
    add_strict(parser)
    assert run("demo", parser, ["go"]) == 0
    assert capsys.readouterr().err == "demo: warning: sensitivity = 11.24 V/N is odd\n"
