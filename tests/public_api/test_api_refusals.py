"""Every public callable refuses what no user value can be, naming the parameter (issue 24).

For each callable of the public API (``conftest.covered``), each parameter in turn is
given every value of its kind that must be refused (``conftest.MUST_REFUSE``: NaN,
infinities, text for a number, a fraction for a count, an empty, NaN or 2-D array, a
number for an object, ``None`` where ``None`` is no default...) while the others keep
their valid values. The call must raise :class:`ParameterError` (or
:class:`TraceFormatError`) whose message names the parameter: not succeed (a silently
wrong result), not raise anything else, not hang. Exhaustive and deterministic: a few
thousand calls, each refused before any work.
"""

from contactlab.errors import ParameterError, TraceFormatError


def names(parameter):
    """The words a refusal may use for a parameter: its name, or the singular of a plural
    (``velocities`` are refused one at a time: "velocity must be ...")."""
    if parameter.endswith("ies"):
        return parameter, parameter[:-3] + "y"
    return (parameter, parameter[:-1]) if parameter.endswith("s") else (parameter,)


def test_bad_values_are_refused_naming_the_parameter(api, api_name):
    function, valid, kinds = api.baseline(api_name)
    problems = []
    for parameter, (kind, default) in kinds.items():
        for label, value in api.refusals(kind, default, parameter):
            try:
                api.call(function, {**valid, parameter: value})
            except (ParameterError, TraceFormatError) as exc:
                if not any(w.lower() in str(exc).lower() for w in names(parameter)):
                    problems.append(f"{parameter}={label}: refused without naming it: {exc}")
            except Exception as exc:
                problems.append(f"{parameter}={label}: {type(exc).__name__}: {exc}")
            else:
                problems.append(f"{parameter}={label}: accepted")
    assert not problems, f"{api_name}:\n" + "\n".join(problems)
