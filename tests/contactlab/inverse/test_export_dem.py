"""DEM-code snippets from a fit: parameter names, numbers, time steps and syntax."""

import ast
import json
import math
import re

import pytest

import contactlab as cl
from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.inverse import DEM_CODES, export_dem, read_fit
from contactlab.solver.wall import wall_contact_time

GRAIN = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
VELOCITY = 2.0  # [m/s]
SNIPPET_CODES = sorted(set(DEM_CODES) - {"kratos"})
"""Codes written as commented snippets; Kratos' MaterialsDEM.json holds numbers and fixed
keys only, no header (tests/contactlab/inverse/test_export_kratos.py)."""


def _entry(value, unit):
    return {"value": value, "stderr": 0.01 * value, "ci95": [0.98 * value, 1.02 * value],
            "unit": unit, "identifiable": True}  # fmt: skip


def _fit_dict(law_name, law, fitted):
    """The FIT.json layout of ContactFit.to_dict, for a known law."""
    return {
        "format": "contactlab-fit-1",
        "law": law_name,
        "law_parameters": law.parameters(),
        "parameters": {
            **fitted,
            "velocity": _entry(VELOCITY, "m/s"),
            "onset": _entry(1e-7, "s"),
        },
        "velocity [m/s]": VELOCITY,
        "grain": GRAIN.to_dict(),
    }


LINEAR = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
LINEAR_FIT = _fit_dict(
    "linear", LINEAR, {"stiffness": _entry(1e5, "N/m"), "damping": _entry(1.0, "N*s/m")}
)
E_STAR = 2.25e7  # [Pa]: E = 21.6 MPa, nu = 0.2 against a rigid flat
HERTZ = cl.laws.HertzDamped(
    analytic.hertz_stiffness(E_STAR, GRAIN.radius),
    analytic.tsuji_damping_coefficient(
        analytic.hertz_stiffness(E_STAR, GRAIN.radius), GRAIN.mass, 0.5
    ),
)
HERTZ_FIT = _fit_dict(
    "hertz_damped",
    HERTZ,
    {"effective_modulus": _entry(E_STAR, "Pa"), "restitution": _entry(0.5, "-")},
)


def _number(text, pattern):
    """The float after ``pattern`` in ``text``."""
    match = re.search(pattern + r"\s*([-+0-9.eE]+)", text)
    assert match, f"{pattern!r} not found in:\n{text}"
    return float(match.group(1))


def _linear_contact_time():
    # the one-sided law ends at zero force: the "force" convention
    return analytic.linear_contact_time(1e5, 1.0, GRAIN.mass, convention="force")


def _grain_youngs_modulus():
    # 1/E* = (1 - nu^2)/E + (1 - nu_p^2)/E_p with a steel plate
    return (1 - 0.2**2) / (1 / E_STAR - (1 - 0.3**2) / 210e9)


def _rayleigh_time():
    e = _grain_youngs_modulus()
    return analytic.rayleigh_time(GRAIN.radius, GRAIN.density, e / 2.4, 0.2)


def _liggghts_commands(text):
    """Check LIGGGHTS syntax: known commands, and value counts of property/global fixes."""
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    for line in lines:
        words = line.split()
        assert words[0] in ("pair_style", "pair_coeff", "fix", "timestep"), line
        if words[0] == "fix" and words[3] == "property/global":
            style, values = words[5], words[6:]
            expected = {"peratomtype": 2, "peratomtypepair": 5}[style]
            assert len(values) == expected, line
            if style == "peratomtypepair":
                assert values[0] == "2"
            [float(v) for v in values]
    return lines


# 4 significant figures: every number is written with 7; the rest is rounding
REL = 1e-4


def test_liggghts_linear():
    text = export_dem(LINEAR_FIT, "liggghts", source="FIT.json")
    _liggghts_commands(text)
    assert "pair_style gran model hooke/stiffness" in text
    assert "absolute_damping on" in text and "limitForce on" in text
    assert _number(text, "kn peratomtypepair 2") == pytest.approx(1e5, rel=REL)
    assert _number(text, "gamman_abs peratomtypepair 2") == pytest.approx(1.0, rel=REL)
    assert _number(text, "\ntimestep") == pytest.approx(_linear_contact_time() / 50, rel=REL)
    assert "# source: FIT.json" in text
    assert "NOT FITTED" in text
    assert "check/timestep/gran" not in text  # it needs youngsModulus, absent here


def test_liggghts_hertz():
    text = export_dem(HERTZ_FIT, "liggghts")
    _liggghts_commands(text)
    assert "pair_style gran model hertz tangential history limitForce on" in text
    e = _number(text, "youngsModulus peratomtype")
    assert e == pytest.approx(_grain_youngs_modulus(), rel=REL)
    assert _number(text, "poissonsRatio peratomtype") == 0.2
    assert _number(text, "coefficientRestitution peratomtypepair 2") == 0.5
    assert _number(text, "\ntimestep") == pytest.approx(0.1 * _rayleigh_time(), rel=REL)
    assert "check/timestep/gran 1000 0.1 0.1" in text


def test_mercurydpm_linear_and_hertz():
    linear = export_dem(LINEAR_FIT, "mercurydpm")
    assert "LinearViscoelasticSpecies()" in linear
    assert _number(linear, r"setStiffness\(") == pytest.approx(1e5, rel=REL)
    assert _number(linear, r"setDissipation\(") == pytest.approx(1.0, rel=REL)
    assert _number(linear, r"setTimeStep\(") == pytest.approx(_linear_contact_time() / 50, rel=REL)
    hertz = export_dem(HERTZ_FIT, "mercurydpm")
    assert _number(hertz, r"setElasticModulusAndRestitutionCoefficient\(") == pytest.approx(
        E_STAR, rel=REL
    )
    assert re.search(r"setElasticModulusAndRestitutionCoefficient\([^,]+, 0\.5\)", hertz)
    t_hertz = wall_contact_time(HERTZ, GRAIN.mass, VELOCITY)
    assert _number(hertz, r"setTimeStep\(") == pytest.approx(t_hertz / 50, rel=REL)
    for text in (linear, hertz):
        code = [ln for ln in text.splitlines() if ln and not ln.startswith("//")]
        assert all(ln.split("//")[0].rstrip().endswith(";") for ln in code)
        assert text.count("(") == text.count(")")


def test_yade_snippets_are_python():
    linear = export_dem(LINEAR_FIT, "yade")
    tree = ast.parse(linear)
    assert any(isinstance(node, ast.Assign) for node in tree.body)
    # ViscElMat: the contact takes 1/(1/kn1 + 1/kn2), so each material carries 2 k, 2 c
    assert _number(linear, "ViscElMat\\(kn=") == pytest.approx(2e5, rel=REL)
    assert _number(linear, "cn=") == pytest.approx(2.0, rel=REL)
    assert "Law2_ScGeom_ViscElPhys_Basic()" in linear
    assert _number(linear, "O.dt =") == pytest.approx(0.05 * _linear_contact_time(), rel=REL)
    hertz = export_dem(HERTZ_FIT, "yade")
    ast.parse(hertz)
    assert _number(hertz, "young=") == pytest.approx(_grain_youngs_modulus(), rel=REL)
    assert "MatchMaker(algo='val', val=0.5)" in hertz
    assert "Law2_ScGeom_MindlinPhys_Mindlin()" in hertz
    pwave = GRAIN.radius * math.sqrt(GRAIN.density / _grain_youngs_modulus())
    assert _number(hertz, "O.dt =") == pytest.approx(0.5 * pwave, rel=REL)


def test_edem_values():
    hertz = export_dem(HERTZ_FIT, "edem", friction=0.3)
    assert "Hertz-Mindlin (no slip)" in hertz
    g = _grain_youngs_modulus() / 2.4
    assert _number(hertz, "Shear Modulus \\[Pa\\] =") == pytest.approx(g, rel=REL)
    assert _number(hertz, "Poisson's Ratio =") == 0.2
    assert _number(hertz, "Coefficient of Restitution =") == 0.5
    assert _number(hertz, "Coefficient of Static Friction =") == 0.3
    assert "NOT FITTED" not in hertz.split("Coefficient of Static Friction:")[1].split("\n")[0]
    assert _number(hertz, "Fixed Time Step \\[s\\] =") == pytest.approx(
        0.2 * _rayleigh_time(), rel=REL
    )
    linear = export_dem(LINEAR_FIT, "edem")
    e = analytic.linear_restitution(1e5, 1.0, GRAIN.mass, convention="overlap")
    assert _number(linear, "Coefficient of Restitution =") == pytest.approx(e, rel=REL)
    assert _number(linear, "Normal stiffness \\[N/m\\] =") == pytest.approx(1e5, rel=REL)
    for text in (linear, hertz):
        body = [ln for ln in text.splitlines() if ln and not ln.startswith(("#", "["))]
        assert all(" = " in ln for ln in body)


@pytest.mark.parametrize("code", SNIPPET_CODES)
def test_every_snippet_states_source_and_time_step_guidance(code):
    text = export_dem(HERTZ_FIT, code, source="runs/FIT.json")
    assert "runs/FIT.json" in text
    assert "time step" in text and "steps" in text
    assert text.endswith("\n")


def test_a_parameter_held_fixed_in_the_fit_is_exported():
    """fit_contact(..., fixed={"restitution": 0.5}) writes it under "fixed", not "parameters"."""
    fitted = {k: v for k, v in HERTZ_FIT["parameters"].items() if k != "restitution"}
    fixed = {**HERTZ_FIT, "parameters": fitted, "fixed": {"restitution": 0.5}}
    text = export_dem(fixed, "liggghts")
    assert _number(text, "coefficientRestitution peratomtypepair 2") == 0.5
    assert "restitution = 0.5 (fixed)" in text
    # everything but the header's note is the same as with a fitted restitution
    body = [ln for ln in text.splitlines() if "fitted law:" not in ln]
    assert body == [
        ln for ln in export_dem(HERTZ_FIT, "liggghts").splitlines() if "fitted law:" not in ln
    ]


def test_read_fit_round_trip(tmp_path):
    path = tmp_path / "FIT.json"
    path.write_text(json.dumps(HERTZ_FIT))
    assert export_dem(read_fit(path), "yade") == export_dem(HERTZ_FIT, "yade")


@pytest.mark.parametrize(
    ("fit", "kwargs", "message"),
    [
        (LINEAR_FIT, {"code": "pfc"}, "code must be one of"),
        ({**LINEAR_FIT, "law": "walton_braun"}, {}, "not supported"),
        ({"law": "linear"}, {}, "missing 'grain'"),
        (
            {**HERTZ_FIT, "grain": {**HERTZ_FIT["grain"], "poisson_ratio [-]": None}},
            {},
            "poisson_ratio is needed",
        ),
        (HERTZ_FIT, {"plate_youngs_modulus": 1e7}, "stiffer than the plate"),
        (HERTZ_FIT, {"friction": -0.1}, "friction must be"),
        ("FIT.json", {}, "fit must be a ContactFit or the dict"),
        (
            {**HERTZ_FIT, "parameters": {"effective_modulus": _entry(E_STAR, "Pa")}},
            {},
            "'restitution' is neither fitted nor fixed",
        ),
    ],
)
def test_bad_input_names_the_parameter(fit, kwargs, message):
    kwargs = {"code": "liggghts", **kwargs}
    with pytest.raises(ParameterError, match=message):
        export_dem(fit, **kwargs)


def test_read_fit_errors(tmp_path):
    with pytest.raises(ParameterError, match="not found"):
        read_fit(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ParameterError, match="not valid JSON"):
        read_fit(bad)


# --- LAMMPS (realised by LAMMPS itself in tests/dem_check/engines/lammps/test_realise.py) ---
def _commands(text):
    return [ln for ln in text.splitlines() if ln and not ln.startswith("#")]


def test_hertz_snippet_is_the_fitted_law_on_the_plane():
    commands = _commands(export_dem(HERTZ_FIT, "lammps"))
    assert commands[0] == "pair_style granular"
    wall = next(ln for ln in commands if ln.startswith("fix sensor_plate all wall/gran"))
    words = wall.split()
    assert words[4:7] == ["granular", "hertz", f"{4 / 3 * E_STAR:.7g}"]  # k = 4/3 E*
    assert words[7] == "0.5"  # the fit's restitution, LAMMPS' coeff_restitution input
    assert "damping coeff_restitution" in wall and "limit_damping" in wall
    assert wall.endswith("zplane 0.0 NULL")
    # grain-grain: hertz/material with the grain's E behind E* (steel plate)
    pair = next(ln for ln in commands if ln.startswith("pair_coeff * *"))
    youngs = float(pair.split()[4])
    expected = (1 - 0.2**2) / (1 / E_STAR - (1 - 0.3**2) / 210e9)
    assert youngs == pytest.approx(expected, rel=1e-6)  # 7 significant digits written


def test_linear_snippet_takes_k_and_c_as_they_are():
    commands = _commands(export_dem(LINEAR_FIT, "lammps"))
    wall = next(ln for ln in commands if ln.startswith("fix sensor_plate"))
    assert "hooke 100000 1 damping velocity" in wall and "limit_damping" in wall
    step = float(next(ln for ln in commands if ln.startswith("timestep")).split()[1])
    contact = analytic.linear_contact_time(
        LINEAR.stiffness, LINEAR.damping, GRAIN.mass, convention="force"
    )
    assert step == pytest.approx(contact / 200, rel=1e-6)  # 7 significant digits


@pytest.mark.parametrize("fit", [HERTZ_FIT, LINEAR_FIT], ids=["hertz_damped", "linear"])
def test_snippet_creates_nothing_and_does_not_run(fit):
    for line in _commands(export_dem(fit, "lammps")):
        command = line.split()[0]
        assert command in ("pair_style", "pair_coeff", "fix", "timestep"), line
        assert not re.search(r"nve|velocity all|create_atoms|^run", line), line


def test_every_header_states_the_realised_rebound():
    fitted = analytic.tsuji_restitution(analytic.tsuji_damping_factor(0.5), "force")
    for code in SNIPPET_CODES:
        text = export_dem(HERTZ_FIT, code)
        line = next(ln for ln in text.splitlines() if "realised rebound" in ln)
        assert f"{fitted:.4f}" in line, code  # the fitted law's 0.5503 is always named
        if code == "mercurydpm":
            assert "realised rebound on a rigid plate: 0.5000, NOT the fitted law's" in line
        elif code == "edem":
            assert "not documented" in line
        else:
            assert f"realised rebound on a rigid plate: {fitted:.4f}, the fitted law's" in line
    assert math.isclose(fitted, 0.550283, rel_tol=1e-5)  # the table of tsuji_restitution


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("baseline_status", 3, "baseline_status must be text"),
        ("baseline_notes", "drift", "baseline_notes must be a list of texts"),
        ("baseline_notes", [1.0], "baseline_notes must be a list of texts"),
        ("baseline_notes", ["drift\nshell touch /tmp/x"], "baseline_notes"),
    ],
)
def test_a_fit_s_baseline_status_must_be_text(key, value, message):
    """The local baseline's status and notes of a FIT.json are read, never exported:
    anything but text is refused, a text status is exported as before."""
    with pytest.raises(ParameterError, match=message):
        export_dem({**LINEAR_FIT, key: value}, "yade")
    good = {**LINEAR_FIT, "baseline_status": "drifting baseline", "baseline_notes": ["x"]}
    assert export_dem(good, "yade") == export_dem(LINEAR_FIT, "yade")
