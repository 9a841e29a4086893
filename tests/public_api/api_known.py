"""Known defects the API property tests found and this change did not fix.

Each entry is a strict xfail (``conftest._pinned``) whose reason is what was measured:
the parameter, the values and what came out. Fixing one turns its test into a failure
until the entry is removed.
"""

KNOWN_REFUSAL_DEFECTS = {
}  # fmt: skip
"""Callables that still accept, or fail on, a value they must refuse: what was measured."""

KNOWN_HOSTILE_DEFECTS = {
}  # fmt: skip
"""Callables whose sweep found a value answered with something else than ParameterError:
``(parameter, value, what came out)``. The test calls exactly that value (a strict
xfail) instead of the sweep, so the pin does not depend on the draws."""
