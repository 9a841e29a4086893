"""Bad input to the public API gives ParameterError, never another exception (issue 24).

Every public constructor and entry point below is called with values drawn from the whole
space a user can type (finite, zero, negative, huge, tiny, NaN, infinite, text, None,
booleans) in every argument, at a fixed budget. A call may succeed or raise
:class:`ParameterError`; ``OverflowError``, ``ZeroDivisionError``, ``LinAlgError``,
``TypeError`` or anything else is a failure. Arguments that would start a long
simulation are drawn only in shapes that are refused before any work (``simulate_impact``
with a bad argument among valid ones).
"""

import inspect
import math
import warnings

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab.errors import ContactlabWarning, ParameterError
from contactlab.laws import LAWS

ANY_VALUE = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-320, 1e308, -1e308, 5e-324, math.nan, math.inf]),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.sampled_from(["1e5", "", "nan", None, True, False, 1j, [1.0], {"a": 1}]),
)
"""Whatever a user may pass where a number is expected."""

SETTINGS = settings(
    max_examples=150, deadline=None, derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)  # fmt: skip  # fixed budget: about a second per test


def _parameters(callable_):
    return [
        p.name
        for p in inspect.signature(callable_).parameters.values()
        if p.name != "self" and p.kind is p.POSITIONAL_OR_KEYWORD
    ]


def _call(function, **arguments):
    """Call; a ParameterError is an answer, and so is a warning (WindowWarning, ...)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactlabWarning)
        try:
            function(**arguments)
        except ParameterError:
            pass


CONSTRUCTORS = {
    **{f"laws.{name}": cls for name, cls in sorted(LAWS.items())},
    "Grain": cl.Grain,
    "Grain.from_mass": cl.Grain.from_mass,
    "Sensor": cl.Sensor,
    "Sensor.from_resonance": cl.Sensor.from_resonance,
    "Sensor.from_disc": cl.Sensor.from_disc,
}


@pytest.mark.parametrize("name", sorted(CONSTRUCTORS))
@SETTINGS
@given(data=st.data())
def test_constructors_answer_any_value_with_parameter_error(name, data):
    function = CONSTRUCTORS[name]
    arguments = {p: data.draw(ANY_VALUE, label=p) for p in _parameters(function)}
    _call(function, **arguments)


GRAIN = cl.Grain(diameter=5e-3, density=765.0)
SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
LAW = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)
VALID = {"velocity": 2.0, "duration": 5e-4, "sample_rate": 1e6}


@SETTINGS
@given(name=st.sampled_from(sorted(VALID)), value=ANY_VALUE)
@example(name="velocity", value=3.375558653572067e-270)  # impact energy underflowed to 0 J
def test_simulate_impact_answers_any_value_with_parameter_error(name, value):
    arguments = {**VALID, name: value}
    if name != "velocity" and isinstance(value, int | float) and not isinstance(value, bool):
        # a valid window or rate larger than needed is a long run, not bad input
        if value > VALID[name] * 10:
            return
    _call(cl.simulate_impact, grain=GRAIN, sensor=SENSOR, law=LAW, **arguments)


TRACE = __import__("pathlib").Path(__file__).parent.parent / "data" / "traces" / "generic.csv"


@SETTINGS
@given(
    name=st.sampled_from(["format", "channel", "sensitivity"]),
    value=st.one_of(ANY_VALUE, st.text(max_size=12)),
)
def test_read_trace_answers_any_argument_with_parameter_or_format_error(name, value):
    from contactlab.errors import TraceFormatError
    from contactlab.traces import read_trace

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactlabWarning)  # a warning is an answer too
        try:
            read_trace(TRACE, **{name: value})
        except (ParameterError, TraceFormatError):
            pass


OBLIQUE = {"velocity": 2.0, "angle": 0.5, "spin": 0.0, "duration": 5e-4, "rtol": 1e-9}


@SETTINGS
@given(name=st.sampled_from(sorted(OBLIQUE)), value=ANY_VALUE)
def test_simulate_oblique_answers_any_value_with_parameter_error(name, value):
    number = isinstance(value, int | float) and not isinstance(value, bool)
    if name == "duration" and number and value > 10 * OBLIQUE["duration"]:
        return  # a valid long window is a long run, not bad input
    if name == "spin" and number and math.isfinite(value) and abs(value) < 1e6:
        return  # a valid spin: a simulation, not the subject here
    normal = cl.laws.HertzDamped(1.5e6, 4.0)
    tangential = cl.laws.Mindlin.from_material(
        cl.analytic.Material(21.6e6, 0.2, GRAIN.radius), friction=0.5
    )
    arguments = {**OBLIQUE, name: value}
    _call(cl.simulate_oblique, grain=GRAIN, sensor=SENSOR, normal_law=normal,
          tangential_law=tangential, **arguments)  # fmt: skip


def test_a_linear_contact_too_stiff_for_a_float_is_refused_by_name():
    law = cl.laws.LinearViscoelastic(stiffness=1e300, damping=1.0)  # rates overflow
    with pytest.raises(ParameterError, match=r"overflow a float.*stiffness or damping"):
        cl.simulate_impact(GRAIN, SENSOR, law, velocity=2.0)
