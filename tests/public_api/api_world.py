"""Valid arguments of every public callable: the world the API property tests start from.

Values by parameter name (:data:`VALUES`), by callable (:data:`OVERRIDES`), instances of
classes their constructor's valid call cannot build (:data:`INSTANCES`), and the cached
objects behind them (a grain, a sensor, an impact, a fit, a trace, a study...). Imported
by ``conftest.py`` (see its docstring).
"""

import functools
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[2]
TRACE_FILE = ROOT / "data" / "traces" / "generic.csv"

instance = None
"""``conftest.instance`` (a valid instance of a public class), bound when conftest loads."""

# --- the valid world every call starts from ------------------------------------------------


def _on_a_wall(quantity):
    """The law's ``quantity`` for the grain at 2 m/s on a rigid wall (``cl.wall_*``)."""
    import contactlab as cl

    return getattr(cl, f"wall_{quantity}")(law(), grain().mass, 2.0)


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
    tangential = cl.laws.Mindlin.from_material(
        cl.analytic.Material(21.6e6, 0.2, grain().radius), friction=0.5
    )
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


def _sliding():
    import contactlab as cl

    return cl.analytic.ObliqueImpact(2.0, 10.0, 0.0, 2.5e-3, 0.8, 0.5)


def _steel_flat():
    import contactlab as cl

    return cl.analytic.Material(210e9, 0.3, float("inf"))


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
    "poisson_ratio": lambda: 0.2, "radius": lambda: 2.5e-3,
    "other": lambda: _steel_flat(),
    "material": lambda: grain().material(),
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
    "noise_model": lambda: "ar", "contact_edges": lambda: "significance",
    "contact_family": lambda: ("linear", 0.2),
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
    # streams
    "case": lambda: stream_case(), "result": lambda: stream_result(),
    "scored": lambda: _stream_score(), "features": lambda: _stream_features(),
    "detector": lambda: None, "run": lambda: _stream_run, "reach": lambda: 1e-4,
    "pileup_rates": lambda: (500.0,), "capacity": lambda: 0.05,
    "effects": lambda: _effects(), "end_rate": lambda: 800.0,
    "tangential": lambda: {"law": "mindlin", "friction": 0.3},
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
    # solver states (Sensor.signal, Sensor.energy)
    "states": lambda: np.zeros((64, 4)), "contact_force": lambda: np.zeros(64),
    "x1": lambda: 1e-6, "v1": lambda: 0.1,
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


def _oblique_frame():
    """One oblique Hertz-Mindlin row (contactlab.batch.oblique_impacts)."""
    mindlin = {"k_mindlin [N/m**1.5]": 1e6, "friction [-]": 0.3}
    frame = _frame("hertz").assign(**mindlin)
    return frame.assign(**{"radius [m]": 2.5e-3, "angle [rad]": 0.5, "spin [rad/s]": 0.0})


STREAM_TOML = """[stream]
duration = 3e-3
noise = 0.005
[flow]
rate = 500.0
arrivals = 'regular'
[[particles]]
species = 'wheat'
contact = {law = 'hertz_damped', from_material = true, restitution = 0.5}
"""
"""A stream case of one wheat particle in 3 ms (one LAMMPS run of about 4 s)."""


@functools.cache
def _stream_case_file():
    path = _temporary("case.toml")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(STREAM_TOML, "utf-8")
    return path


@functools.cache
def stream_case():
    from dem_check.stream import read_case

    return read_case(_stream_case_file())


@functools.cache
def stream_result():
    """The stream of :data:`STREAM_TOML`, run once in LAMMPS."""
    import warnings

    from contactlab.errors import ContactlabWarning
    from dem_check.stream import run_stream

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ContactlabWarning)
        return run_stream(stream_case())


def _stream_run(case):
    """A stream runner (``run(case) -> StreamResult``) that returns the one run: the
    curves' own arithmetic is what their valid call exercises, not LAMMPS again."""
    return stream_result()


@functools.cache
def _stream_score():
    from dem_check.stream import score

    return score(stream_result())


@functools.cache
def _stream_features():
    """A :func:`~dem_check.stream.hit_features` table of four hits, two of each kind (the
    one-particle stream has one hit; the classification needs two per fold)."""
    from dem_check.stream import FEATURES, hit_features

    one = hit_features(stream_result(), _stream_score())
    rows = pd.concat([one] * 4, ignore_index=True)
    rows["kind"] = ["wheat", "chaff", "wheat", "chaff"]
    rows[list(FEATURES)] *= np.array([1.0, 0.5, 1.1, 0.6])[:, None]
    return rows


def _effects():
    from dem_check.campaign.records import Effects

    return Effects()


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
    "contactlab.analytic.hertz.hunt_crossley_restitution_linearised": {"damping": lambda: 0.1},
    "contactlab.config.second_body": {"table": lambda: {"other_youngs_modulus": 2e11}},
    "contactlab.analytic.tangential.ObliqueImpact": {"normal_velocity": lambda: 2.0,
                                                     "tangential_velocity": lambda: 10.0},
    "contactlab.analytic.tangential.gross_sliding_rebound": {"impact": lambda: _sliding()},
    "contactlab.analytic.tangential.slides_throughout": {"impact": lambda: _sliding()},
    "contactlab.batch.hertz.hertz_impacts": {"frame": lambda: _frame("hertz")},
    "contactlab.batch.oblique.oblique_impacts": {"frame": _oblique_frame},
    "contactlab.quantities.quantity": {"name": lambda: "contact_time"},
    "contactlab.quantities.column": {"name": lambda: "contact_time"},
    "contactlab.engines.load_engine": {"name": lambda: "bullet"},
    "dem_check.stream.case.read_case": {"path": _stream_case_file},
    "dem_check.stream.case.Flow": {"rate": lambda: 500.0},
    "dem_check.stream.case.Flow.at": {"t": lambda: np.linspace(0.0, 3e-3, 64),
                                     "duration": lambda: 3e-3},
    "dem_check.stream.case.ParticleKind": {
        "name": lambda: "wheat", "diameter": lambda: (4e-3, 5e-3),
        "density": lambda: (1200.0, 1400.0), "contact": lambda: {"law": "linear",
                                                                 "stiffness": 1e5}},
    "dem_check.stream.case.StreamCase": {"particles": lambda: stream_case().particles},
    "dem_check.stream.calibration.calibration_curve": {
        "capacity": lambda: 0.05, "**": lambda: {"run": _stream_run}},
    "dem_check.stream.scoring.pileup_curve": {
        "rates": lambda: (500.0,), "**": lambda: {"run": _stream_run}},
    "dem_check.stream.scoring.campaign_detector": {"trace": lambda: stream_result().trace()},
    "dem_check.stream.result.StreamResult.write": {"out": lambda: _temporary("stream")},
    "dem_check.stream.study.stream_study": {"out": lambda: _temporary("stream")},
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
    "contactlab.inverse.identify.SensorIdentification.ringing": {"t": lambda: np.linspace(
        *instance("contactlab.inverse.identify.SensorIdentification").window, 64)},
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
        "expected": lambda: _on_a_wall("contact_time")},
    "contactlab.testing.assertions.assert_restitution": {
        "expected": lambda: _on_a_wall("restitution")},
    "contactlab.testing.golden_trace.GoldenTrace.read": {"directory": lambda: _golden()},
    "contactlab.testing.golden.GoldenStore.check": {"name": lambda: "case"},
    "contactlab.compare.impacts.compare_trace": {"trace": lambda: _force_trace()},
    "contactlab.traces.api.write_trace": {"path": lambda: _temporary("trace.csv")},
    "contactlab.inverse.fit_result.ContactFit.to_json": {"path": lambda: _temporary("FIT.json")},
    "contactlab.traces.trace.Trace.derive": {"step": lambda: {"step": "test"}},
    "contactlab.config.law_from_table": {
        "table": lambda: {"law": "linear", "stiffness": 1e4, "damping": 0.3}},
    "contactlab.config.sensor_from_table": {
        "table": lambda: {"diameter": 10e-3, "thickness": 2e-3, "resonance": 40e3}},
    "contactlab.traces.trace.Trace": {"t": lambda: trace().t, "values": lambda: trace().values,
                                     "unit": lambda: "V"},
}  # fmt: skip
"""Values of one callable's parameters where the name alone does not tell."""

INSTANCES = {
    "contactlab.result.ImpactResult": impact,
    "contactlab.oblique_result.ObliqueResult": oblique,
    "contactlab.inverse.fit_result.ContactFit": fit,
    "contactlab.inverse.identify.SensorIdentification": _identification,
    "contactlab.inverse.reconstruction.ForceReconstruction": _reconstruction,
    "contactlab.study.setup.StudySetup": setup,
    "contactlab.study.sweep.SweepResult": lambda: _study(),
    "contactlab.study.design_map.DesignMap": lambda: _design_map(),
    "contactlab.metrics.PulseMetrics": lambda: impact().sensor_metrics,
    "contactlab.testing.golden_trace.GoldenTrace": lambda: _golden_trace(),
    "contactlab.laws.base.Exit": lambda: _exit(),
    "contactlab.advisor.species.Species": species,
    "contactlab.analytic.pair.PairRebound": lambda: _pair(),
    "contactlab.compare.comparison.Comparison": lambda: _comparison(),
    "dem_check.engines.result.EngineResult": lambda: _engine_result(),
    "dem_check.campaign.result.CampaignResult": lambda: _campaign(),
    "contactlab.traces.trace.Trace": trace,
    "contactlab.testing.golden.GoldenStore": lambda: _store(),
    "dem_check.stream.case.StreamCase": lambda: stream_case(),
    "dem_check.stream.case.Flow": lambda: stream_case().flow,
    "dem_check.stream.case.ParticleKind": lambda: stream_case().particles[0],
    "dem_check.stream.result.StreamResult": lambda: stream_result(),
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
    from contactlab.config import ImpactConfig
    from dem_check import drop_test

    return drop_test(ImpactConfig(grain(), sensor(), law(), {"velocity": 2.0}))


@functools.cache
def _force_trace():
    from dem_check.traces import read_trace

    return read_trace(TRACE_FILE, sensitivity=0.01)


@functools.cache
def _campaign():
    from dem_check import run_campaign

    return run_campaign([TRACE_FILE], sensor(), sensitivity=0.01)
