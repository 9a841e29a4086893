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
  as roots of the exact expressions (:mod:`contactlab.propagators`);
* ``"adaptive"``: nonlinear contact pieces with DOP853 (order 8, error-controlled,
  :mod:`contactlab.dop853`), started in ``s = t**(1/4)`` at a touch, with event location
  on its dense output; free pieces still exact;
* ``"euler"``: the paper's explicit Euler at a fixed step (reference method; events are
  step-limited, as in the paper's program);
* ``"auto"``: exact where the law allows it, else adaptive.
"""

import math
import warnings

import numpy as np

from contactlab.bodies import Grain, Sensor
from contactlab.dop853 import DenseSteps, Stepper, interpolate
from contactlab.errors import ParameterError, ResolutionWarning, WindowWarning
from contactlab.euler import solve_euler
from contactlab.laws import ContactLaw, PlasticTrapezoid
from contactlab.pieces import AffineForceStates, DenseStates, LinearContactStates
from contactlab.propagators import crosses, earliest_root, first_event, linear_flow
from contactlab.segment import Segment
from contactlab.validation import check_choice, check_number

__all__ = ["METHODS", "Segment", "simulate_impact"]

METHODS = ("auto", "exact", "adaptive", "euler")

DEFAULT_SAMPLES = 20001
"""Output samples over the window when no sample rate is given."""

MAX_CONTACTS = 200
"""Contact intervals after which the solver stops (a grain resting on a ringing plate)."""

_SCAN_STEPS_PER_RADIAN = 5.0
"""Event scan: about 31 points per period of the fastest mode, so no two crossings of an
event function fall between scan points."""


class _System:
    """Masses and sensor element; the linear algebra of the pieces."""

    def __init__(self, grain, sensor):
        self.m2 = grain.mass
        self.rigid = sensor.is_rigid
        self.m1, self.k1, self.c1 = sensor.mass, sensor.stiffness, sensor.damping
        if not self.rigid:
            self.sensor_flow = linear_flow([[0.0, 1.0], [-self.k1 / self.m1, -self.c1 / self.m1]])

    def contact_flow(self, k, c):
        """The :class:`~contactlab.propagators.LinearFlow` of a linear contact branch."""
        return linear_flow(self.contact_matrix(k, c))

    def contact_matrix(self, k, c):
        """System matrix under a contact force ``k d + c d' + f0`` (rigid: grain only)."""
        m1, m2 = self.m1, self.m2
        if self.rigid:
            return np.array([[0.0, 1.0], [-k / m2, -c / m2]])
        k1, c1 = self.k1, self.c1
        return np.array(
            [
                [0.0, 1.0, 0.0, 0.0],
                [-(k1 + k) / m1, -(c1 + c) / m1, k / m1, c / m1],
                [0.0, 0.0, 0.0, 1.0],
                [k / m2, c / m2, -k / m2, -c / m2],
            ]
        )

    def rhs(self, force):
        """Right-hand side ``y' = f(y)`` for a contact force function of (d, d').

        The state is unpacked to Python floats and the law's formula evaluated on them
        (the ``_*_raw`` formulas of :mod:`contactlab.laws` take floats): one call costs
        about a microsecond, against ten for the same arithmetic through numpy scalars.
        """
        m1, m2, k1, c1 = self.m1, self.m2, self.k1, self.c1
        if self.rigid:

            def f(y):
                _, _, x2, v2 = y.tolist()
                return np.array([0.0, 0.0, v2, -force(x2, v2) / m2])

        else:

            def f(y):
                x1, v1, x2, v2 = y.tolist()
                s2 = force(x2 - x1, v2 - v1)
                return np.array([v1, (s2 - k1 * x1 - c1 * v1) / m1, v2, -s2 / m2])

        return f

    def signal(self, states, contact_force):
        """Sensor signal S1 [N]: ``k1 x1 + c1 v1``, or S2 itself on an immovable wall."""
        if self.rigid:
            return np.asarray(contact_force, dtype=float)
        signal = states[:, 0] * self.k1
        signal += self.c1 * states[:, 1]
        return signal


def _overlap_rate(states):
    return states[:, 2] - states[:, 0], states[:, 3] - states[:, 1]


def _scan_step(rate, tau_max):
    """Scan step [s] for events of a piece whose fastest mode has ``|lambda| = rate``."""
    return (
        tau_max / 64.0
        if rate == 0.0
        else min(tau_max / 64.0, 1.0 / (_SCAN_STEPS_PER_RADIAN * rate))
    )


# ---------------------------------------------------------------------------
# Exactly solvable pieces
# ---------------------------------------------------------------------------
def _event_directions(branch):
    """Crossing directions of a contact piece's events: contact end (the force falls to
    zero), then the branch's exits."""
    return [-1] + [e.direction for e in branch.exits]


def _branch_events(branch, contact_force):
    """Event functions of a contact piece (vectorised over states) and their directions."""
    directions = _event_directions(branch)

    def values(states):
        d, r = _overlap_rate(states)
        cols = [contact_force(d, r)] + [e.value(d, r) for e in branch.exits]
        return np.column_stack(cols)

    return values, directions


def _exact_contact(system, branch, t0, y0, tau_max):
    """Exact contact piece on a linear branch; returns (Segment, y_end, event or None)."""
    k, c, f0 = branch.linear
    if k == 0.0 and c == 0.0:
        states = AffineForceStates(system, f0, 0.0, y0)
    else:
        states = LinearContactStates(system, k, c, f0, y0)
    force = branch.force
    values, directions = _branch_events(branch, force)
    hit = first_event(
        lambda tau: values(states(tau)), tau_max, _scan_step(states.rate, tau_max), directions
    )
    tau_end = tau_max if hit is None else hit[0]
    event = None if hit is None else ("end" if hit[1] == 0 else branch.exits[hit[1] - 1].target)
    seg = Segment(t0, t0 + tau_end, "contact", branch.name, states, _clipped(force), states.grid)
    return seg, states(tau_end)[0], event


def _clipped(force):
    """Contact force S2 [N] of a contact piece: the branch formula, never tensile.

    Zero overlap counts as contact (``d >= 0``): at the touch a damped law's force jumps
    to ``c v0``, and the piece's force is the right-hand limit there, so its largest
    value is attained, not only approached.
    """

    def contact_force(tau, states):
        d, r = _overlap_rate(states)
        return np.where(d >= 0, np.maximum(force(d, r), 0.0), 0.0)

    return contact_force


def _free(system, law, max_overlap, t0, y0, tau_max):
    """Free flight until the plate and grain touch again; returns (Segment, y_end, hit)."""
    states = AffineForceStates(system, 0.0, 0.0, y0)
    seg_force = lambda tau, s: np.zeros(len(s))  # noqa: E731
    if law.prescribed or tau_max <= 0.0:
        seg = Segment(t0, t0 + tau_max, "free", None, states, seg_force, states.grid)
        return seg, None, None
    threshold, entry = law.reentry(max_overlap)
    entry_force = law.branch(entry, max_overlap).force

    def values(tau):
        d, r = _overlap_rate(states(tau))
        # below the threshold: its distance, kept negative at the threshold itself, where
        # grain and plate touch without contact (so a receding grain is no crossing)
        below = np.minimum(d - threshold, -np.finfo(float).tiny)
        return np.where(d > threshold, entry_force(d, r), below)[:, None]

    search = min(tau_max, _recontact_horizon(system, y0, threshold))
    hit = first_event(values, search, _scan_step(states.rate, search), [+1])
    tau_end = tau_max if hit is None else hit[0]
    seg = Segment(t0, t0 + tau_end, "free", None, states, seg_force, states.grid)
    return seg, states(tau_end)[0], None if hit is None else entry


def _recontact_horizon(system, y0, threshold):
    """Latest local time [s] at which a free grain can reach the plate again.

    The free plate's displacement never exceeds ``sqrt(2 E / k1)``, ``E`` its energy at
    the start (damping only removes energy), and a receding grain (``v2 < 0``) moves
    away at constant speed: beyond the returned time the overlap cannot reach
    ``threshold`` [m]. Infinite for a grain that is not receding.
    """
    x1, v1, x2, v2 = (float(v) for v in y0)
    if v2 >= 0.0:
        return math.inf
    reach = 0.0 if system.rigid else math.sqrt(system.m1 * v1**2 / system.k1 + x1**2)
    return max((x2 + reach - threshold) / -v2, 0.0)


# ---------------------------------------------------------------------------
# Adaptive pieces
# ---------------------------------------------------------------------------
def _adaptive_contact(system, branch, t0, y0, tau_max, rtol, velocity):
    """Contact piece on any branch with DOP853; returns (Segment, y_end, event or None).

    The integrator (:class:`contactlab.dop853.Stepper`: DOP853, order 8 with error
    control) is stepped directly; after each step the event functions (force falling to
    zero, the branch's exits) are checked at the step end and a sign change is located on
    the step's 7th-order interpolant to machine precision.

    A piece that starts with a touch (zero overlap, approaching) begins in the variable
    ``s = (t - t0)**(1/4)``: Hertz-family forces go with fractional powers of the overlap
    (``d**0.25 d'`` in damped Hertz), which are not smooth in ``t`` at the touch but are
    in ``s``, so the integrator needs a few steps there instead of a dozen shrinking
    ones. It returns to ``t`` once a step in ``s`` spans less time than has elapsed
    (:func:`_warp_stops_paying`).
    """
    force = branch.force
    directions = _event_directions(branch)
    exits = [e.value for e in branch.exits]

    def event_values(y):
        x1, v1, x2, v2 = y[:4].tolist()
        d, r = x2 - x1, v2 - v1
        return [float(force(d, r))] + [value(d, r) for value in exits]

    scale = velocity * 1e-6  # displacement scale [m]: 1 us of travel at impact speed
    atol = 1e-3 * rtol * np.array([scale, velocity, scale, velocity])
    fun = system.rhs(force)
    start, switch, y, hit, first = None, 0.0, np.asarray(y0, dtype=float), None, None
    if y[2] - y[0] == 0.0 and y[3] - y[1] > 0.0:
        # first step in s: the s of the step an integrator in t would start with
        first_in_s = Stepper(fun, t0, y, rtol, atol).initial_step() ** 0.25
        z0, z_tol = np.append(y, 0.0), np.append(atol, 1.0)
        warped = Stepper(_warped(fun), 0.0, z0, rtol, z_tol, first_step=first_in_s)
        start, hit = _run(warped, tau_max**0.25, event_values, directions, _warp_stops_paying)
        switch, y = warped.t**4, warped.y[:4]
        first = switch - warped.t_old**4  # carry on with the last step's length in t
        if hit is not None:
            hit = (t0 + hit[0] ** 4, hit[1])
    steps = None
    if hit is None and switch < tau_max:
        stepper = Stepper(fun, t0 + switch, y, rtol, atol, first_step=first)
        steps, hit = _run(stepper, t0 + tau_max, event_values, directions)
    t_end = t0 + tau_max if hit is None else hit[0]
    event = None if hit is None else ("end" if hit[1] == 0 else branch.exits[hit[1] - 1].target)
    states = DenseStates(t0, steps, start, switch)
    seg = Segment(t0, t_end, "contact", branch.name, states, _clipped(force), states.grid)
    return seg, states(t_end - t0)[0], event


def _warped(fun):
    """Right-hand side in ``s``, with ``t = t0 + s**4``, for ``z = (y, s)``:
    ``dy/ds = 4 s**3 f(y)`` and ``ds/ds = 1``."""

    def g(z):
        out = np.empty(z.size)
        out[:-1] = fun(z[:-1])
        out[:-1] *= 4.0 * z[-1] ** 3
        out[-1] = 1.0
        return out

    return g


def _warp_stops_paying(s_old, s_new):
    """Whether to leave ``s = t**(1/4)`` for ``t``: once a step spans less time than has
    elapsed since the touch, steps in ``t`` (which near the touch grow in proportion to
    the elapsed time) do as well, without the warp's factor ``4 s**3``."""
    return s_old > 0.0 and s_new**4 - s_old**4 < s_old**4


def _run(stepper, end, event_values, directions, stop=None):
    """Step until ``end``, an event, or ``stop(t_old, t_new)``; returns (DenseSteps, hit).

    ``hit`` is ``(time, index)`` of the first event crossing, or None.
    """
    steps, hit, before = [], None, event_values(stepper.y)
    while stepper.t < end:
        if not stepper.step(end):
            raise RuntimeError(f"adaptive integration failed at t = {stepper.t:.6g}")
        steps.append(
            (stepper.t_old, stepper.t - stepper.t_old, stepper.y_old, stepper.interpolant())
        )
        after = event_values(stepper.y)
        hit = _first_crossing(steps[-1], before, after, directions, event_values)
        if hit is not None or (stop is not None and stop(stepper.t_old, stepper.t)):
            break
        before = after
    return DenseSteps(*zip(*steps, strict=True)), hit


def _first_crossing(step, before, after, directions, event_values):
    """Earliest event crossing inside one step ``(t_old, h, y_old, F)``: (time, index) or
    None. At the step's end the events take their end values (``after``), so an event
    that lands exactly on zero there is found there."""
    t_old, h, y_old, F = step
    events = [
        j
        for j, (a, b, d) in enumerate(zip(before, after, directions, strict=True))
        if crosses(a, b, d)
    ]
    if not events:
        return None

    def value(t, j):
        if t == t_old + h:
            return after[j]
        return event_values(interpolate(F, y_old, (t - t_old) / h))[j]

    return earliest_root(events, value, t_old, t_old + h)


# ---------------------------------------------------------------------------
# The event loop
# ---------------------------------------------------------------------------
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
        horizon = (limit if intervals else _contact_horizon(system, limit)) - t
        seg, y, event = contact_solver(system, branch, t, y, horizon)
        segments.append(seg)
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
            limit = _auto_window(system, t)
        if len(intervals) >= MAX_CONTACTS:
            warnings.warn(
                f"stopped after {MAX_CONTACTS} contacts at t = {t:.4g} s (grain at rest on "
                "the ringing plate?)",
                WindowWarning,
                stacklevel=3,
            )
            break
        seg, y_free, entry = _free(system, law, max_overlap, t, y, limit - t)
        segments.append(seg)
        if entry is None:
            break
        t, y, branch_name, start = seg.t1, y_free, entry, seg.t1
        log.append((t, "contact"))
    return segments, intervals, log, limit


def _contact_horizon(system, limit):
    """How far to follow the first contact when looking for its end [s]: a contact longer
    than a second (or 100 windows) is not an impact."""
    return 1.0 if math.isinf(limit) else max(100.0 * limit, 1.0)


def _auto_window(system, contact_end):
    """Window after the first contact when none was given: the contact and the ringing."""
    ringing = 0.0 if system.rigid else 5.0 * 2.0 * math.pi / math.sqrt(system.k1 / system.m1)
    return max(1.5 * contact_end, contact_end + ringing)


def _solve_pulse(system, law, velocity, window):
    """The paper's prescribed trapezoid: exact first-order hold on each straight piece."""
    segments, y, log = [], np.array([0.0, 0.0, 0.0, velocity]), []
    for ta, tb, fa, fb in law.pieces(system.m2, velocity):
        slope = (fb - fa) / (tb - ta)
        states = AffineForceStates(system, fa, slope, y)
        segments.append(
            Segment(ta, tb, "pulse", None, states, _pulse_force(fa, slope), states.grid)
        )
        y = states(tb - ta)[0]
    end = law.contact_time
    log.append((end, "separation"))
    limit = _auto_window(system, end) if window is None else window
    seg, _, _ = _free(system, law, 0.0, end, y, max(limit - end, 0.0))
    segments.append(seg)
    return segments, [(0.0, end)], log, limit


def _pulse_force(a, b):
    return lambda tau, states: np.maximum(a + b * np.asarray(tau), 0.0)


# ---------------------------------------------------------------------------
# Public entry point
# ---------------------------------------------------------------------------
def _check_inputs(grain, sensor, law, velocity, duration, sample_rate):
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if not isinstance(law, (ContactLaw, PlasticTrapezoid)):
        raise ParameterError(
            f"law must be a contact law from contactlab.laws; got {type(law).__name__}"
        )
    velocity = check_number("velocity", velocity, low=0.0, unit="m/s")
    if duration is not None:
        duration = check_number("duration", duration, low=0.0, unit="s")
    if sample_rate is not None:
        sample_rate = check_number("sample_rate", sample_rate, low=0.0, unit="Hz")
    return velocity, duration, sample_rate


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
        Impact speed ``v0`` [m/s], > 0.
    duration : float, optional
        Output window [s] from first touch. Default: the first contact and five sensor
        periods of ringing after it (at least 1.5 contact times). The first contact is
        always solved to its end; if it outlasts the window a :class:`WindowWarning`
        says how long the window must be.
    sample_rate : float, optional
        Output sample rate [Hz]. Default: 20 001 samples over the window. A
        :class:`ResolutionWarning` gives the minimum rate when the grid cannot resolve
        the sensor period or the contact (10 samples each).
    method : {"auto", "exact", "adaptive", "euler"}
        Solver (see :mod:`contactlab.impact`). ``"exact"`` needs a piecewise-linear law.
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
    from contactlab.result import ImpactResult

    velocity, duration, sample_rate = _check_inputs(
        grain, sensor, law, velocity, duration, sample_rate
    )
    method = check_choice("method", method, METHODS)
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    if method == "auto":
        method = "exact" if law.piecewise_linear else "adaptive"
    if method == "exact" and not law.piecewise_linear:
        raise ParameterError(
            f"method='exact' needs a piecewise-linear law; {type(law).__name__} is "
            "nonlinear: use method='adaptive' (or 'auto')"
        )
    system = _System(grain, sensor)
    if method == "euler":
        time_step = check_number("time_step", time_step, low=0.0, unit="s")
        segments, intervals, log, window = solve_euler(system, law, velocity, duration, time_step)
    elif law.prescribed:
        segments, intervals, log, window = _solve_pulse(system, law, velocity, duration)
    else:
        if method == "exact":
            solver = _exact_contact
        else:

            def solver(sys_, branch, t0, y0, tau_max):
                return _adaptive_contact(sys_, branch, t0, y0, tau_max, rtol, velocity)

        segments, intervals, log, window = _solve_pieces(system, law, velocity, duration, solver)
    _warn_window(intervals, log, window, duration)
    if sample_rate is None:
        sample_rate = (DEFAULT_SAMPLES - 1) / window
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
        system=system,
        threshold=threshold,
    )
    if verify:
        result.verification = _verify(result, rtol, time_step)
    return result


def _warn_window(intervals, log, window, duration):
    if duration is None:
        return
    if not intervals or intervals[0][1] > duration:
        needed = intervals[0][1] if intervals else math.nan
        warnings.warn(
            f"duration = {duration:.4g} s is shorter than the first contact; it must be at "
            f"least {needed:.4g} s (the results beyond the window are still exact)",
            WindowWarning,
            stacklevel=3,
        )


def _warn_resolution(sensor, intervals, sample_rate):
    needs = []
    if not sensor.is_rigid:
        needs.append(10.0 * sensor.resonance)
    if intervals:
        needs.append(10.0 / (intervals[0][1] - intervals[0][0]))
    minimum = max(needs, default=0.0)
    if sample_rate < minimum:
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
