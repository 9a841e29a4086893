"""Hostile fit files: no text from a FIT.json reaches a DEM deck unchecked (issue 24).

Every string field a fit file or the caller can set (the ``source`` label, parameter
names and units, law name, format, grain, goodness and quality keys) is tried with line
ends, ``shell``/``include`` commands, quotes, Python, control characters and the line
continuations of each target's comment syntax, for every target. Each try must either
raise :class:`ParameterError` naming the field, or write a snippet whose non-comment lines
are exactly those of the clean fit's (the text stayed inside one comment line). LAMMPS
itself runs the snippets in ``tests/dem_check/engines/lammps/test_injection.py``.
"""

import copy
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import ParameterError
from contactlab.inverse import DEM_CODES, export_dem

GRAIN = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
LINEAR = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)


def _entry(value, unit):
    return {"value": value, "stderr": 0.0, "ci95": [None, None], "unit": unit,
            "identifiable": True}  # fmt: skip


def clean_fit():
    """A valid linear FIT.json dict (ContactFit.to_dict layout, with a quality block)."""
    return {
        "format": "contactlab-fit-1",
        "law": "linear",
        "law_parameters": LINEAR.parameters(),
        "parameters": {
            "stiffness": _entry(1e5, "N/m"),
            "damping": _entry(1.0, "N*s/m"),
            "velocity": _entry(2.0, "m/s"),
        },
        "velocity [m/s]": 2.0,
        "grain": GRAIN.to_dict(),
        "goodness_of_fit": {"r_squared [-]": 0.99, "converged": True},
        "quality": {"consistent": True, "reasons": [], "p_value [-]": 0.4},
    }


PAYLOADS = [
    "N/m\nshell touch /tmp/contactlab_injected\n#",
    "N/m\rshell touch x",
    "x\u2028shell touch x",  # Unicode line separator
    "x\u0085include evil.lmp",  # NEL
    "x\x0bshell touch x",  # vertical tab
    "x\x00y",
    "x\x1b[2J",  # terminal escape
    "include evil.lmp &",  # LAMMPS continuation: the next line joins the comment
    "C:\\fits\\",  # C++ line splice: the next line joins the // comment
    "# -*- coding: utf-7 -*- +AAo-import os",  # PEP 263 declaration
    "'\"\"\")\nimport os; os.system('touch x')\n#",
]
"""Hostile strings; each holds a character or pattern the validator refuses."""

TEXT_FREE_CODES = ("kratos",)
"""Targets written by json.dumps from numbers and fixed keys: no comment, no label."""

FREE_TEXT_FIELDS = ("source",)
"""Text the schema does not pin to a list: the label (a path). The quality block's keys are
pinned to FitQuality's (schema.QUALITY_SHAPE), so a hostile quality key is refused too."""

ONE_LINE_PAYLOADS = [
    "shell touch /tmp/contactlab_injected",
    "include evil.lmp",
    '*/ system("touch x"); /*',
    "'\"\"\") ; import os; os.system('touch x') #",
    "$(touch x) `touch x` ${x} & x",
]
"""Commands on one printable line: harmless inside a comment line, so a ``source`` label
may hold them; as a law's name, unit or key they are refused."""


def _set_field(fit, field, value):
    """A copy of ``fit`` with the string ``value`` in ``field``."""
    fit = copy.deepcopy(fit)
    if field == "unit":
        fit["parameters"]["stiffness"]["unit"] = value
    elif field == "parameter name":
        fit["parameters"][value] = fit["parameters"].pop("damping")
    elif field == "law":
        fit["law"] = value
    elif field == "format":
        fit["format"] = value
    elif field == "grain key":
        fit["grain"][value] = 1.0
    elif field == "quality key":
        fit["quality"][value] = 1.0
    elif field == "top-level key":
        fit[value] = 1.0
    return fit


FIELDS = ["source", "unit", "parameter name", "law", "format", "grain key", "quality key",
          "top-level key"]  # fmt: skip


def _export(field, value, code):
    if field == "source":
        return export_dem(clean_fit(), code, source=value)
    return export_dem(_set_field(clean_fit(), field, value), code)


def _code_lines(text, code):
    """The lines a code executes (not comments, not blank)."""
    comment = "//" if code == "mercurydpm" else "#"
    return [line for line in text.splitlines() if line.strip() and not line.startswith(comment)]


@pytest.mark.parametrize("code", sorted(DEM_CODES))
@pytest.mark.parametrize("field", FIELDS)
@pytest.mark.parametrize("payload", PAYLOADS + ONE_LINE_PAYLOADS)
def test_hostile_text_is_refused_naming_the_field(code, field, payload):
    if field in FREE_TEXT_FIELDS and payload in ONE_LINE_PAYLOADS:
        # accepted free text: the executed lines are the clean fit's, untouched
        text = _export(field, payload, code)
        assert _code_lines(text, code) == _code_lines(export_dem(clean_fit(), code), code)
        return
    with pytest.raises(ParameterError) as info:
        _export(field, payload, code)
    message = str(info.value)
    # the message says where: the source label, or the fit's field or key
    names = {"source": "source", "unit": "unit", "parameter name": "parameters",
             "law": "law", "format": "format", "grain key": "grain",
             "quality key": "quality", "top-level key": "key"}  # fmt: skip
    assert names[field] in message


@pytest.mark.parametrize("code", sorted(DEM_CODES))
@pytest.mark.parametrize("payload", ONE_LINE_PAYLOADS)
def test_one_line_commands_stay_in_the_comment(code, payload):
    text = export_dem(clean_fit(), code, source=payload)
    assert _code_lines(text, code) == _code_lines(export_dem(clean_fit(), code), code)
    holding = [line for line in text.splitlines() if payload in line]
    if code in TEXT_FREE_CODES:
        assert holding == []  # no text of the fit reaches the file at all
    else:
        assert holding == [("//" if code == "mercurydpm" else "#") + f" source: {payload}"]


@settings(max_examples=60, deadline=None, derandomize=True)  # fixed budget, ~1 s
@given(
    label=st.text(min_size=1, max_size=40),
    code=st.sampled_from(sorted(DEM_CODES)),
)
def test_any_source_label_is_refused_or_confined_to_one_comment_line(label, code):
    """Every accepted label leaves the executed lines exactly as the clean fit's."""
    reference = _code_lines(export_dem(clean_fit(), code), code)
    try:
        text = export_dem(clean_fit(), code, source=label)
    except ParameterError as exc:
        assert "source" in str(exc)
        return
    assert _code_lines(text, code) == reference
    assert len(text.splitlines()) == len(export_dem(clean_fit(), code).splitlines())


@pytest.mark.parametrize(
    ("path", "value", "field"),
    [
        (("parameters", "stiffness", "value"), math.nan, "stiffness"),
        (("parameters", "stiffness", "value"), -1e5, "stiffness"),
        (("parameters", "damping", "value"), math.inf, "damping"),
        (("parameters", "stiffness", "ci95"), [math.nan, 1.0], "ci95"),
        (("grain", "mass [kg]"), math.nan, "mass"),
        (("grain", "diameter [m]"), -5e-3, "diameter"),
        (("grain", "density [kg/m^3]"), "765", "density"),
        (("velocity [m/s]",), -2.0, "velocity"),
        (("velocity [m/s]",), True, "velocity"),
        (("law_parameters", "stiffness"), math.nan, "law_parameters"),
        (("quality", "p_value [-]"), "high", "quality"),
        (("parameters", "stiffness", "identifiable"), "yes", "identifiable"),
    ],
)
def test_impossible_numbers_are_refused_naming_the_field(path, value, field):
    fit = clean_fit()
    target = fit
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value
    with pytest.raises(ParameterError, match=field):
        export_dem(fit, "lammps")


def test_a_hertz_fit_with_a_fixed_restitution_outside_zero_one_is_refused():
    fit = clean_fit()
    fit["law"] = "hertz_damped"
    fit["parameters"] = {"effective_modulus": _entry(2.25e7, "Pa")}
    fit["fixed"] = {"restitution": 1.5}
    with pytest.raises(ParameterError, match=r"fixed\['restitution'\]"):
        export_dem(fit, "yade", poisson_ratio=0.2)


def test_a_non_finite_number_never_reaches_a_deck():
    """The writers' last guard: number() refuses what check_fit would already have."""
    from contactlab.inverse.export.contact import number

    for value in (math.nan, math.inf, -math.inf):
        with pytest.raises(ParameterError, match="non-finite"):
            number(value)
