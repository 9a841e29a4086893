"""The layout's rules, checked on the source: layers, no import cycle, small modules.

``docs/architecture.md`` draws the layers; this test keeps the drawing true. Imports are
read from the source (``ast``), function-level ones included, so a lazy import that
climbs a layer or closes a cycle is caught as well.
"""

import ast
import graphlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("contactlab", "dem_check")

MAX_LINES = 500
"""Largest source module [lines]: a module is one idea (architecture issue)."""

LAYERS = (
    (
        "foundation",
        (
            "contactlab.errors",
            "contactlab.blas",
            "contactlab.validation",
            "contactlab.entry_checks",
            "contactlab.roots",
            "contactlab.plausibility",
            "contactlab.strict_json",
            "contactlab.compiled",
            "contactlab.engines",
            "contactlab.quantities",
            "contactlab.tables",
        ),
    ),
    ("compiled numerical core", ("contactlab.kernels",)),
    ("closed forms and bodies", ("contactlab.analytic", "contactlab.bodies")),
    ("contact laws", ("contactlab.laws",)),
    (
        "results, metrics and traces",
        (
            "contactlab.metrics",
            "contactlab.signals",
            "contactlab._head_level",
            "contactlab._block_levels",
            "contactlab.result",
            "contactlab.oblique_result",
            "contactlab.plotting",
            "contactlab.quadrature",
            "contactlab.audit",
            "contactlab.impact_audit",
            "contactlab.traces",
        ),
    ),
    ("solver", ("contactlab.solver", "contactlab.config", "contactlab.batch", "contactlab")),
    ("studies", ("contactlab.study", "contactlab.advisor", "contactlab.benchmarks")),
    ("measurements", ("contactlab.compare", "contactlab.inverse")),
    ("applications", ("contactlab.testing", "contactlab.demo", "contactlab.cli")),
    (
        "DEM engines and campaigns",
        (
            "dem_check.traces",
            "dem_check.compare",
            "dem_check.engines",
            "dem_check.engines.kratos",
            "dem_check.campaign",
            "dem_check.stream",
        ),
    ),
    ("dem_check's applications", ("dem_check.cli", "dem_check")),
)
"""Layers from the bottom up, as module-name prefixes; the longest matching prefix places
a module (a package's own name, ``contactlab`` or ``dem_check``, places only its
``__init__``). A module imports from its own layer or the ones below, never above."""


def _modules():
    """Module name -> source path, for every module of the two packages."""
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            found[name] = path
    return found


MODULES = _modules()


def _resolve(module, name):
    """What ``from module import name`` depends on: the submodule if there is one."""
    return f"{module}.{name}" if f"{module}.{name}" in MODULES else module


def _imports(name, path):
    """Project modules that ``name`` imports anywhere in its source."""
    is_package = path.name == "__init__.py"
    deps = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            deps.update(a.name for a in node.names if a.name in MODULES)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = name.split(".") if is_package else name.split(".")[:-1]
                anchor = anchor[: len(anchor) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            if base in MODULES:
                deps.update(_resolve(base, a.name) for a in node.names)
    deps.discard(name)
    return deps


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def _layer(name):
    matches = [
        (len(prefix), index)
        for index, (_, prefixes) in enumerate(LAYERS)
        for prefix in prefixes
        if name == prefix or (prefix not in PACKAGES and name.startswith(prefix + "."))
    ]
    return max(matches)[1] if matches else None


def test_every_module_has_a_layer():
    unplaced = sorted(name for name in MODULES if _layer(name) is None)
    assert not unplaced, f"place these modules in a layer of LAYERS: {unplaced}"


def test_no_module_imports_a_layer_above_its_own():
    climbs = [
        f"{name} ({LAYERS[_layer(name)][0]}) imports {dep} ({LAYERS[_layer(dep)][0]})"
        for name, deps in GRAPH.items()
        for dep in sorted(deps)
        if _layer(dep) > _layer(name)
    ]
    assert not climbs, "\n".join(climbs)


def _child_edges_removed():
    """The graph without a package's imports of its own children (re-exports are fine)."""
    return {name: {d for d in deps if not d.startswith(name + ".")} for name, deps in GRAPH.items()}


def test_no_import_cycle():
    try:
        graphlib.TopologicalSorter(_child_edges_removed()).prepare()
    except graphlib.CycleError as exc:
        pytest.fail(f"import cycle: {' -> '.join(exc.args[1])}")


def test_cycle_check_catches_a_cycle():
    """The check itself: a two-module cycle is reported."""
    with pytest.raises(graphlib.CycleError):
        graphlib.TopologicalSorter({"a": {"b"}, "b": {"a"}}).prepare()


def test_laws_never_simulate():
    """Laws define forces and closed forms only; simulation lives in the solver."""
    reach = {
        dep
        for name, deps in GRAPH.items()
        if name.startswith("contactlab.laws")
        for dep in deps
        if dep.startswith(("contactlab.solver", "contactlab.result"))
    }
    assert not reach, f"contactlab.laws imports {sorted(reach)}"


def _contactlab_imports_of_dem_check(graph):
    """``"module imports dep"`` for each import of dem_check by a contactlab module."""
    return [
        f"{name} imports {dep}"
        for name, deps in graph.items()
        if name.split(".")[0] == "contactlab"
        for dep in sorted(deps)
        if dep.split(".")[0] == "dem_check"
    ]


def test_contactlab_never_imports_dem_check():
    """dem_check builds on contactlab, never the other way, lazily or not: contactlab's
    commands find DEM engines through the ``contactlab.engines`` entry points."""
    reach = _contactlab_imports_of_dem_check(GRAPH)
    assert not reach, "\n".join(reach)


@pytest.mark.parametrize(
    "source",
    [
        "def f():\n    from dem_check.traces import Trace\n",
        "def f():\n    import dem_check.engines\n",
        "class A:\n    def f(self):\n        from dem_check import engines\n",
    ],
)
def test_dem_check_check_catches_a_function_level_import(tmp_path, source):
    """The check itself: a lazy import inside a function (or a method) of any contactlab
    module, its applications included, is found; dem_check importing itself is not."""
    path = tmp_path / "module.py"
    path.write_text(source, encoding="utf-8")
    graph = {name: _imports(name, path) for name in ("contactlab.cli.inverse", "dem_check.cli")}
    found = _contactlab_imports_of_dem_check(graph)
    assert len(found) == 1 and found[0].startswith("contactlab.cli.inverse imports dem_check")


@pytest.mark.parametrize("name", sorted(MODULES))
def test_module_is_small(name):
    lines = MODULES[name].read_text(encoding="utf-8").count("\n")
    assert lines <= MAX_LINES, f"{MODULES[name].relative_to(ROOT)} has {lines} lines"
