"""The two-mass grain/sensor impact solver.

The model is the paper's (Keska et al. 2021, Section 2.2) with the signs of
``shared/paper/NOTES.md``: axis along the grain's travel, first touch at ``t = 0`` with
``x1 = x2 = 0``, ``v1 = 0``, ``v2 = v0 > 0``;

* overlap ``d = x2 - x1``, contact force ``S2 = law(d, d', history) >= 0``,
* sensor signal ``S1 = k1 x1 + c1 v1``,
* ``m1 v1' = S2 - S1`` and ``m2 v2' = -S2``.

An immovable wall (:meth:`Sensor.rigid`) is the same function with ``x1 = v1 = 0``.

The impact is cut into pieces at events (contact ends, a law changes branch, the plate
strikes the grain again), each solved by the best method for it:

* ``"exact"``: every piece linear time-invariant (linear laws and branches, the paper's
  prescribed trapezoid, the free sensor): modal solution or matrix exponential, events
  as roots of the exact expressions (:mod:`contactlab.solver.exact`);
* ``"adaptive"``: nonlinear contact pieces with DOP853 (order 8, error-controlled,
  :mod:`contactlab.solver.adaptive`), started in ``s = t**(1/4)`` at a touch, with event location
  on its dense output; free pieces still exact;
* ``"euler"``: the paper's explicit Euler at a fixed step (reference method; events are
  step-limited, as in the paper's program);
* ``"auto"``: exact where the law allows it, else adaptive.
"""

import dataclasses
import math
import warnings

import numpy as np

from contactlab.audit import warn_if_broken
from contactlab.bodies import Grain, Sensor
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError, ResolutionWarning, WindowWarning
from contactlab.kernels.rules import MAX_CONTACTS, contact_horizon, ringing_time, window_end
from contactlab.kernels.segments import Segment
from contactlab.laws import ContactLaw, PlasticTrapezoid
from contactlab.plausibility import check_plausible
from contactlab.result import ImpactResult
from contactlab.solver.adaptive import adaptive_contact
from contactlab.solver.compiled import core_law, solve_on_core
from contactlab.solver.euler import solve_euler
from contactlab.solver.exact import affine_states, exact_contact, free_flight
from contactlab.solver.system import System
from contactlab.validation import check_choice, check_number, keyword_checked

__all__ = ["METHODS", "simulate_impact"]

METHODS = ("auto", "exact", "adaptive", "euler")

DEFAULT_SAMPLES = 20001
"""Output samples over the window when no sample rate is given."""

SPEED_OF_LIGHT = 299_792_458.0
"""No impact is faster [m/s]: the bound that keeps a velocity's squares and products
finite (a velocity of 1e157 m/s overflowed the free-flight horizon)."""

MAX_OUTPUT_SAMPLES = 20_000_000
"""Most output samples of one impact (``duration * sample_rate + 1``): the result holds
about ten arrays of them (1.6 GB at this limit); more is refused before allocating."""


def check_output_size(duration, sample_rate):
    """Refuse a window and sample rate whose output grid would not fit in memory."""
    samples = duration * sample_rate + 1.0  # may overflow to inf: refused below too
    if samples < 2.0:
        raise ParameterError(
            f"sample_rate = {sample_rate:.4g} Hz gives fewer than 2 samples in the "
            f"{duration:.4g} s window; it must be at least {1.0 / duration:.4g} Hz"
        )
    if not samples <= MAX_OUTPUT_SAMPLES:
        raise ParameterError(
            f"duration = {duration:.4g} s at sample_rate = {sample_rate:.4g} Hz asks for "
            f"{samples:.3g} output samples (limit {MAX_OUTPUT_SAMPLES:.3g}): shorten the "
            "duration or lower the sample_rate"
        )


def _solve_pieces(system, law, velocity, window, contact_solver):
    """Alternate contact and free pieces until the window ends.

    Returns the segments, the contact intervals [(start, end), ...] and the event log.
    """
    segments, intervals, log = [], [], []
    t, y = 0.0, np.array([0.0, 0.0, 0.0, velocity])
    branch_name, max_overlap, start = law.initial_branch, 0.0, 0.0
    # the first contact is always followed to its end, even past the window
    limit = math.inf if window is None else max(window, 0.0)
    while True:
        branch = law.branch(branch_name, max_overlap)
        horizon = (limit if intervals else contact_horizon(limit)) - t
        seg, y, event = contact_solver(system, branch, t, y, horizon)
        # the branch as built: the result asks the law for it again (laws hold forces)
        segments.append(dataclasses.replace(seg, overlap=max_overlap) if max_overlap else seg)
        t = seg.t1
        if branch.loading:
            max_overlap = max(max_overlap, y[2] - y[0])
        if event is None:
            log.append((t, "window end in contact"))
            break
        if event != "end":
            log.append((t, f"branch {branch.name} -> {event}"))
            branch_name = event
            continue
        intervals.append((start, t))
        log.append((t, "separation"))
        if window is None:
            limit = auto_window(system, t)
        if len(intervals) >= MAX_CONTACTS:
            warnings.warn(
                f"stopped after {MAX_CONTACTS} contacts at t = {t:.4g} s (grain at rest on "
                "the ringing plate?)",
                WindowWarning,
                stacklevel=3,
            )
            break
        seg, y_free, entry = free_flight(system, law, max_overlap, t, y, limit - t)
        segments.append(seg)
        if entry is None:
            break
        t, y, branch_name, start = seg.t1, y_free, entry, seg.t1
        log.append((t, "contact"))
    return segments, intervals, log, limit


def auto_window(system, contact_end):
    """Window after a contact when none was given: the contact and the ringing
    (:func:`contactlab.kernels.rules.window_end`)."""
    return window_end(contact_end, ringing_time(system.m1, system.k1, system.rigid))


STEEP_RAMP = 1e-12
"""Ramps of the prescribed pulse shorter than this share of it are solved as a constant
force at their mean (the same impulse): the sensor's particular solution of a ramp
``a + b tau`` carries ``b / k1`` and ``c1 b / k1**2``, which cancel to the last digit when
the ramp lasts 1e-20 s (``b ~ 1e20 F``: the audit's residual was 8e-6, at 1e-224 s the
signal overflowed, found by the audit matrix). The shape inside so short a ramp moves the
sensor by less than 1e-24 of its deflection."""


def _solve_pulse(system, law, velocity, window):
    """The paper's prescribed trapezoid: exact first-order hold on each straight piece."""
    segments, y, log = [], np.array([0.0, 0.0, 0.0, velocity]), []
    for ta, tb, fa, fb in law.pieces(system.m2, velocity):
        slope = (fb - fa) / (tb - ta)
        if tb - ta < STEEP_RAMP * law.contact_time:  # a ramp this steep is a step
            fa, slope = 0.5 * (fa + fb), 0.0
        states = affine_states(system, fa, slope, y)
        segments.append(Segment(ta, tb, "pulse", None, states, load=(fa, slope)))
        y = states(tb - ta)[0]
    end = law.contact_time
    log.append((end, "separation"))
    limit = auto_window(system, end) if window is None else window
    seg, _, _ = free_flight(system, law, 0.0, end, y, max(limit - end, 0.0))
    segments.append(seg)
    return segments, [(0.0, end)], log, limit


def _check_inputs(grain, sensor, law, velocity, duration, sample_rate):
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if not isinstance(law, (ContactLaw, PlasticTrapezoid)):
        raise ParameterError(
            f"law must be a contact law from contactlab.laws; got {type(law).__name__}"
        )
    velocity = check_plausible(
        "impact_velocity",
        check_number("velocity", velocity, low=0.0, high=SPEED_OF_LIGHT, unit="m/s"),
        "velocity",
    )
    if 0.5 * grain.mass * velocity**2 < np.finfo(float).tiny:
        # the audit's energy ledger divides by the impact energy
        raise ParameterError(
            f"velocity = {velocity!r} m/s is too small: the impact energy 1/2 m v**2 of the "
            f"{grain.mass!r} kg grain underflows a float (below {np.finfo(float).tiny:.3g} J)"
        )
    if duration is not None:
        duration = check_number("duration", duration, low=0.0, unit="s")
    if sample_rate is not None:
        sample_rate = check_number("sample_rate", sample_rate, low=0.0, unit="Hz")
    return velocity, duration, sample_rate


@keyword_checked
def simulate_impact(
    grain,
    sensor,
    law,
    velocity,
    duration=None,
    sample_rate=None,
    method="auto",
    *,
    verify=False,
    rtol=1e-10,
    time_step=1e-10,
    threshold=0.0,
    audit=True,
):
    """Simulate a grain striking a force sensor (or an immovable wall).

    Parameters
    ----------
    grain : Grain
        The grain (mass ``m2``).
    sensor : Sensor
        The sensor (``m1, k1, c1``), or ``Sensor.rigid()`` for an immovable wall.
    law : ContactLaw or PlasticTrapezoid
        Grain-sensor contact law.
    velocity : float
        Impact speed ``v0`` [m/s], > 0; outside 0.05-50 m/s a
        :class:`~contactlab.errors.PlausibilityWarning` names the likely unit slip.
    duration : float, optional
        Output window [s] from first touch. Default: the first contact and five sensor
        periods of ringing after it (at least 1.5 contact times). The first contact is
        always solved to its end; if it outlasts the window a :class:`WindowWarning`
        says how long the window must be.
    sample_rate : float, optional
        Output sample rate [Hz]. Default: 20 001 samples over the window, or more where
        that cannot resolve the sensor period or the contact (10 samples each). A given
        rate below that gets a :class:`ResolutionWarning` with the minimum rate.
    method : {"auto", "exact", "adaptive", "euler"}
        Solver (see :mod:`contactlab.solver`). ``"exact"`` needs a piecewise-linear law.
    verify : bool, default False
        Re-solve at tighter settings (exact: the adaptive solver at ``rtol * 1e-2``;
        adaptive: ``rtol * 1e-2``; Euler: a ten times smaller step, the paper's check)
        and report relative differences in ``result.verification``.
    rtol : float, default 1e-10
        Relative tolerance of the adaptive solver.
    time_step : float, default 1e-10
        Step of the Euler method [s] (the paper's value).
    threshold : float, default 0
        Level [N] at which the sensor signal's first lobe is read
        (``result.sensor_response_time``).
    audit : bool, default True
        Check that the rebound carries no more energy than came in
        (:meth:`ImpactResult.audit` with ``full=False``) and issue an
        :class:`~contactlab.errors.AuditWarning` if it does beyond the method's tolerance
        (an Euler step too coarse for the contact creates energy).

    Returns
    -------
    ImpactResult

    Examples
    --------
    >>> import contactlab as cl
    >>> grain = cl.Grain(diameter=5e-3, density=765.0)
    >>> law = cl.laws.LinearViscoelastic(stiffness=1e5, damping=0.0)
    >>> res = cl.simulate_impact(grain, cl.Sensor.rigid(), law, velocity=2.0)
    >>> round(res.contact_time * 1e6, 2)  # pi sqrt(m/k)
    70.3
    """

    velocity, duration, sample_rate = _check_inputs(
        grain, sensor, law, velocity, duration, sample_rate
    )
    if duration is not None and sample_rate is not None:
        check_output_size(duration, sample_rate)  # before any work
    method = check_choice("method", method, METHODS)
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    time_step = check_number("time_step", time_step, low=0.0, unit="s")  # euler's only
    threshold = check_number("threshold", threshold, low=0.0, low_open=False, unit="N")
    verify, audit = check_flag("verify", verify), check_flag("audit", audit)
    if method == "auto":
        method = "exact" if law.piecewise_linear else "adaptive"
    if method == "exact" and not law.piecewise_linear:
        raise ParameterError(
            f"method='exact' needs a piecewise-linear law; {type(law).__name__} is "
            "nonlinear: use method='adaptive' (or 'auto')"
        )
    system, headline = System(grain, sensor), None
    if method == "euler":
        segments, intervals, log, window = solve_euler(system, law, velocity, duration, time_step)
    elif law.prescribed:
        segments, intervals, log, window = _solve_pulse(system, law, velocity, duration)
    else:
        branch = core_law(law, method)
        solved = None if branch is None else solve_on_core(system, branch, velocity, duration, rtol)
        if solved is not None:
            segments, intervals, log, window, headline = solved
            if threshold != 0.0:  # the loop reads the sensor lobe at zero
                del headline["sensor_lobe"], headline["_sensor_peak"]
        else:
            segments, intervals, log, window = _solve_pieces(
                system, law, velocity, duration, _contact_solver(method, rtol, velocity)
            )
        if not intervals:
            _no_contact_end(system, log[-1][0])
    _warn_window(intervals, log, window, duration)
    if sample_rate is None:  # a contact or sensor period long against the window's: more
        sample_rate = max((DEFAULT_SAMPLES - 1) / window, _resolving_rate(sensor, intervals))
    check_output_size(window, sample_rate)
    _warn_resolution(sensor, intervals, sample_rate)
    result = ImpactResult(
        grain=grain,
        sensor=sensor,
        law=law,
        velocity=velocity,
        duration=window,
        sample_rate=sample_rate,
        method=method,
        segments=segments,
        contact_intervals=intervals,
        events=log,
        threshold=threshold,
        rtol=rtol,
        time_step=time_step,
        headline=headline,
    )
    if audit:
        warn_if_broken(result.audit(full=False), f"simulate_impact's result (method={method!r})")
    if verify:
        result.verification = _verify(result, rtol, time_step)
    return result


def _contact_solver(method, rtol, velocity):
    """The Python contact piece of ``method`` ("exact" or "adaptive")."""
    if method == "exact":
        return exact_contact

    def solver(sys_, branch, t0, y0, tau_max):
        return adaptive_contact(sys_, branch, t0, y0, tau_max, rtol, velocity)

    return solver


def _no_contact_end(system, horizon):
    """The first contact never ended: not an impact; say which inputs to look at."""
    raise ParameterError(
        f"the first contact had not ended after {horizon:.4g} s, so this is not an impact: "
        f"check the units of the grain (mass {system.m2:.4g} kg), the contact law's "
        "parameters and the velocity"
    )


def _warn_window(intervals, log, window, duration):
    if duration is None:
        return
    if not intervals:  # Euler stops at the window's end
        warnings.warn(
            f"duration = {duration:.4g} s is shorter than the first contact, which had not "
            "ended at the window's end: give a longer duration",
            WindowWarning,
            stacklevel=3,
        )
    elif intervals[0][1] > duration:
        warnings.warn(
            f"duration = {duration:.4g} s is shorter than the first contact; it must be at "
            f"least {intervals[0][1]:.4g} s (the results beyond the window are still exact)",
            WindowWarning,
            stacklevel=3,
        )


def _resolving_rate(sensor, intervals):
    """Lowest sample rate [Hz] with 10 samples per sensor period and per first contact."""
    needs = []
    if not sensor.is_rigid:
        needs.append(10.0 * sensor.resonance)
    if intervals:
        needs.append(10.0 / (intervals[0][1] - intervals[0][0]))
    return max(needs, default=0.0)


def _warn_resolution(sensor, intervals, sample_rate):
    minimum = _resolving_rate(sensor, intervals)
    # a rate equal to the minimum up to round-off resolves it (ten samples each)
    if sample_rate < minimum * (1.0 - 1e-12):
        warnings.warn(
            f"sample_rate = {sample_rate:.4g} Hz cannot resolve the sensor period and the "
            f"contact (10 samples each); use at least {minimum:.4g} Hz",
            ResolutionWarning,
            stacklevel=3,
        )


_VERIFIED = ("contact_time", "peak_contact_force", "peak_sensor_force", "restitution", "impulse")


def _verify(result, rtol, time_step):
    """Re-solve at tighter settings; relative differences of the headline numbers."""
    kwargs = dict(duration=result.duration, sample_rate=result.sample_rate)
    if result.method == "euler":
        kwargs.update(method="euler", time_step=time_step / 10.0)
    else:
        kwargs.update(method="adaptive", rtol=max(rtol * 1e-2, 1e-13))
        if result.method == "exact" and result.law.prescribed:
            kwargs.update(method="exact")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", WindowWarning)
        ref = simulate_impact(
            result.grain,
            result.sensor,
            result.law,
            result.velocity,
            threshold=result.threshold,
            **kwargs,
        )
    diffs = {}
    for name in _VERIFIED:
        a, b = getattr(result, name), getattr(ref, name)
        diffs[name] = abs(a - b) / abs(b) if b else abs(a - b)
    diffs["reference_method"] = kwargs["method"]
    return diffs
