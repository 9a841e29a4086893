"""The public API, enumerated from the source, and a valid call of each of its callables.

:func:`public_callables` walks ``contactlab``, ``dem_check`` and every public sub-package
and module of them (all but :data:`NOT_PUBLIC`), reads each ``__all__`` and collects every
function, class and public method there, named by where it is defined
(``contactlab.laws.hertz.Hertz.force``). :func:`baseline` builds a valid call of each: a
required argument's value comes from :data:`VALUES` (by parameter name) or
:data:`OVERRIDES` (by callable); an optional one keeps its default, and its kind (what a
hostile value for it is) comes from the default or, for a ``None`` default, from the same
tables. A callable none of this can call is a failure of ``test_api_coverage.py`` until
it is given values or listed in :data:`EXEMPT` with a reason, so a new public function is
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
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from contactlab.errors import ContactlabWarning

ROOT = Path(__file__).resolve().parents[2]
TRACE_FILE = ROOT / "data" / "traces" / "generic.csv"

PACKAGES = ("contactlab", "dem_check")

NOT_PUBLIC = {
    "contactlab.errors": "the exception classes themselves",
    "contactlab.validation": "the entry checks themselves (tests/contactlab/test_validation*)",
    "contactlab.compiled": "numba's njit for the compiled modules",
    "contactlab.roots": "root locator of the solvers' events (internal)",
    "contactlab.quadrature": "Gauss-Legendre rule of the audits (internal)",
    "contactlab.plotting": "drawing helpers of the results' plot methods (covered there)",
    "contactlab.strict_json": "JSON writer of the results (internal)",
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
    "contactlab.inverse.reconstruct.ForceReconstruction": "result record of reconstruct_force",
    "contactlab.metrics.PulseMetrics": "result record built by pulse_metrics",
    "contactlab.signals.Baseline": "result record (a named tuple) built by baseline",
    "contactlab.signals.RunningBaseline": "result record (a named tuple) of running_baseline",
    "contactlab.analytic.pair.PairRebound": "result record built by pair_rebound",
    "contactlab.laws.base.Branch": "a law's branch description, built by the law",
    "contactlab.laws.base.Exit": "a branch's exit condition, built by the law",
    "contactlab.advisor.advice.Advice": "result record built by advise",
    "dem_check.compare.comparison.Comparison": "result record built by compare",
    "dem_check.compare.quantities.Quantity": "a row of the tolerance table, built there",
    "dem_check.engines.result.EngineResult": "result record built by the engines",
    "dem_check.campaign.result.CampaignResult": "result record built by run_campaign",
    "contactlab.testing.closed_forms.ClosedForm": "record a closed-form function returns",
    "contactlab.testing.golden_trace.GoldenTrace": "record built by GoldenTrace.of/read",
    "contactlab.config.ImpactConfig": "record built by load_config/load_preset",
    "contactlab.plausibility.Range": "a row of the RANGES table, built there",
    "contactlab.result.ImpactResult": "result record built by simulate_impact",
    "contactlab.oblique_result.ObliqueResult": "result record built by simulate_oblique",
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


def kind(value):
    """What sort of argument a valid value is: it selects the hostile values tried."""
    if isinstance(value, bool):
        return "flag"
    if isinstance(value, numbers.Integral):
        return "count"
    if isinstance(value, numbers.Real):
        return "number"
    if isinstance(value, str):
        return "text"
    if isinstance(value, os.PathLike):
        return "path"
    if isinstance(value, np.ndarray):
        return "array"
    if isinstance(value, dict):
        return "mapping"
    if isinstance(value, tuple | list):
        return "sequence"
    return "object"


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


def _kind(name, parameter, value):
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
        try:
            value = _value(name, p.name) if empty or p.default is None else p.default
        except LookupError:
            missing.append(p.name)
            continue
        if empty:
            arguments[p.name] = value
        kinds[p.name] = (_kind(name, p.name, value), None if empty else p.default)
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


# --- the valid world every call starts from ------------------------------------------------


@functools.cache
def grain():
    import contactlab as cl

    return cl.Grain(diameter=5e-3, density=765.0, youngs_modulus=21.6e6, poisson_ratio=0.2)


@functools.cache
def sensor():
    import contactlab as cl

    return cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)


@functools.cache
def law():
    import contactlab as cl

    return cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)


@functools.cache
def impact():
    import contactlab as cl

    return cl.simulate_impact(grain(), sensor(), law(), 2.0, duration=5e-4, sample_rate=1e6)


@functools.cache
def oblique():
    import contactlab as cl

    normal = cl.laws.HertzDamped(1.5e6, 4.0)
    tangential = cl.laws.Mindlin.from_material(21.6e6, 0.2, grain().radius, friction=0.5)
    return cl.simulate_oblique(grain(), sensor(), normal, tangential, 2.0, 0.5,
                               duration=5e-4, sample_rate=1e6)  # fmt: skip


@functools.cache
def synthetic():
    """``(t, signal, truth)`` of a noisy sensor signal (contactlab.inverse.synthetic_trace)."""
    from contactlab.inverse import synthetic_trace

    return synthetic_trace(grain(), sensor(), law(), 2.0, duration=3e-4, sample_rate=2e6)


@functools.cache
def fit():
    from contactlab.inverse import fit_contact

    t, signal, _ = synthetic()
    return fit_contact(t, signal, grain(), sensor(), velocity=2.0, max_nfev=20)


@functools.cache
def trace():
    from dem_check.traces import read_trace

    return read_trace(TRACE_FILE)


@functools.cache
def setup():
    from contactlab.study import StudySetup

    return StudySetup(grain(), sensor(), law())


@functools.cache
def species():
    from contactlab.advisor import list_species, load_species

    return load_species(list_species()[0])


_SCRATCH = tempfile.TemporaryDirectory(prefix="contactlab-api-")
"""Folder of the files the valid calls write; removed when the tests end."""


def _temporary(name):
    """A path in a new folder (the folder exists, the file does not)."""
    return Path(tempfile.mkdtemp(dir=_SCRATCH.name)) / name


def _array(n=64):
    return np.linspace(0.0, 1e-4, n)


def _pulse(n=64):
    return np.sin(np.linspace(0.0, np.pi, n)) ** 2


VALUES = {
    # bodies, laws, impacts
    "grain": grain, "sensor": sensor, "law": law, "normal_law": law,
    "tangential_law": lambda: instance("contactlab.laws.tangential.Mindlin"),
    "mass": lambda: 5e-5, "velocity": lambda: 2.0, "overlap": lambda: 1e-6,
    "max_overlap": lambda: 2e-6, "rate": lambda: 0.5, "stiffness": lambda: 1e5,
    "damping": lambda: 1.0, "k_hertz": lambda: 1.5e6, "k_mindlin": lambda: 1e4,
    "dissipation": lambda: 1e-6, "exponent": lambda: 1.5, "yield_force": lambda: 0.5,
    "loading_stiffness": lambda: 1e5, "unloading_stiffness": lambda: 2e5,
    "effective_modulus": lambda: 20e6, "effective_radius": lambda: 2.5e-3,
    "effective_shear_modulus": lambda: 8e6, "yield_pressure": lambda: 5e6,
    "youngs_modulus": lambda: 21.6e6, "shear_modulus": lambda: 9e6,
    "poisson_ratio": lambda: 0.2, "radius": lambda: 2.5e-3, "other": lambda: 2.5e-3,
    "density": lambda: 765.0, "diameter": lambda: 5e-3, "thickness": lambda: 2e-3,
    "resonance": lambda: 40e3, "damping_ratio": lambda: 0.02, "friction": lambda: 0.5,
    "restitution": lambda: 0.8, "alpha": lambda: 0.5, "contact_time": lambda: 1e-4,
    "ramp_time": lambda: 2e-5, "time": lambda: 5e-5, "amplitude": lambda: 3.0,
    "pulse_duration": lambda: 1e-4, "period": lambda: 2.5e-5, "angle": lambda: 0.5,
    "spin": lambda: 0.0, "normal_velocity": lambda: -2.0, "tangential_velocity": lambda: 1.0,
    "inertia_factor": lambda: 0.4, "slip": lambda: 1e-7, "slip_rate": lambda: 0.1,
    "overlap_rate": lambda: 0.5, "history": lambda: 0.0, "force": lambda: 0.1,
    "duration": lambda: 5e-4, "sample_rate": lambda: 1e6, "time_step": lambda: 1e-7,
    "threshold": lambda: 0.0, "rtol": lambda: 1e-6, "expected": lambda: 0.8,
    "masses": lambda: (5e-5, 1e-3), "radii": lambda: (2.5e-3, 5e-3),
    "before": lambda: instance("contactlab.analytic.pair.PairRebound"),
    "normal_impulse": lambda: 1e-4, "tangential_impulse": lambda: 0.0,
    # signals, traces
    "t": _array, "y": _pulse, "signal": _pulse, "window": lambda: (0.0, 3e-5),
    "baseline_window": lambda: (-1e-4, -1e-5), "interval": lambda: 1e-6,
    "cutoff": lambda: 1e5, "width": lambda: 8, "exclude": lambda: np.zeros(64, bool),
    "k": lambda: 5.0, "pre_trigger": lambda: 1e-4, "onset": lambda: 0.0, "dt": lambda: 1e-6,
    "order": lambda: 2, "trace": trace, "path": lambda: TRACE_FILE,
    "sensitivity": lambda: 0.01, "channel": lambda: 0, "measured": lambda: 1.1,
    "true": lambda: 1.0, "start": lambda: 0.0, "end": lambda: 1e-4, "low": lambda: 0.1,
    "high": lambda: 0.9, "a": impact, "b": impact, "actual": impact, "reference": impact,
    "tolerances": lambda: {}, "labels": lambda: ("a", "b"), "config": lambda: _preset(),
    "step": lambda: 1, "min_force": lambda: 0.1, "min_separation": lambda: 1e-3,
    # inverse
    "fit": fit, "code": lambda: "lammps", "identification": lambda: _identification(),
    "reconstruction": lambda: _reconstruction(), "truth": lambda: None,
    "max_unknowns": lambda: 400, "regularization": lambda: "gcv", "fixed": lambda: {},
    "laws": lambda: ("linear",), "y_pencil": _pulse, "seed": lambda: 0,
    # study, advisor
    "setup": setup, "overrides": lambda: {}, "factors": lambda: np.ones(3),
    "grid": lambda: {"resonance": [40e3]}, "resonances": lambda: (40e3,),
    "diameters": lambda: (5e-3,), "impacts": lambda: _impacts(), "by": lambda: "resonance",
    "tasks": lambda: [], "column": lambda: "resonance", "species": species,
    "target": lambda: 5.0, "cases": lambda: "corners", "noise": lambda: 0.01,
    "peak": lambda: 1.0, "seed_sequence": lambda: np.random.SeedSequence(0),
    "factor": lambda: 1.0, "tolerance": lambda: 10.0, "client": lambda: None,
    "progress": lambda: False, "chunksize": lambda: 1, "partitions": lambda: 1,
    "frame": lambda: _frame(),
    # campaigns, records
    "paths": lambda: [TRACE_FILE], "velocities": lambda: (2.0,), "onsets": lambda: (1e-4,),
    "length": lambda: 1e-3, "out": lambda: _temporary("out"), "metadata": lambda: None,
    "trigger": lambda: 0.1, "directory": lambda: _temporary("golden"),
    "impact": impact, "name": lambda: "case", "law_class": lambda: _Law,
    "function": lambda: (lambda law, mass, velocity: []), "log": lambda: [],
    "ax": lambda: None, "title": lambda: "title", "engine": lambda: "bullet",
    "key": lambda: "grain.diameter", "value": lambda: 5e-3, "values": lambda: [5e-3],
    "what": lambda: "case", "preset": lambda: None, "samples": lambda: 101,
    "max_nfev": lambda: 20, "align": lambda: "onset", "friction_steel": lambda: 0.3,
    "full_scale": lambda: 10.0, "vary": lambda: "stiffness",
}  # fmt: skip
"""A valid value of each parameter, by name."""

KINDS = {
    "title": "label", "source": "label", "description": "label", "what": "label",
    "labels": "label", "sources": "label", "unit": "label", "name": "label",
    "channel": "object",  # a name or an index: anything but a name or index is wrong
    "tolerances": "mapping", "fixed": "mapping", "overrides": "mapping", "grid": "mapping",
    "client": "opaque", "ax": "object", "align": "text", "friction_steel": "number",
    "truth": "object", "metadata": "object",
}  # fmt: skip
"""Parameters whose kind the valid value does not say."""


class _Law:
    """A throwaway class for register_closed_form (the registry is global)."""


def _preset():
    from contactlab.config import list_presets, load_preset

    return load_preset(list_presets()[0])


def _identification():
    from contactlab.inverse import identify_sensor

    truth = synthetic()[2]
    return identify_sensor(truth.t, truth.sensor_force)


def _reconstruction():
    from contactlab.inverse import reconstruct_force

    t, signal, _ = synthetic()
    return reconstruct_force(t, signal, sensor(), max_unknowns=200)


def _impacts():
    return pd.DataFrame({"resonance": [40e3, 40e3], "error": [1.0, 2.0]})


def _frame(law="linear"):
    from contactlab.batch.warm_up import _one_row_frame

    if law == "hertz":
        return _one_row_frame(**{"k_hertz [N/m**1.5]": 3.0e6, "damping [N*s/m**1.25]": 2.0})
    return _one_row_frame(**{"k2 [N/m]": 1e5, "c2 [N*s/m]": 1.0})


def _measured(name):
    """``t`` and ``signal`` of the synthetic sensor signal, for the inverse methods."""
    t, signal, _ = synthetic()
    return {"t": lambda: t, "signal": lambda: signal}[name]


_MEASURED = {"t": _measured("t"), "signal": _measured("signal")}

OVERRIDES = {
    "contactlab.advisor.species.Species.from_toml": {"path": lambda: _species_file()},
    "contactlab.advisor.species.load_species": {"name": lambda: "wheat"},
    "contactlab.config.load_preset": {"name": lambda: "fig5"},
    "contactlab.config.load": {"**": lambda: {"preset": "fig5"},
                               "config": lambda: ROOT / "data/traces/model_soft.toml"},
    "contactlab.config.load_config": {"path": lambda: ROOT / "data/traces/model_soft.toml"},
    "contactlab.config.read_document": {"path": lambda: ROOT / "data/traces/model_soft.toml"},
    "contactlab.inverse.export.contact.read_fit": {"path": lambda: _fit_file()},
    "contactlab.inverse.demo.reconstruction_demo": {"path": lambda: _temporary("demo.png")},
    "contactlab.laws.get_law": {"name": lambda: "linear", "**": lambda: {"stiffness": 1e5}},
    "contactlab.analytic.materials.contact_modulus_radius": {
        "other": lambda: (210e9, 0.3, float("inf"))},
    "contactlab.analytic.hertz.hunt_crossley_restitution_linearised": {"damping": lambda: 0.1},
    "contactlab.analytic.tangential.gross_sliding_rebound": {"normal_velocity": lambda: 2.0,
                                                             "tangential_velocity": lambda: 10.0},
    "contactlab.analytic.tangential.slides_throughout": {"normal_velocity": lambda: 2.0},
    "contactlab.batch.hertz.hertz_impacts": {"frame": lambda: _frame("hertz")},
    "contactlab.batch.dask.dask_hertz_impacts": {"frame": lambda: _frame("hertz"),
                                                 "client": lambda: "tcp://127.0.0.1:1"},
    "contactlab.batch.dask.dask_linear_impacts": {"client": lambda: "tcp://127.0.0.1:1"},
    "contactlab.bodies.Grain": {"**": lambda: {"density": 765.0}},
    "contactlab.inverse.compare_laws.compare_laws": _MEASURED,
    "contactlab.inverse.fit.fit_contact": _MEASURED,
    "contactlab.inverse.reconstruct.reconstruct_force": _MEASURED,
    "contactlab.inverse.identify.identify_sensor": {
        "t": lambda: synthetic()[2].t, "signal": lambda: synthetic()[2].sensor_force},
    "contactlab.inverse.plots.plot_identification": {
        "t": lambda: synthetic()[2].t, "signal": lambda: synthetic()[2].sensor_force},
    "contactlab.inverse.identify.matrix_pencil": {"y": lambda: synthetic()[2].sensor_force},
    "contactlab.plausibility.check_plausible": {"key": lambda: "grain_diameter"},
    "contactlab.plausibility.implausible_rows": {"key": lambda: "grain_diameter",
                                                 "labels": lambda: ["row 0"]},
    "contactlab.plausibility.likely_slips": {"key": lambda: "grain_diameter"},
    "contactlab.signals.detect_onset": {"y": lambda: np.r_[np.zeros(32), np.ones(32)]
                                        + 1e-3 * np.sin(np.arange(64.0))},
    "contactlab.signals.running_baseline": {
        "width": lambda: 32, "y": lambda: np.random.default_rng(0).normal(size=256)},
    "contactlab.study.sweep.point_statistics": {"impacts": lambda: _study().impacts,
                                                "by": lambda: "resonance [Hz]"},
    "contactlab.study.setup.StudySetup.check_parameter": {"name": lambda: "sensor.resonance"},
    "contactlab.study.setup.StudySetup.column": {"name": lambda: "sensor.resonance"},
    "contactlab.study.design_map.DesignMap.grid": {"column": lambda: "time_error [%]"},
    "contactlab.study.sweep.run_grid": {"grid": lambda: {"sensor.resonance": [40e3]}},
    "contactlab.testing.assertions.assert_contact_time": {
        "expected": lambda: law().contact_time(grain().mass, 2.0)},
    "contactlab.testing.assertions.assert_restitution": {
        "expected": lambda: law().restitution(grain().mass, 2.0)},
    "contactlab.testing.golden_trace.GoldenTrace.read": {"directory": lambda: _golden()},
    "contactlab.testing.golden.GoldenStore.check": {"name": lambda: "case"},
    "dem_check.compare.impacts.compare_trace": {"trace": lambda: _force_trace()},
    "dem_check.traces.api.write_trace": {"path": lambda: _temporary("trace.csv")},
    "contactlab.inverse.fit_result.ContactFit.to_json": {"path": lambda: _temporary("FIT.json")},
    "dem_check.traces.trace.Trace": {"t": lambda: trace().t, "values": lambda: trace().values,
                                     "unit": lambda: "V"},
}  # fmt: skip
"""Values of one callable's parameters where the name alone does not tell."""

INSTANCES = {
    "contactlab.result.ImpactResult": impact,
    "contactlab.oblique_result.ObliqueResult": oblique,
    "contactlab.inverse.fit_result.ContactFit": fit,
    "contactlab.inverse.identify.SensorIdentification": _identification,
    "contactlab.inverse.reconstruct.ForceReconstruction": _reconstruction,
    "contactlab.study.setup.StudySetup": setup,
    "contactlab.study.sweep.SweepResult": lambda: _study(),
    "contactlab.study.design_map.DesignMap": lambda: _design_map(),
    "contactlab.metrics.PulseMetrics": lambda: impact().sensor_metrics,
    "contactlab.testing.golden_trace.GoldenTrace": lambda: _golden_trace(),
    "contactlab.laws.base.Exit": lambda: _exit(),
    "contactlab.advisor.species.Species": species,
    "contactlab.analytic.pair.PairRebound": lambda: _pair(),
    "dem_check.compare.comparison.Comparison": lambda: _comparison(),
    "dem_check.engines.result.EngineResult": lambda: _engine_result(),
    "dem_check.campaign.result.CampaignResult": lambda: _campaign(),
    "dem_check.traces.trace.Trace": trace,
    "contactlab.testing.golden.GoldenStore": lambda: _store(),
}
"""Instances of public classes their constructor's baseline cannot build."""

ABSTRACT = {
    "contactlab.laws.base.ContactLaw": "abstract: its methods run on every concrete law",
    "contactlab.laws.base.SmoothLaw": "abstract: its methods run on every concrete law",
    "contactlab.laws.tangential.TangentialLaw": "base: its methods run on its subclasses",
}
"""Base classes, neither constructed nor called (their subclasses are), with the reason."""


@functools.cache
def _study():
    from contactlab.study import run_grid

    return run_grid(setup(), {"sensor.resonance": [40e3]})


@functools.cache
def _design_map():
    from contactlab.study import design_map

    return design_map(setup(), resonances=(20e3, 40e3), diameters=(3e-3, 5e-3))


@functools.cache
def _species_file():
    from contactlab.advisor import SPECIES_DIR

    return SPECIES_DIR / "wheat.toml"


@functools.cache
def _fit_file():
    path = _temporary("FIT.json")
    path.parent.mkdir(parents=True, exist_ok=True)
    fit().to_json(path)
    return path


@functools.cache
def _golden_trace():
    from contactlab.testing import GoldenTrace

    return GoldenTrace.of("case", impact())


@functools.cache
def _golden():
    directory = _temporary("golden")
    directory.mkdir(parents=True)
    _golden_trace().write(directory)
    return directory


def _pair():
    from contactlab.analytic import PairRebound

    return PairRebound(2.0, -1.0, 0.0, 0.0, 0.0, 0.0)


@functools.cache
def _store():
    from contactlab.testing import GoldenStore

    return GoldenStore(_golden())


def _exit():
    from contactlab.laws import WaltonBraun

    return WaltonBraun(1e5, 2e5).branch("unloading").exits[0]


@functools.cache
def _comparison():
    from dem_check import compare

    return compare(impact(), impact())


@functools.cache
def _engine_result():
    from dem_check import drop_test

    return drop_test(grain(), sensor(), law(), 2.0)


@functools.cache
def _force_trace():
    from dem_check.traces import read_trace

    return read_trace(TRACE_FILE, sensitivity=0.01)


@functools.cache
def _campaign():
    from dem_check import run_campaign

    return run_campaign([TRACE_FILE], sensor(), sensitivity=0.01)


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
)  # fmt: skip
"""Methods of the laws (``contactlab.laws``) that the solvers call at every event or
integration step with their own state (Python floats): they are public so that a user can
write a law, but no user value reaches them, and a check there would cost every step of
the oblique solver. The laws' user-facing methods (``force``, ``work``, ``impact``,
``restitution``, ...) are covered."""


def covered():
    """Names of the public callables the property tests call, with arguments."""
    names = []
    for name in public_callables():
        cls = owner_class(name)
        owner = f"{cls.__module__}.{cls.__qualname__}" if cls else None
        if name in EXEMPT or name in ABSTRACT or owner in ABSTRACT:
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
    """Call with a hang alarm; ContactlabWarnings are answers too, other warnings errors."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, HANG)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactlabWarning)
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
        metafunc.parametrize("cheap_name", _pinned(cheap, KNOWN_HOSTILE_DEFECTS))


KNOWN_REFUSAL_DEFECTS = {}
"""Callables that still accept, or fail on, a value they must refuse: what was measured."""

KNOWN_HOSTILE_DEFECTS = {}
"""Callables that still raise something else than ParameterError on a drawn value."""


@pytest.fixture(autouse=True)
def _in_a_temporary_folder(tmp_path, monkeypatch):
    """Calls that write (a hostile text may be a relative path) write in a temporary folder."""
    monkeypatch.chdir(tmp_path)


@pytest.fixture(scope="session")
def api():
    """This module: the enumeration, the tables and the valid world."""
    return sys.modules[__name__]


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
    "flag": [], "label": [],
}  # fmt: skip
"""Values that no parameter of the kind may accept, by kind; ``None`` is added where the
parameter has no ``None`` default, ``inf`` is dropped where it is the default (a rigid
body's modulus)."""


NONE_ALLOWED = {"threads", "damping_ratio"}
"""Parameters with a number as default where ``None`` is documented too (every core; no
damping)."""


def refusals(kind_, default, parameter=""):
    """``[(label, value)]`` a parameter of this kind and default must refuse."""
    values = [(label, v) for label, v in MUST_REFUSE[kind_] if not _same(v, default)]
    if default is not None and kind_ not in ("flag", "label") and parameter not in NONE_ALLOWED:
        values.append(("None", None))
    return values


def _same(value, default):
    return isinstance(value, float) and isinstance(default, float) and value == default
