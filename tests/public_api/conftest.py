"""The public API, enumerated from the source, and a valid call of each of its callables.

:func:`public_callables` walks ``contactlab``, ``dem_check`` and every public sub-package
and module of them (all but :data:`NOT_PUBLIC`), reads each ``__all__`` and collects every
function, class and public method there, named by where it is defined
(``contactlab.laws.hertz.Hertz.force``). :func:`baseline` builds a valid call of each: a
required argument's value comes from :data:`VALUES` (by parameter name) or
:data:`OVERRIDES` (by callable); an optional one keeps its default, and its kind (what a
hostile value for it is) comes from the default or, for a ``None`` default (or the engine
entries' :data:`~dem_check.engines.config.UNSET`, "not given"), from the same tables. A
callable none of this can call is a failure of ``test_api_coverage.py`` until it is given
values or listed in :data:`EXEMPT` with a reason, so a new public function is
never silently left out.
"""

import functools
import importlib
import inspect
import math
import numbers
import os
import pkgutil
import signal
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from contactlab.errors import ContactlabWarning
from dem_check.engines.config import UNSET

sys.path.insert(0, str(Path(__file__).parent))  # the sibling modules below (importlib mode)

import api_world
from api_known import KNOWN_HOSTILE_DEFECTS, KNOWN_REFUSAL_DEFECTS
from api_world import ABSTRACT, INSTANCES, KINDS, OVERRIDES, VALUES

PACKAGES = ("contactlab", "dem_check")

NOT_PUBLIC = {
    "contactlab.errors": "the exception classes themselves",
    "contactlab.validation": "the entry checks themselves (tests/contactlab/test_validation*)",
    "contactlab.entry_checks": "the entry checks of objects and switches (same tests)",
    "contactlab.compiled": "numba's njit for the compiled modules",
    "contactlab.roots": "root locator of the solvers' events (internal)",
    "contactlab.quadrature": "Gauss-Legendre rule of the audits (internal)",
    "contactlab.plotting": "drawing helpers of the results' plot methods (covered there)",
    "contactlab.strict_json": "JSON writer of the results (internal)",
    "contactlab.tables": "spreadsheet-safe CSV tables (internal; tests/contactlab/test_tables.py)",
    "contactlab.audit": "invariant checks run by the solvers on their own results",
    "contactlab.impact_audit": "the normal impact's audit, run by the solver",
    "contactlab.result": "the result record ImpactResult (its methods are covered)",
    "contactlab.oblique_result": "the result record ObliqueResult (its methods are covered)",
    "contactlab.cli": "the command line: argv, tested in tests/contactlab/cli",
    "contactlab.demo": "the demo command's back end (minutes of work, tested in cli)",
    "contactlab.benchmarks": "benchmark harness (benchmarks/)",
    "contactlab.data": "package data, no code",
    "dem_check.cli": "the command line: argv, tested in tests/dem_check",
}
"""First-level modules outside the public API, with the reason."""

EXEMPT = {
    "contactlab.study.sweep.SweepResult": "result record built by the study",
    "contactlab.study.design_map.DesignMap": "result record built by design_map",
    "contactlab.inverse.fit_result.ContactFit": "result record built by fit_contact",
    "contactlab.inverse.fit_quality.FitQuality": "result record built by fit_contact",
    "contactlab.inverse.fit_result.FittedParameter": "result record built by fit_contact",
    "contactlab.inverse.compare_laws.LawComparison": "result record built by compare_laws",
    "contactlab.inverse.identify.SensorIdentification": "result record of identify_sensor",
    "contactlab.inverse.reconstruction.ForceReconstruction": "result record of reconstruct_force",
    "contactlab.metrics.PulseMetrics": "result record built by pulse_metrics",
    "contactlab.signals.Baseline": "result record (a named tuple) built by baseline",
    "contactlab.signals.RunningBaseline": "result record (a named tuple) of running_baseline",
    "contactlab.analytic.pair.PairRebound": "result record built by pair_rebound",
    "contactlab.laws.base.Branch": "a law's branch description, built by the law",
    "contactlab.laws.base.Exit": "a branch's exit condition, built by the law",
    "contactlab.advisor.advice.Advice": "result record built by advise",
    "contactlab.compare.comparison.Comparison": "result record built by compare",
    "contactlab.compare.quantities.Quantity": "a row of the tolerance table, built there",
    "dem_check.engines.result.EngineResult": "result record built by the engines",
    "dem_check.campaign.result.CampaignResult": "result record built by run_campaign",
    "contactlab.laws.closed_form.ClosedForm": "record a law's closed_forms returns",
    "contactlab.testing.golden_trace.GoldenTrace": "record built by GoldenTrace.of/read",
    "contactlab.config.ImpactConfig": "record built by load_config/load_preset",
    "contactlab.plausibility.Range": "a row of the RANGES table, built there",
    "contactlab.quantities.Quantity": "a row of the QUANTITIES vocabulary, built there",
    "contactlab.result.ImpactResult": "result record built by simulate_impact",
    "contactlab.oblique_result.ObliqueResult": "result record built by simulate_oblique",
    "dem_check.stream.calibration.Calibration": "result record built by calibration_curve",
    "dem_check.stream.scoring.Score": "result record built by score",
    "dem_check.stream.result.StreamResult": "result record built by run_stream (from "
    "LAMMPS' raw output)",
}
"""Constructors of records the library builds (their methods are covered), with the reason."""


def _public_modules():
    names = []
    for package in PACKAGES:
        module = importlib.import_module(package)
        names.append(package)
        for info in pkgutil.iter_modules(module.__path__, f"{package}."):
            short = info.name.rsplit(".", 1)[1]
            if not short.startswith("_") and info.name not in NOT_PUBLIC:
                names.append(info.name)
    return names


def _own_methods(cls):
    for name in dir(cls):
        if name.startswith("_"):
            continue
        raw = inspect.getattr_static(cls, name)
        if isinstance(raw, staticmethod | classmethod) or inspect.isfunction(raw):
            yield name, getattr(cls, name)


@functools.cache
def public_callables():
    """``{defining name: callable}`` of every public function, class and method."""
    found = {}
    for module_name in _public_modules():
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.ismodule(obj) or not callable(obj):
                continue
            if isinstance(obj, type) and issubclass(obj, BaseException):
                continue  # an exception class: raised, not called with user input
            qualified = f"{obj.__module__}.{obj.__qualname__}"
            found[qualified] = obj
            if isinstance(obj, type):
                for method_name, method in _own_methods(obj):
                    found[f"{qualified}.{method_name}"] = method
    return dict(sorted(found.items()))


def owner_class(name):
    """The class a method name belongs to, or None for a function or a class."""
    owner = name.rsplit(".", 1)[0]
    candidate = public_callables().get(owner)
    return candidate if isinstance(candidate, type) else None


def target(name):
    """What a call of ``name`` invokes: the function, the class, or a bound method of a
    valid instance (:func:`instance`)."""
    function = public_callables()[name]
    cls = owner_class(name)
    if cls is None:
        return function
    raw = inspect.getattr_static(cls, name.rsplit(".", 1)[1])
    if isinstance(raw, staticmethod | classmethod):
        return function
    return getattr(instance(f"{cls.__module__}.{cls.__qualname__}"), function.__name__)


def parameters(name, function=None):
    """The callable's named parameters (``self``, ``*args`` and ``**kwargs`` left out)."""
    function = public_callables()[name] if function is None else function
    signature = inspect.signature(function)
    kinds = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    names = [p for p in signature.parameters.values() if p.kind in kinds]
    if names and names[0].name == "self":
        names = names[1:]  # an unbound method's
    return names


METHOD_VALUES = {"work": {"overlap": lambda: np.linspace(0.0, 2e-6, 21)}}
"""Values of a parameter of every method of this name (a law's ``work`` takes a path)."""


def _value(name, parameter):
    method = METHOD_VALUES.get(name.rsplit(".", 1)[1], {})
    table = {**VALUES, **method, **OVERRIDES.get(name, {})}
    if parameter in table:
        return table[parameter]()
    raise LookupError(parameter)


KIND_OF_TYPE = (
    (bool, "flag"),
    (numbers.Integral, "count"),
    (numbers.Real, "number"),
    (str, "text"),
    (os.PathLike, "path"),
    (np.ndarray, "array"),
    (dict, "mapping"),
    (tuple | list, "sequence"),
)
"""``(type, kind)``, the first match wins (a bool is also an Integral, an int a Real)."""


def kind(value):
    """What sort of argument a valid value is: it selects the hostile values tried."""
    return next((name for cls, name in KIND_OF_TYPE if isinstance(value, cls)), "object")


VECTORISED = {
    "contactlab.laws.hertz.hertz_force", "contactlab.laws.hertz.hertz_damped_force",
    "contactlab.laws.hertz.kuwabara_kono_force", "contactlab.laws.hertz.hunt_crossley_force",
    "contactlab.laws.linear.linear_viscoelastic_force",
    "contactlab.laws.hysteretic.walton_braun_force", "contactlab.laws.plastic.linear_plastic_force",
    "contactlab.laws.plastic.thornton_force", "contactlab.laws.pulse.plastic_trapezoid_force",
    "contactlab.laws.tangential.mindlin_stiffness",
}  # fmt: skip
"""Vectorised functions: every numeric argument may be a scalar or an array."""

VECTORISED_METHODS = {"force": ("overlap", "rate", "max_overlap"), "force_at": ("time",)}
"""Methods whose named arguments may be a scalar or an array, on every class."""


CALLABLE_KINDS = {
    "contactlab.advisor.species.Species": dict.fromkeys(
        ("diameter", "density", "youngs_modulus", "friction_steel"), "values"),  # or ranges
}  # fmt: skip
"""Kinds of one callable's parameters where the name's kind is not theirs."""


def _kind(name, parameter, value):
    if parameter in CALLABLE_KINDS.get(name, {}):
        return CALLABLE_KINDS[name][parameter]
    if parameter in KINDS:
        return KINDS[parameter]
    numeric = kind(value) in ("number", "count", "array")
    if numeric and name in VECTORISED:
        return "values"
    if numeric and parameter in VECTORISED_METHODS.get(name.rsplit(".", 1)[1], ()):
        return "values"
    return kind(value)


def baseline(name):
    """``(callable, arguments, {parameter: (kind, default)})`` of a valid call of ``name``.

    Raises
    ------
    LookupError
        Naming the parameters no table gives a value or kind for.
    """
    function = target(name)
    arguments, kinds, missing = {}, {}, []
    for p in parameters(name, function):
        empty = p.default is inspect.Parameter.empty
        omitted = p.default is None or p.default is UNSET
        try:
            value = _value(name, p.name) if empty or omitted else p.default
        except LookupError:
            missing.append(p.name)
            continue
        if empty:
            arguments[p.name] = value
        kinds[p.name] = (_kind(name, p.name, value), None if empty or omitted else p.default)
    if missing:
        raise LookupError(f"{name}: no valid value for {', '.join(missing)}")
    if "**" in OVERRIDES.get(name, {}):
        arguments.update(OVERRIDES[name]["**"]())
    return function, arguments, kinds


@functools.cache
def instance(class_name):
    """A valid instance of a public class, for its methods."""
    if class_name in ABSTRACT:
        raise LookupError(f"{class_name}: {ABSTRACT[class_name]}")
    if class_name in INSTANCES:
        return INSTANCES[class_name]()
    function, arguments, _ = baseline(class_name)
    return function(**arguments)


COSTLY = {
    "contactlab.advisor.advice.advise", "contactlab.advisor.worst_case.sensor_errors",
    "contactlab.batch.dask.dask_hertz_impacts", "contactlab.batch.dask.dask_linear_impacts",
    "contactlab.inverse.compare_laws.compare_laws", "contactlab.inverse.demo.reconstruction_demo",
    "contactlab.inverse.fit.fit_contact", "contactlab.inverse.reconstruct.reconstruct_force",
    "contactlab.inverse.synthetic.synthetic_trace", "contactlab.inverse.export.export_dem",
    "contactlab.study.design_map.design_map", "contactlab.study.paper.paper_study",
    "contactlab.study.sweep.run_grid", "contactlab.study.sweep.diameter_sweep",
    "contactlab.study.sweep.frequency_sweep", "contactlab.study.points.simulate_point",
    "contactlab.study.points.simulate_points", "contactlab.solver.impact.simulate_impact",
    "contactlab.solver.oblique.simulate_oblique", "contactlab.solver.wall.wall_impact",
    "dem_check.campaign.api.run_campaign", "dem_check.campaign.records.realistic_record",
    "dem_check.campaign.synthetic.synthetic_record", "dem_check.engines.drop_test",
    "dem_check.campaign.result.CampaignResult.write",
    "dem_check.campaign.result.CampaignResult.to_html",
    "dem_check.stream.result.run_stream", "dem_check.stream.study.stream_study",
    "dem_check.stream.calibration.calibration_curve", "dem_check.stream.scoring.pileup_curve",
}  # fmt: skip
"""Callables whose valid calls take seconds (simulations, fits, studies, campaigns, a
cluster): only values that must be refused before any work are tried on them."""

COSTLY_METHODS = ("impact", "contact_time", "restitution", "dissipated_energy", "plot")
"""Method names that simulate an impact or draw a figure (costly on every class)."""


def costly(name):
    """Whether only must-refuse values are tried on ``name`` (see :data:`COSTLY`)."""
    short = name.rsplit(".", 1)[1]
    return name in COSTLY or short in COSTLY_METHODS or short.startswith(("plot", "assert_"))


SOLVER_INTERFACE = (
    "branch", "reentry", "value", "stiffness", "stiffness_slope", "damping_coefficient",
    "damping_slope", "trial_force", "trial_force_rate", "history_rate", "history_on_cap",
    "history_of", "elastic_force", "elastic_force_rate",
)  # fmt: skip
"""Methods of the laws (``contactlab.laws``) that the solvers call at every event or
integration step with their own state (Python floats): they are public so that a user can
write a law, but no user value reaches them, and a check there would cost every step of
the oblique solver. The laws' user-facing methods (``force``, ``work``, ``impact``,
``restitution``, ...) are covered."""


PENDING = {}
"""Public modules whose callables are not in the property tests yet, with the reason."""


def covered():
    """Names of the public callables the property tests call, with arguments."""
    names = []
    for name in public_callables():
        cls = owner_class(name)
        owner = f"{cls.__module__}.{cls.__qualname__}" if cls else None
        if name in EXEMPT or name in ABSTRACT or owner in ABSTRACT:
            continue
        if any(name == module or name.startswith(f"{module}.") for module in PENDING):
            continue
        interface = name.rsplit(".", 1)[1] in SOLVER_INTERFACE
        if owner and owner.startswith("contactlab.laws.") and interface:
            continue
        if parameters(name):
            names.append(name)
    return names


HANG = 30.0
"""A refusal takes milliseconds; a call still running after this many seconds hangs [s]."""


class Hang(Exception):
    """Raised by the alarm in a call that did not return in :data:`HANG` seconds."""


def _alarm(signum, frame):
    raise Hang(f"no answer within {HANG} s")


def call(function, arguments):
    """Call with a hang alarm; ContactlabWarnings and a deprecated callable's own
    DeprecationWarning are answers too, other warnings errors."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, HANG)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactlabWarning)
            # a deprecated callable's warning ("X is deprecated: use Y") is its answer
            warnings.filterwarnings("ignore", r"[\w.]+ is deprecated", DeprecationWarning)
            return function(**arguments)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def _pinned(names, defects):
    return [
        pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=defects[n]))
        if n in defects
        else n
        for n in names
    ]


def pytest_generate_tests(metafunc):
    """``api_name``: every covered callable; ``cheap_name``: those not :func:`costly`.

    Known defects (:data:`KNOWN_REFUSAL_DEFECTS`, :data:`KNOWN_HOSTILE_DEFECTS`) are strict
    xfails: fixing one turns its test into a failure until its entry is removed.
    """
    if "api_name" in metafunc.fixturenames:
        metafunc.parametrize("api_name", _pinned(covered(), KNOWN_REFUSAL_DEFECTS))
    if "cheap_name" in metafunc.fixturenames:
        cheap = [n for n in covered() if not costly(n)]
        reasons = {n: f"{p}={v!r}: {what}" for n, (p, v, what) in KNOWN_HOSTILE_DEFECTS.items()}
        metafunc.parametrize("cheap_name", _pinned(cheap, reasons))
    if "valid_name" in metafunc.fixturenames:
        metafunc.parametrize("valid_name", [n for n in covered() if not costly(n)])


@pytest.fixture(autouse=True)
def _in_a_temporary_folder(tmp_path, monkeypatch):
    """Calls that write (a hostile text may be a relative path) write in a temporary folder."""
    monkeypatch.chdir(tmp_path)


@pytest.fixture(scope="session")
def api():
    """This module: the enumeration, the tables and the valid world."""
    return sys.modules[__name__]


api_world.instance = instance


# --- hostile values ------------------------------------------------------------------------

MUST_REFUSE = {
    "number": [("nan", math.nan), ("inf", math.inf), ("-inf", -math.inf), ("text", "1e5"),
               ("complex", 1j), ("list", [1.0, 2.0])],
    "count": [("nan", math.nan), ("fraction", 2.5), ("text", "3"), ("negative", -1),
              ("bool", True)],
    "text": [("number", 1.0), ("list", ["a"])],
    "path": [("number", 1.0)],
    "array": [("empty", np.array([])), ("nan", np.full(64, math.nan)),
              ("2-D", np.ones((8, 8))), ("text", "1, 2, 3")],
    "mapping": [("number", 1.0), ("text", "a=1"), ("list", [1.0])],
    "sequence": [("number", math.nan), ("text", "abc"), ("nan", [math.nan])],
    "object": [("number", 1.0), ("text", "text"), ("list", [1.0])],
    "opaque": [("number", 1.0), ("list", [1.0])],
    "values": [("nan", math.nan), ("inf", math.inf), ("text", "1e5"), ("complex", 1j),
               ("ragged", [[1.0], [2.0, 3.0]])],
    "flag": [("text", "no"), ("number", 1.0), ("list", [True])], "label": [],
}  # fmt: skip
"""Values that no parameter of the kind may accept, by kind; ``None`` is added where the
parameter has no ``None`` default, ``inf`` is dropped where it is the default (a rigid
body's modulus)."""


NONE_ALLOWED = {"threads", "damping_ratio", "align", "duration"}
"""Parameters with a default where ``None`` is documented too (every core, no damping, no
alignment, the automatic window)."""


def refusals(kind_, default, parameter=""):
    """``[(label, value)]`` a parameter of this kind and default must refuse."""
    values = [(label, v) for label, v in MUST_REFUSE[kind_] if not _same(v, default)]
    if default is not None and kind_ not in ("flag", "label") and parameter not in NONE_ALLOWED:
        values.append(("None", None))
    return values


def _same(value, default):
    return isinstance(value, float) and isinstance(default, float) and value == default
