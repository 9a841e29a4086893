"""Regression testing of contact laws: closed forms, passivity, golden traces, strategies.

Assertions (each raises AssertionError saying what was expected, what came out, the
tolerance and the closed form used with its reference):

- :func:`assert_restitution`, :func:`assert_contact_time`: one quantity of an impact on
  an immovable wall against a value you give;
- :func:`assert_matches_closed_form`: every closed form known for the law's class
  (registry :data:`CLOSED_FORMS`, extended with :func:`register_closed_form`);
- :func:`assert_passive`: no energy created over a loading-unloading cycle;
- :func:`assert_trace_matches`: an impact against a reference (a golden trace, another
  simulation or a measured trace): headline quantities and waveforms, compared by
  :func:`contactlab.compare.compare` at regression tolerances (:func:`compare_impacts`
  gives the table without raising).

Golden traces (:class:`GoldenStore`, :class:`GoldenTrace`) store an impact with its
set-up and provenance and compare later runs with it. The pytest plugin
(:mod:`contactlab.testing.plugin`, loaded automatically) adds the paper's grains and
sensors as fixtures, a ``golden`` fixture and the ``--contactlab-update-golden`` flag.
Hypothesis strategies live in :mod:`contactlab.testing.strategies` (needs hypothesis).
See ``docs/testing.md`` for a worked example.
"""

from contactlab.testing.assertions import (
    assert_contact_time,
    assert_matches_closed_form,
    assert_passive,
    assert_restitution,
    assert_trace_matches,
)
from contactlab.testing.closed_forms import (
    CLOSED_FORMS,
    ClosedForm,
    NoClosedFormError,
    closed_forms_for,
    register_closed_form,
)
from contactlab.testing.golden import GoldenStore, compare_impacts
from contactlab.testing.golden_trace import GoldenMissingError, GoldenTrace

__all__ = [
    "CLOSED_FORMS",
    "ClosedForm",
    "GoldenMissingError",
    "GoldenStore",
    "GoldenTrace",
    "NoClosedFormError",
    "assert_contact_time",
    "assert_matches_closed_form",
    "assert_passive",
    "assert_restitution",
    "assert_trace_matches",
    "closed_forms_for",
    "compare_impacts",
    "register_closed_form",
]
