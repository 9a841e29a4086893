"""Command line: help, presets, TOML configs and clear errors."""

import json
import re

import pytest
from documents import PAPER_CASE as GOOD

import contactlab as cl
from contactlab.cli import main as contactlab_main
from contactlab.config import list_presets, load_config
from contactlab.errors import ParameterError
from dem_check.cli import main as dem_check_main


@pytest.mark.parametrize("main", [contactlab_main, dem_check_main])
def test_help(main, capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    assert "usage:" in capsys.readouterr().out


def test_simulate_config_json(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(GOOD)
    assert (
        contactlab_main(["simulate", str(path), "--json", "--plot", str(tmp_path / "f.png")]) == 0
    )
    summary = json.loads(capsys.readouterr().out)
    grain = cl.Grain(diameter=5e-3, density=765.0)
    sensor = cl.Sensor.from_resonance(40e3, mass=1.233e-3, damping_ratio=0.02)
    direct = cl.simulate_impact(grain, sensor, cl.laws.LinearViscoelastic(1e5, 1.0), 2.0, 500e-6)
    # the same deterministic computation through TOML and through Python
    assert summary["contact_time [s]"] == pytest.approx(direct.contact_time, rel=1e-14)
    assert (tmp_path / "f.png").stat().st_size > 0


@pytest.mark.parametrize("name", list_presets())
def test_presets_run(name, capsys):
    assert contactlab_main(["simulate", "--preset", name]) == 0
    assert "ImpactResult" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (GOOD.replace("damping = 1.0", "dampin = 1.0"), "'dampin' (did you mean 'damping'?)"),
        (GOOD.replace("[simulation]", "[simulaton]"), "'simulaton' (did you mean 'simulation'?)"),
        (GOOD.replace('law = "linear"', 'law = "lineer"'), "Did you mean 'linear'"),
        (GOOD.replace("velocity = 2.0", "velocity = -2.0"), "velocity"),
        (GOOD.replace("duration = 500.0e-6", "durration = 1.0"), "(did you mean 'duration'?)"),
    ],
)
def test_config_errors_name_the_key(tmp_path, capsys, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert contactlab_main(["simulate", str(path)]) == 2
    assert message in capsys.readouterr().err


LINEAR = 'law = "linear"\nstiffness = 1.0e5\ndamping = 1.0'
MATERIAL = "density = 765.0\nshear_modulus = 9e6\npoisson_ratio = 0.2"


CONFIG_ERRORS = {
    # a key the sensor's constructor does not take: named, with the valid ones
    "unknown key named": (
        "damping_ratio = 0.02",
        "damping_ratio = 0.02\ncolour = 1",
        "[sensor]: unknown key(s) 'colour'",
    ),
    "valid keys listed": (
        "damping_ratio = 0.02",
        "damping_ratio = 0.02\ncolour = 1",
        "valid keys are resonance",
    ),
    "missing key named": (
        "damping_ratio = 0.02",
        "thickness = 2e-3",
        "missing required key(s) 'diameter'",
    ),
    # a flag given as a string would be truthy: refused, not guessed
    "rigid as text": (
        "resonance = 40.0e3",
        'rigid = "false"\nresonance = 40.0e3',
        "rigid must be true or",
    ),
    "from_material as text": (
        LINEAR,
        'law = "hertz"\nfrom_material = "no"',
        "from_material must be true or false",
    ),
    "unknown contact key": (
        LINEAR,
        'law = "hertz"\nfrom_material = true\nradus = 1',
        "unknown key(s) 'radus'",
    ),
    "table as a number": (
        f"[grain]\ndiameter = 5.0e-3\n{MATERIAL}\n",
        "grain = 5\n",
        "grain must be a table",
    ),
}
"""Config mistakes: ``(text replaced, replacement, message)`` by what they show."""


@pytest.mark.parametrize(("old", "new", "message"), CONFIG_ERRORS.values(), ids=CONFIG_ERRORS)
def test_config_errors_name_file_table_and_key(tmp_path, old, new, message):
    path = tmp_path / "bad.toml"
    text = GOOD.replace("density = 765.0", MATERIAL)
    assert old in text
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ParameterError, match=re.escape(message)) as info:
        load_config(path)
    assert str(info.value).startswith(f"{path}: ")
    assert str(info.value).count(str(path)) == 1  # named once, not once per level


def test_unreadable_config_file_is_a_parameter_error(tmp_path):
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b"\xff\xfe[grain]\n")
    with pytest.raises(ParameterError, match=r"binary\.toml, byte 0: not UTF-8 text"):
        load_config(binary)
    with pytest.raises(ParameterError, match="cannot read config file"):
        load_config(tmp_path)  # a folder


def test_config_from_material(tmp_path):
    path = tmp_path / "hertz.toml"
    path.write_text(
        GOOD.replace(
            "density = 765.0", "density = 765.0\nshear_modulus = 9e6\npoisson_ratio = 0.2"
        ).replace(
            'law = "linear"\nstiffness = 1.0e5\ndamping = 1.0',
            'law = "hertz"\nfrom_material = true',
        )
    )
    config = load_config(path)
    assert type(config.law).__name__ == "Hertz"


def test_config_second_body_keys_give_the_hertz_closed_form():
    """A [contact] table's other_* keys are the second body of from_material: kH =
    4/3 E* sqrt(R*) with 1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2 and 1/R* = 1/R1 + 1/R2,
    written out here; a key not given is the rigid flat's (other_poisson_ratio here)."""
    grain = cl.Grain(diameter=5e-3, density=765.0, youngs_modulus=21.6e6, poisson_ratio=0.2)
    table = {"law": "hertz", "from_material": True}
    table |= {"other_youngs_modulus": 2.1e11, "other_radius": 0.01}
    law = cl.config.law_from_table(table, grain)
    modulus = 1.0 / ((1.0 - 0.2**2) / 21.6e6 + 1.0 / 2.1e11)
    radius = 1.0 / (1.0 / 2.5e-3 + 1.0 / 0.01)
    # the same formulas in another order: a few ulps
    assert law.k_hertz == pytest.approx(4.0 / 3.0 * modulus * radius**0.5, rel=1e-14)
    with pytest.raises(ParameterError, match="did you mean 'other_radius'"):
        cl.config.law_from_table({**table, "other_radus": 0.01}, grain)


def test_demo_writes_figure_and_summary(tmp_path, capsys):
    assert contactlab_main(["demo", "--out", str(tmp_path), "--quick"]) == 0

    def refuse(name):  # json.loads accepts NaN and Infinity; strict JSON does not
        raise ValueError(f"summary.json holds {name}")

    summary = json.loads((tmp_path / "summary.json").read_text(), parse_constant=refuse)
    # the rigid wall's resonance is infinite: null, with the reason beside it
    assert summary["base_case_rigid_wall"]["sensor"]["resonance [Hz]"] is None
    assert "inf" in summary["null_reasons"]["base_case_rigid_wall.sensor.resonance [Hz]"]
    assert summary["base_case_rigid_wall"]["contact_time [s]"] > 0
    assert (tmp_path / "base_case.png").stat().st_size > 10_000
    assert summary["engine_check"]["passed"] is True
    chung_ooi = summary["chung_ooi"]  # the nine tests, LAMMPS beside on 4-6
    assert chung_ooi["passed"] == chung_ooi["graded"] and chung_ooi["not_run"] == {}
    assert chung_ooi["lammps"] == "run beside (tests 4-6)"  # the test extra has LAMMPS
    # the reconstruction recovers the peak within the 5 % where the raw signal misses
    errors = summary["reconstruction_relative_errors"]
    assert abs(errors["raw_peak [-]"]) > 0.5
    assert abs(errors["tikhonov_peak [-]"]) < 0.05
