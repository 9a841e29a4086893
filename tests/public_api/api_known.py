"""Known defects the API property tests found and this change did not fix.

Each entry is a strict xfail (``conftest._pinned``) whose reason is what was measured:
the parameter, the values and what came out. Fixing one turns its test into a failure
until the entry is removed.
"""

import numpy as np

KNOWN_REFUSAL_DEFECTS = {
    "contactlab.advisor.advice.advise": (
        "sensor_mass nan/inf/-inf/text/complex/list/None: refused without naming it"
    ),
    "contactlab.advisor.worst_case.sensor_errors": (
        "sensor_mass nan/inf/-inf/text/complex/list/None: refused without naming it"
    ),
    "contactlab.inverse.compare_laws.compare_laws": "laws number: TypeError",
    "contactlab.inverse.identify.SensorIdentification.ringing": (
        "t empty/nan/2-D: accepted; t text: ValueError"
    ),
    "contactlab.inverse.identify.matrix_pencil": (
        "y empty/2-D/text: ValueError; y nan: LinAlgError; dt nan: RuntimeWarning; dt "
        "inf/-inf/complex/list: accepted; dt text: TypeError; order nan/fraction/text: "
        "TypeError; order negative/bool: accepted"
    ),
    "contactlab.inverse.plots.plot_fit": "fit number/text/list: AttributeError",
    "contactlab.inverse.plots.plot_identification": (
        "t empty/nan/2-D/text: ValueError; signal empty/nan/2-D/text: ValueError; "
        "identification number/text/list: AttributeError"
    ),
    "contactlab.inverse.plots.plot_reconstruction": (
        "reconstruction number/text/list: AttributeError; truth number: TypeError; truth "
        "text/list: ValueError"
    ),
    "contactlab.inverse.reconstruct.ForceReconstruction.plot": (
        "truth number/text/list: RuntimeWarning"
    ),
    "contactlab.plausibility.check_plausible": (
        "value nan/inf/-inf: accepted; value text/complex/list: TypeError"
    ),
    "contactlab.plausibility.implausible_rows": (
        "values number/nan: accepted; values text: ValueError"
    ),
    "contactlab.plausibility.likely_slips": (
        "value nan/inf/-inf: accepted; value text/complex/list: TypeError"
    ),
    "contactlab.signals.baseline": "y nan: refused without naming it",
    "contactlab.signals.detect_onset": "y nan: refused without naming it",
    "contactlab.signals.in_window": (
        "t empty/nan/2-D: accepted; t text: TypeError; window number: TypeError; window "
        "text/nan: ValueError"
    ),
    "contactlab.signals.noise_level": "y nan: refused without naming it",
    "contactlab.signals.running_baseline": "exclude empty/nan/2-D/text: TypeError",
    "contactlab.study.design_map.DesignMap.grid": "column number/list: KeyError",
    "contactlab.study.design_map.DesignMap.plot": (
        "tolerance nan/inf/-inf/text/complex/list/None: RuntimeWarning"
    ),
    "contactlab.study.design_map.design_map": (
        "setup number/text/list: AttributeError; resonances text: ValueError; diameters text:"
        " ValueError"
    ),
    "contactlab.study.paper.PaperGrid": (
        "resonances number/text/nan: accepted; sweep_diameters number/text/nan/None: "
        "accepted; diameters number/text/nan/None: accepted; diameter_resonances "
        "number/text/nan/None: accepted; dampings number/text/nan/None: accepted; repetitions"
        " nan/fraction/text/negative/bool/None: accepted"
    ),
    "contactlab.study.paper.paper_study": "out number: TypeError; formats number/None: TypeError",
    "contactlab.study.points.simulate_point": (
        "setup number/text/list: AttributeError; overrides number/text/list: AttributeError; "
        "factors empty: ValueError; factors nan: refused without naming it; factors 2-D: "
        "TypeError; factors text: UFuncTypeError"
    ),
    "contactlab.study.points.simulate_points": (
        "tasks number/nan: TypeError; tasks text: AttributeError; client number/list: "
        "accepted"
    ),
    "contactlab.study.setup.Scatter.factors": "seed_sequence number/text/list: TypeError",
    "contactlab.study.setup.StudySetup.at": "overrides number/text/list: AttributeError",
    "contactlab.study.setup.StudySetup.scattered": (
        "law number/text/list: AttributeError; factor nan/inf/-inf/complex: refused without "
        "naming it; factor text/list: TypeError"
    ),
    "contactlab.study.sweep.point_statistics": (
        "impacts number/text/list: AttributeError; by number: TypeError"
    ),
    "contactlab.testing.golden.GoldenStore": "log number/text/nan: accepted",
    "dem_check.campaign.api.run_campaign": (
        "channel text: accepted; out number: TypeError; metadata number/list: TypeError"
    ),
    "dem_check.campaign.records.Effects": (
        "pink nan/inf/-inf/text/complex/list/None: accepted; drift "
        "nan/inf/-inf/text/complex/list/None: accepted; hum "
        "nan/inf/-inf/text/complex/list/None: accepted; mains "
        "nan/inf/-inf/text/complex/list/None: accepted; harmonics number/text/nan/None: "
        "accepted; crosstalk nan/inf/-inf/text/complex/list/None: accepted; plate_modes "
        "number/text/nan/None: accepted; full_scale nan/inf/-inf/text/complex/list: accepted;"
        " bits nan/fraction/text/negative/bool/None: accepted; steps "
        "nan/fraction/text/negative/bool/None: accepted; step_size "
        "nan/inf/-inf/text/complex/list/None: accepted; bounce "
        "nan/inf/-inf/text/complex/list/None: accepted; bounce_delay "
        "nan/inf/-inf/text/complex/list/None: accepted"
    ),
    "dem_check.campaign.records.Effects.everything": (
        "noise nan/inf/-inf/complex: accepted; noise text/list: TypeError; peak "
        "nan/inf/-inf/complex: accepted; peak text/list: TypeError"
    ),
    "dem_check.campaign.records.realistic_record": (
        "velocities text: ValueError; onsets text: ValueError; trigger nan/inf/-inf: refused "
        "without naming it; trigger text: accepted; trigger complex/list: TypeError; "
        "sensitivity nan/inf/-inf: accepted; sensitivity text: UFuncTypeError; sensitivity "
        "complex: refused without naming it; sensitivity list: ValueError"
    ),
    "dem_check.campaign.synthetic.synthetic_record": (
        "velocities text: ValueError; onsets text: ValueError"
    ),
    "contactlab.compare.impacts.compare": "b number/text/list: refused without naming it",
    "contactlab.compare.impacts.compare_trace": "tolerances number/text/list: TypeError",
    "contactlab.traces.trace.Trace.derive": "step number/text/list: accepted",
}  # fmt: skip
"""Callables that still accept, or fail on, a value they must refuse: what was measured."""

KNOWN_HOSTILE_DEFECTS = {
    "contactlab.inverse.identify.SensorIdentification.ringing": (
        "t", [[1.0], [2.0, 3.0]], "ValueError: inhomogeneous shape"),
    "contactlab.inverse.identify.matrix_pencil": (
        "dt", 0.0, "RuntimeWarning: divide by zero encountered in divide"),
    "contactlab.oblique_result.ObliqueResult.audit": (
        "full", np.array([]), "ValueError: truth value of an empty array is ambiguous"),
    "contactlab.result.ImpactResult.audit": (
        "full", np.array([]), "ValueError: truth value of an empty array is ambiguous"),
    "contactlab.plausibility.check_plausible": (
        "value", "1e5", "TypeError: '<=' not supported between float and str"),
    "contactlab.plausibility.implausible_rows": (
        "values", [[1.0], [2.0, 3.0]], "ValueError: inhomogeneous shape"),
    "contactlab.plausibility.likely_slips": (
        "value", "1e5", "TypeError: can't multiply sequence by non-int of type 'float'"),
    "contactlab.signals.in_window": (
        "window", 0.0, "TypeError: cannot unpack non-iterable float object"),
    "contactlab.signals.lowpass": (
        "interval", 5e-324, "ValueError: filter critical frequencies must be greater than 0"),
    "contactlab.signals.running_baseline": (
        "exclude", 0.0, "TypeError: ufunc 'invert' not supported for the input types"),
    "contactlab.study.design_map.DesignMap.grid": ("column", 0.0, "KeyError: 0.0"),
    "contactlab.study.setup.Scatter.factors": (
        "seed_sequence", 0.0, "TypeError: SeedSequence expects int or sequence of ints"),
    "contactlab.study.setup.StudySetup.at": (
        "overrides", 0.0, "AttributeError: 'float' object has no attribute 'items'"),
    "contactlab.study.setup.StudySetup.column": (
        "name", 0.0, "AttributeError: 'float' object has no attribute 'startswith'"),
    "contactlab.study.setup.StudySetup.scattered": (
        "law", 0.0, "AttributeError: 'float' object has no attribute 'parameters'"),
    "contactlab.study.sweep.point_statistics": (
        "by", 0.0, "TypeError: 'float' object is not iterable"),
    "contactlab.testing.golden.compare_impacts": (
        "labels", 1.0, "TypeError: 'float' object is not iterable"),
    "dem_check.campaign.records.Effects.everything": (
        "peak", "5", "TypeError: can't multiply sequence by non-int of type 'float'"),
    "contactlab.compare.impacts.compare_trace": (
        "tolerances", [[1.0], [2.0, 3.0]], "TypeError: 'list' object is not a mapping"),
}  # fmt: skip
"""Callables whose sweep found a value answered with something else than ParameterError:
``(parameter, value, what came out)``. The test calls exactly that value (a strict
xfail) instead of the sweep, so the pin does not depend on the draws."""
