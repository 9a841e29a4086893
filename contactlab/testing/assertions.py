"""Assertions for contact-law regression tests.

Each raises :class:`AssertionError` with what was expected, what came out, the tolerance
and, for closed forms, the formula and its published source, so a failing test explains
itself. Impacts are on an immovable wall (:meth:`contactlab.Sensor.rigid`), where the
closed forms hold, with the contact ending when the force returns to zero.
"""

import numpy as np

from contactlab.bodies import Sensor
from contactlab.errors import ParameterError
from contactlab.laws import ContactLaw
from contactlab.quantities import QUANTITIES
from contactlab.solver import simulate_impact
from contactlab.testing.closed_forms import ClosedForm, closed_forms_for
from contactlab.testing.golden import compare_impacts
from contactlab.validation import check_count, check_number

__all__ = [
    "CLOSED_FORM_RTOL",
    "assert_contact_time",
    "assert_matches_closed_form",
    "assert_passive",
    "assert_restitution",
    "assert_trace_matches",
]

CLOSED_FORM_RTOL = 1e-6
"""Default relative tolerance against a closed form that is exact for the law: the solver's
events are roots of exact expressions (exact method) or located on DOP853's dense output
at rtol 1e-10 (adaptive), far inside 1e-6."""

PASSIVE_RTOL = 1e-12
"""Default tolerance of :func:`assert_passive`, as a fraction of ``F(d_max) d_max``: the
trapezoidal loading and unloading integrals of an elastic law cancel to roundoff."""


def _tolerances(rtol, atol, unit):
    rtol = check_number("rtol", rtol, low=0.0, low_open=False)
    return rtol, check_number("atol", atol, low=0.0, low_open=False, unit=unit)


def _mismatch(result, form, rtol, atol):
    """Failure text for one closed form, or None when the result is within tolerance."""
    got = float(getattr(result, form.quantity))
    tolerance = atol + form.atol + rtol * abs(form.value)
    difference = abs(got - form.value)
    if difference <= tolerance:
        return None
    allowance = (
        f" + closed-form allowance {form.atol:.3g} ({form.atol_reason})" if form.atol else ""
    )
    lines = [
        f"{form.quantity} [{QUANTITIES[form.quantity].unit}]: expected {form.value:.10g}, "
        f"got {got:.10g}; |got - expected| = {difference:.3g} > tolerance {tolerance:.3g} "
        f"= rtol {rtol:g} * |expected| + atol {atol:g}{allowance}",
    ]
    if form.reference:
        lines += [f"    closed form: {form.formula}", f"    reference:   {form.reference}"]
    else:
        lines.append(f"    expected from: {form.formula}")
    return "\n".join(lines)


def _check(result, forms, rtol, atol=0.0):
    failures = [text for form in forms if (text := _mismatch(result, form, rtol, atol))]
    if failures:
        context = (
            f"{result.law!r} on an immovable wall, grain of {result.grain.mass:.6g} kg at "
            f"{result.velocity:.6g} m/s (contact ends when the force returns to zero):"
        )
        raise AssertionError("\n".join([context, *failures]))
    return result


def _wall_impact(law, grain, velocity):
    return simulate_impact(grain, Sensor.rigid(), law, velocity=velocity)


def _assert_quantity(quantity, law, grain, velocity, expected, rtol, atol, source):
    unit = QUANTITIES[quantity].unit
    rtol, atol = _tolerances(rtol, atol, unit)
    form = ClosedForm(quantity, check_number("expected", expected, unit=unit), source, "")
    return _check(_wall_impact(law, grain, velocity), (form,), rtol, atol)


def assert_restitution(
    law, grain, velocity, expected, rtol=CLOSED_FORM_RTOL, atol=0.0, source="value given"
):
    """Assert the restitution of an impact on an immovable wall.

    Parameters
    ----------
    law : ContactLaw or PlasticTrapezoid
        The contact law.
    grain : contactlab.Grain
        The grain (its mass is the effective mass on a wall).
    velocity : float
        Impact speed [m/s].
    expected : float
        Expected restitution [-].
    rtol : float, default :data:`CLOSED_FORM_RTOL`
        Relative tolerance [-].
    atol : float, default 0
        Absolute tolerance [-] (needed for an expected value of 0).
    source : str, default "value given"
        Where ``expected`` comes from (a formula and its reference), shown on failure.

    Returns
    -------
    ImpactResult
        The simulated impact, for further checks.

    Raises
    ------
    AssertionError
        If ``|e - expected| > atol + rtol |expected|``.
    """
    return _assert_quantity("restitution", law, grain, velocity, expected, rtol, atol, source)


def assert_contact_time(
    law, grain, velocity, expected, rtol=CLOSED_FORM_RTOL, atol=0.0, source="value given"
):
    """Assert the contact time of an impact on an immovable wall.

    Parameters
    ----------
    law, grain, velocity, rtol, source
        As for :func:`assert_restitution`.
    expected : float
        Expected contact time [s].
    atol : float, default 0
        Absolute tolerance [s].

    Returns
    -------
    ImpactResult
        The impact whose contact time was checked.

    Raises
    ------
    AssertionError
        If ``|t_c - expected| > atol + rtol |expected|``.
    """
    return _assert_quantity("contact_time", law, grain, velocity, expected, rtol, atol, source)


def assert_matches_closed_form(law, grain, velocity, rtol=CLOSED_FORM_RTOL):
    """Assert every closed form known for the law's class (contact time, restitution, peak).

    The closed forms come from :data:`contactlab.testing.CLOSED_FORMS`; each may add its
    own absolute allowance (a truncated series' remainder), stated in its
    ``atol_reason``. All failing quantities are reported together.

    Parameters
    ----------
    law, grain, velocity
        As for :func:`assert_restitution`.
    rtol : float, default :data:`CLOSED_FORM_RTOL`
        Relative tolerance [-] on every quantity.

    Returns
    -------
    ImpactResult
        The impact the closed forms were compared with.

    Raises
    ------
    AssertionError
        If a quantity is outside its tolerance.
    NoClosedFormError
        If no closed form is registered for the law's class (the message lists the laws
        that have one).
    """
    rtol, _ = _tolerances(rtol, 0.0, "")
    result = _wall_impact(law, grain, velocity)
    return _check(result, closed_forms_for(law, grain.mass, velocity), rtol)


def assert_passive(law, max_overlap, rate=0.0, samples=1001, rtol=PASSIVE_RTOL):
    """Assert that a law creates no energy over a loading-unloading cycle.

    The overlap ramps linearly from 0 to ``max_overlap`` at the rate ``+rate`` and back
    to 0 at ``-rate``; the work ``W = integral F dd`` along this closed path (trapezoidal
    rule, :meth:`ContactLaw.work`) is the energy the contact absorbed. A passive contact
    stores and dissipates energy but never creates it: ``W >= -rtol F(d_max) d_max``.

    Parameters
    ----------
    law : ContactLaw
        The contact law (a force of overlap, not a prescribed pulse).
    max_overlap : float
        Largest overlap of the cycle [m].
    rate : float, default 0
        Overlap speed during the cycle [m/s], >= 0 (0: quasi-static).
    samples : int, default 1001
        Samples on each of the two ramps.
    rtol : float, default :data:`PASSIVE_RTOL`
        Tolerance as a fraction of ``F(d_max) d_max`` [-].

    Returns
    -------
    float
        The work absorbed over the cycle [J].

    Raises
    ------
    AssertionError
        If the cycle creates more energy than the tolerance.
    """
    if not isinstance(law, ContactLaw):
        raise ParameterError(
            "assert_passive needs a contact law that is a force of overlap (ContactLaw); "
            f"got {type(law).__name__}"
        )
    d_max = check_number("max_overlap", max_overlap, low=0.0, unit="m")
    rate = check_number("rate", rate, low=0.0, low_open=False, unit="m/s")
    rtol = check_number("rtol", rtol, low=0.0, low_open=False)
    samples = check_count("samples", samples, low=2)
    ramp = np.linspace(0.0, d_max, samples)
    overlap = np.concatenate([ramp, ramp[::-1]])
    rates = np.concatenate([np.full(samples, rate), np.full(samples, -rate)])
    work = law.work(overlap, rates)
    scale = float(law.force(d_max)) * d_max
    if not work >= -rtol * scale:
        raise AssertionError(
            f"{law!r} creates energy over a loading-unloading cycle to {d_max:.6g} m at "
            f"{rate:.6g} m/s: work absorbed {work:.6g} J < -tolerance {rtol * scale:.3g} J "
            f"(rtol {rtol:g} * F(d_max) d_max = {scale:.6g} J). A passive contact stores and "
            "dissipates energy but never creates it: check the sign of the damping term "
            "and that unloading stays below loading."
        )
    return work


def assert_trace_matches(actual, reference, tolerances=None, align=None):
    """Assert that an impact matches a reference: headline quantities and waveforms.

    The comparison is :func:`contactlab.compare.compare`'s (contact time, peak contact
    and sensor forces, sensor response time, restitution, and the RMS and largest
    differences of the sensor signals over the reference's peak), at regression
    tolerances (:data:`contactlab.testing.golden_trace.REGRESSION_RTOL`, 1e-6) unless told
    otherwise. A quantity one side lacks (a measured trace has no contact force) is
    reported as not available, not as failed.

    Parameters
    ----------
    actual, reference : ImpactResult, GoldenTrace or dem_check Trace
        The impact under test and its reference (a golden trace, another simulation, or
        a measured trace in newtons).
    tolerances : dict, optional
        Quantity name -> tolerance, replacing 1e-6 for that quantity (names and how each
        error is measured: :data:`contactlab.compare.QUANTITIES`).
    align : {None, "onset", "xcorr"}, default None
        Time alignment of the sensor signals (None keeps the time axes: right for a rerun;
        use ``"onset"`` for a measured trace).

    Returns
    -------
    contactlab.compare.Comparison
        The comparison, when everything available is within tolerance.

    Raises
    ------
    AssertionError
        With the whole table, if a quantity is outside its tolerance.
    """
    comparison = compare_impacts(actual, reference, tolerances, align)
    if not comparison.passed:
        raise AssertionError(
            f"impact differs from its reference in {', '.join(comparison.failed)}:\n{comparison}"
        )
    return comparison
