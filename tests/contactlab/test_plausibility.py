"""Plausibility ranges: real grains and sensors pass, unit slips are named, nothing clipped."""

import math
import warnings

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.advisor import list_species, load_species
from contactlab.batch import linear_impacts
from contactlab.errors import PlausibilityWarning, UnknownParameterError
from contactlab.plausibility import RANGES, check_plausible, internal, likely_slips
from contactlab.solver.wall import wall_restitution
from contactlab.testing.strategies import grains, impact_velocities, sensors

LAW = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
PAPER_GRAIN = cl.Grain(diameter=5e-3, density=765.0)


def _no_warning(call):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return call()


# the issue's slips, each with the reading the message must offer
@pytest.mark.parametrize(
    ("call", "said"),
    [
        (lambda: cl.Grain(diameter=5.0, density=765.0), "did you mean 0.005 m (5 given in mm)"),
        (lambda: cl.Grain(diameter=5e-3, density=0.765), "765 kg/m^3 (0.765 given in g/cm^3)"),
        (
            lambda: cl.Grain(diameter=5e-3, density=765.0, youngs_modulus=21.6, poisson_ratio=0.2),
            "2.16e+07 Pa (21.6 given in MPa)",
        ),
        (
            lambda: cl.Sensor.from_resonance(40, mass=1.233e-3, damping_ratio=0.02),
            "did you mean 40000 Hz (40 given in kHz)",
        ),
        (lambda: cl.Sensor.from_disc(10, 2e-3, 40e3), "0.01 m (10 given in mm)"),
        (lambda: cl.Sensor.from_disc(10e-3, 2, 40e3), "0.002 m (2 given in mm)"),
        (
            lambda: cl.Sensor.from_resonance(40e3, mass=1.233e-3, damping_ratio=2.0),
            "0.02 - (2 given in %)",
        ),
        (
            lambda: cl.simulate_impact(PAPER_GRAIN, cl.Sensor.rigid(), LAW, 200.0),
            "did you mean 2 m/s (200 given in cm/s)",
        ),
        (lambda: cl.Grain.from_mass(50.0), "0.05 kg (50 given in g)"),
    ],
)
def test_unit_slips_warn_with_the_likely_reading(call, said):
    with pytest.warns(PlausibilityWarning, match=None) as caught:
        call()
    messages = [str(w.message) for w in caught]
    assert any(said in m for m in messages), messages


def test_a_slipped_value_is_kept_as_given():
    with pytest.warns(PlausibilityWarning):
        grain = cl.Grain(diameter=5.0, density=765.0)
    assert grain.diameter == 5.0  # warned, not clipped or converted
    assert grain.mass == pytest.approx(765.0 * math.pi * 5.0**3 / 6.0, rel=1e-15)


def test_the_issue_grain_of_fifty_tonnes_is_not_an_impact():
    with pytest.warns(PlausibilityWarning):
        grain = cl.Grain(diameter=5.0, density=765.0)
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    with pytest.raises(cl.ParameterError, match=r"not an impact.*mass 5\.007e\+04 kg"):
        cl.simulate_impact(grain, sensor, LAW, 2.0, duration=500e-6)


@settings(max_examples=40, deadline=None)
@given(grain=grains(), sensor=sensors(rigid=True), velocity=impact_velocities())
def test_the_testing_strategies_real_ranges_never_warn(grain, sensor, velocity):
    """Grains, sensors and speeds across the strategies' documented real ranges."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a fixed law on any grain may be under-resolved
        warnings.simplefilter("error", PlausibilityWarning)
        cl.simulate_impact(grain, sensor, LAW, velocity)


@pytest.mark.parametrize("name", list_species())
def test_every_species_preset_lies_inside_the_ranges(name):
    """The species presets (measured kernels, with sources) are an independent reference."""
    species = load_species(name)
    for corner in species.grains("corners"):
        _no_warning(lambda corner=corner: cl.Grain(**corner, poisson_ratio=0.3))
        for key, value in zip(
            ("grain_diameter", "grain_density", "youngs_modulus"), corner.values(), strict=True
        ):
            spec = RANGES[key]
            assert spec.low <= value <= spec.high, (name, key, value)


@settings(max_examples=60, deadline=None)
@given(key=st.sampled_from(sorted(RANGES)), position=st.floats(0.0, 1.0))
def test_values_inside_a_range_pass_and_are_returned_unchanged(key, position):
    spec = RANGES[key]
    value = spec.low + position * (spec.high - spec.low)
    assert _no_warning(lambda: check_plausible(key, value)) == value


@settings(max_examples=60, deadline=None)
@given(
    key=st.sampled_from(sorted(RANGES)),
    factor=st.floats(1.001, 1e6),
    above=st.booleans(),
)
def test_values_outside_a_range_warn_and_offer_only_readings_inside_it(key, factor, above):
    spec = RANGES[key]
    if not above and spec.low == 0.0:
        return  # nothing lies below a range starting at 0 but negative values (errors)
    value = spec.high * factor if above else spec.low / factor
    with pytest.warns(PlausibilityWarning, match=key) as caught:
        assert check_plausible(key, value) == value
    for reading, _ in likely_slips(key, value):
        assert spec.low <= reading <= spec.high
        assert f"{float(f'{reading:.4g}'):g} {spec.unit}" in str(caught[0].message)


def test_internal_values_do_not_warn():
    with internal():
        _no_warning(lambda: cl.Grain(diameter=5.0, density=765.0))
    # and law conveniences at any mass and speed (wall impacts) never warn
    _no_warning(lambda: wall_restitution(LAW, 1e3, 200.0))


def test_a_batch_frame_warns_once_per_quantity_naming_its_rows():
    m1, f1 = 1.233e-3, np.array([40e3, 40.0, 50e3, 30.0])  # rows 1 and 3: Hz for kHz
    k1 = m1 * (2 * np.pi * f1) ** 2
    frame = pd.DataFrame(
        {
            "m1 [kg]": m1,
            "k1 [N/m]": k1,
            "c1 [N*s/m]": 2 * 0.02 * np.sqrt(k1 * m1),
            "m2 [kg]": 5e-5,
            "k2 [N/m]": 1e5,
            "c2 [N*s/m]": 1.0,
            "v0 [m/s]": [2.0, 2.0, 200.0, 2.0],  # row 2: cm/s for m/s
        },
        index=["a", "b", "c", "d"],
    )
    with pytest.warns(PlausibilityWarning) as caught:
        linear_impacts(frame)
    messages = sorted(str(w.message) for w in caught)
    assert len(messages) == 2, messages
    assert messages[0].startswith("1 row(s) (c): v0 [m/s] = 200")
    assert messages[1].startswith("2 row(s) (b, d): sensor resonance [Hz] = 40 ")


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: cl.Grain(diam=5e-3, density=765.0), r"'diam' \(did you mean 'diameter'\?\)"),
        (
            lambda: cl.simulate_impact(PAPER_GRAIN, cl.Sensor.rigid(), LAW, velocty=2.0),
            r"'velocty' \(did you mean 'velocity'\?\); missing required parameter\(s\) 'velocity'",
        ),
        (
            lambda: cl.Sensor.from_resonance(40e3, mas=1e-3),
            r"(unexpected keyword|'mas')",
        ),
    ],
)
def test_misspelt_keywords_are_named_with_a_suggestion(call, message):
    with pytest.raises(TypeError, match=message) as info:
        call()
    if info.type is UnknownParameterError:
        assert isinstance(info.value, ValueError)


def test_the_documented_table_is_the_module_table():
    from pathlib import Path

    from contactlab.plausibility import _number

    doc = (Path(__file__).resolve().parents[2] / "docs" / "plausibility.md").read_text()
    rows = {line.split("|")[1].strip(" `"): line for line in doc.splitlines() if "| `" in line}
    for key, spec in RANGES.items():
        cells = [c.strip() for c in rows[key].split("|")[1:-1]]
        assert cells[2:5] == [_number(spec.low), _number(spec.high), spec.unit], key
        assert cells[6] == spec.source, key
