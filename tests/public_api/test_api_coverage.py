"""Every public callable is in the property tests, or exempt with a reason (issue 24).

The API is enumerated from the packages' ``__all__`` (``conftest.public_callables``), so
a new public function, class or method fails here until ``conftest.py`` can call it
with valid arguments (``VALUES`` by parameter name, ``OVERRIDES`` by callable) or lists
it in ``EXEMPT``/``ABSTRACT`` with a reason.
"""

import importlib


def test_the_public_api_is_large_and_every_callable_is_covered_or_exempt(api):
    assert len(api.public_callables()) > 300  # 382 callables when this was written
    missing = []
    for name in api.covered():
        try:
            api.baseline(name)
        except LookupError as exc:
            missing.append(str(exc))
    assert not missing, "give valid values in tests/public_api/conftest.py:\n" + "\n".join(missing)


def test_the_tables_name_only_public_callables(api):
    names = api.public_callables()
    classes = {name for name, obj in names.items() if isinstance(obj, type)}
    for table in (api.EXEMPT, api.OVERRIDES, api.COSTLY):
        stale = set(table) - set(names)
        assert not stale, f"not public (renamed or removed?): {sorted(stale)}"
    stale = (set(api.INSTANCES) | set(api.ABSTRACT)) - classes
    assert not stale, f"not public classes: {sorted(stale)}"
    for module in api.NOT_PUBLIC:
        importlib.import_module(module)  # a stale module name fails here


def test_the_valid_call_of_each_cheap_callable_succeeds(api, valid_name):
    """The refusals the other tests see are then caused by the hostile value alone.

    Costly callables (simulations, fits, studies) are not run here; their refusals are
    checked to name the hostile parameter instead (test_api_refusals.py).
    """
    function, arguments, _ = api.baseline(valid_name)
    api.call(function, arguments)
