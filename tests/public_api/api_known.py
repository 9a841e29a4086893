"""Known defects the API property tests found and this change did not fix.

Each entry is a strict xfail (``conftest._pinned``) whose reason is what was measured:
the parameter, the values and what came out. Fixing one turns its test into a failure
until the entry is removed.
"""

import numpy as np

KNOWN_REFUSAL_DEFECTS = {
    "contactlab.analytic.materials.contact_modulus_radius": "other number: TypeError",
    "contactlab.analytic.pair.pair_rebound": (
        "masses number: TypeError; radii number: TypeError; before number/text/list: "
        "AttributeError"
    ),
    "contactlab.laws.tangential.damping_ratio": (
        "normal_law number/text/list: refused without naming it"
    ),
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
}  # fmt: skip
"""Callables that still accept, or fail on, a value they must refuse: what was measured."""

KNOWN_HOSTILE_DEFECTS = {
    "contactlab.analytic.materials.contact_modulus_radius": (
        "other", 0.0, "TypeError: 'float' object is not subscriptable"),
    "contactlab.analytic.pair.pair_rebound": (
        "before", 0.0, "AttributeError: 'float' object has no attribute 'normal1'"),
    "contactlab.analytic.plastic.linear_plastic_contact_time": (
        "stiffness", 5e-324, "ZeroDivisionError: float division by zero"),
    "contactlab.analytic.plastic.linear_plastic_restitution": (
        "stiffness", 5e-324, "ZeroDivisionError: float division by zero"),
    "contactlab.analytic.plastic.linear_plastic_yield_velocity": (
        "stiffness", 5e-324, "ZeroDivisionError: float division by zero"),
    "contactlab.analytic.sensor.half_sine_residual_amplitude": (
        "period", 5e-324, "RuntimeWarning: invalid value encountered in sin"),
    "contactlab.laws.hertz.hertz_force": (
        "overlap", 5.23892409540283e231, "RuntimeWarning: overflow encountered in multiply"),
    "contactlab.laws.hysteretic.walton_braun_force": (
        "unloading_stiffness", 0.0, "RuntimeWarning: divide by zero encountered in divide"),
    "contactlab.laws.pulse.plastic_trapezoid_force": (
        "ramp_time", np.ones((3, 3)), "ValueError: truth value of an array is ambiguous"),
    "dem_check.campaign.records.Effects.everything": (
        "peak", "5", "TypeError: can't multiply sequence by non-int of type 'float'"),
}  # fmt: skip
"""Callables whose sweep found a value answered with something else than ParameterError:
``(parameter, value, what came out)``. The test calls exactly that value (a strict
xfail) instead of the sweep, so the pin does not depend on the draws."""
