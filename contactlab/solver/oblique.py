"""Oblique impact of a spinning sphere on a flat or a force sensor: normal and tangential.

The normal side is the two-mass model of :func:`contactlab.simulate_impact` (a rigid flat,
or the sensor's moving mass on its spring and damper along the normal). The tangential
side adds three states, the grain's tangential velocity ``vt`` [m/s], its spin ``w``
[rad/s] and the tangential law's history ``h``; the flat (or sensor head) does not move
tangentially. With the contact-point slip ``s = vt - R w`` and the tangential force ``F``
on the grain (:mod:`contactlab.laws.tangential`)::

    m vt' = F,     I w' = -R F,     so  s' = F (1/m + R**2/I),

and ``F`` never feeds back into the normal motion: the normal side is exactly the normal
impact alone. With ``lever_arm="contact"`` the arm is ``R - d`` instead of ``R`` (Kratos'
convention, :mod:`contactlab.solver.conventions`): ``s = vt - (R - d) w``, ``I w' = -(R - d)
F``.

Coulomb friction makes the right-hand side switch between *sticking* (``h`` follows the
law's rate, ``F`` the trial force) and *sliding* with sign ``sigma`` (``F = sigma mu N``,
``h`` slaved to the cap). Each phase is a smooth piece integrated with DOP853
(:func:`contactlab.solver.adaptive.integrate_piece`, the adaptive solver's stepper, started in
``s = t**(1/4)`` at the touch), ended by events located on the step interpolant:

* the normal force falls to zero (contact end);
* sticking: the trial force reaches ``+mu N`` or ``-mu N``;
* sliding: sticking becomes admissible, i.e. ``sigma dF_trial/dt < mu dN/dt`` along a
  sticking path (the limit of LAMMPS' rule "increment the history, then cap" as the time
  step vanishes). ``dN/dt`` comes from central differences of the normal law (relative step
  1e-7: about 1e-13 relative error on smooth laws), the rest is exact. Kratos' cap of the
  elastic force alone (``coulomb_cap="elastic"``) has slides of its own
  (:mod:`contactlab.solver.coulomb_cap`).

At the touch (``N = 0``) the phase is that of LAMMPS' rule in the limit ``t -> 0+``: the
history starts from zero and the contact slides only if the trial force along a sticking
path exceeds ``mu N`` already (:meth:`ObliqueModel.touch_phase`).

With LAMMPS' cap (``coulomb_cap="total"``, the default) the same phase loop, equations,
events and touch rule run compiled on the normal solver's DOP853 kernel
(:mod:`contactlab.kernels.oblique_kernel`, :mod:`contactlab.kernels.oblique_rhs`,
:mod:`contactlab.kernels.oblique_events`; issue 25), shared with the batch
(:func:`contactlab.batch.oblique_impacts`); Kratos' elastic cap still runs the Python loop
of this module.
"""

import math
import warnings

import numpy as np

from contactlab.analytic.tangential import SOLID_SPHERE_INERTIA
from contactlab.audit import warn_if_broken
from contactlab.bodies import Grain, Sensor
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError, WindowWarning
from contactlab.kernels.oblique_kernel import tolerances
from contactlab.kernels.oblique_rhs import pack
from contactlab.kernels.power import pack as pack_normal
from contactlab.kernels.segments import DenseStates
from contactlab.laws import SmoothLaw, TangentialLaw
from contactlab.plausibility import check_plausible
from contactlab.solver.adaptive import integrate_piece
from contactlab.solver.conventions import LEVER_ARMS
from contactlab.solver.coulomb_cap import ELASTIC_SLIDE, FREE_SLIDE, cap_rules
from contactlab.solver.coulomb_cap import sign as _sign
from contactlab.solver.dop853 import Stepper
from contactlab.solver.exact import free_flight
from contactlab.solver.impact import (
    DEFAULT_SAMPLES,
    SPEED_OF_LIGHT,
    auto_window,
    check_output_size,
)
from contactlab.solver.oblique_phases import compiled_contact, grid_signals, piece_phases
from contactlab.solver.system import System
from contactlab.validation import check_choice, check_inertia_factor, check_number, keyword_checked

__all__ = ["ObliqueModel", "simulate_oblique"]

STICK = 0
"""Phase code of a sticking contact (sliding phases are +1 and -1, the sign of F)."""

MAX_PHASES = 1000
"""Stick/slide switches after which the solver gives up (a chattering contact)."""

_PROBE = 1e-6
"""Fraction of the first step at which the phase at a touch is read."""

_DIFF_STEP = 1e-7
"""Relative step of the central differences of the normal law."""


class ObliqueModel:
    """Right-hand sides and event functions of the oblique impact, phase by phase.

    State ``y = [x1, v1, x2, v2, vt, w, h]``: sensor displacement and velocity, grain
    normal position and velocity, grain tangential velocity [m/s], spin [rad/s], and the
    tangential law's history (m or N).

    Parameters
    ----------
    system : contactlab.solver.system.System
        Masses and sensor element (normal side).
    normal_law : SmoothLaw
        Normal contact law.
    tangential_law : TangentialLaw
        Tangential contact law.
    radius : float
        Grain radius [m] (lever arm of the tangential force).
    inertia : float
        Grain moment of inertia [kg*m**2].
    lever_arm : {"radius", "contact"}, default "radius"
        Arm of the torque and of the contact-point slip: ``R``, or ``R - d`` (the centre
        to the contact point at a wall; Kratos' ``actual_arm_vector``).
    """

    def __init__(self, system, normal_law, tangential_law, radius, inertia, lever_arm="radius"):
        self.system, self.law = system, tangential_law.for_contact(normal_law, system.m2)
        branch = normal_law.branch("load")
        self.normal, self._form = branch.force, branch.power
        self.radius, self.inertia = radius, inertia
        self.contact_arm = lever_arm == "contact"
        self.cap_rules = cap_rules(self)  # the slides of the law's Coulomb cap

    def arm(self, overlap):
        """Lever arm [m] at overlap ``d`` [m] (float or array): ``R`` or ``R - max(d, 0)``."""
        if not self.contact_arm:
            return self.radius
        if isinstance(overlap, float):
            return self.radius - max(overlap, 0.0)
        return self.radius - np.maximum(overlap, 0.0)

    def slip(self, states):
        """Contact-point slip ``vt - arm w`` [m/s] of states ``[x1, v1, x2, v2, vt, w, ...]``
        (a list of floats, or an array with the states along its last axis)."""
        if isinstance(states, list):
            return states[4] - self.arm(states[2] - states[0]) * states[5]
        return states[..., 4] - self.arm(states[..., 2] - states[..., 0]) * states[..., 5]

    # -- pieces of the right-hand side ----------------------------------------------------
    def pack(self):
        """Packed parameters of the compiled solver (:func:`kernels.oblique_rhs.pack`)."""
        sys_ = self.system
        normal = pack_normal(self._form, sys_.m1, sys_.k1, sys_.c1, sys_.m2, sys_.rigid)
        return pack(normal, self.law.form(), self.radius, self.inertia, self.contact_arm)

    def _normal_accelerations(self, x1, v1, n):
        """(a1, a2): sensor and grain normal accelerations [m/s**2] under force ``n``."""
        sys_ = self.system
        a2 = -n / sys_.m2
        if sys_.rigid:
            return 0.0, a2
        return (n - sys_.k1 * x1 - sys_.c1 * v1) / sys_.m1, a2

    def tangential_force(self, phase, y):
        """Tangential force F [N] on the grain in ``phase`` at state ``y`` (floats)."""
        x1, _, x2, _, vt, w, h = y
        d = x2 - x1
        if phase == STICK:
            return self.law.trial_force(h, d, vt - self.arm(d) * w)
        return _sign(phase) * self.law.friction * max(self.normal(d, y[3] - y[1]), 0.0)

    def rhs(self, phase):
        """``y' = f(y)`` in ``phase`` (STICK, +1 or -1)."""
        normal, law, arm, inertia = self.normal, self.law, self.arm, self.inertia
        m2, mu = self.system.m2, law.friction
        free = abs(phase) == FREE_SLIDE  # Kratos' cap: the history goes on while sliding

        def f(y):
            x1, v1, x2, v2, vt, w, h = y.tolist()
            d, r = x2 - x1, v2 - v1
            n = normal(d, r)
            lever = arm(d)
            slip = vt - lever * w
            if phase == STICK:
                force, dh = law.trial_force(h, d, slip), law.history_rate(h, d, r, slip)
            else:
                force = _sign(phase) * mu * max(n, 0.0)
                dh = law.history_rate(h, d, r, slip) if free else 0.0
            a1, a2 = self._normal_accelerations(x1, v1, n)
            return np.array([v1, a1, v2, a2, force / m2, -lever * force / inertia, dh])

        return f

    def _normal_force_rate(self, d, r, r_rate):
        """dN/dt [N/s] from central differences of the normal law in overlap and rate."""
        normal = self.normal
        hd = _DIFF_STEP * abs(d) if d != 0.0 else 1e-300
        hr = _DIFF_STEP * max(abs(r), 1e-12)
        n_d = (normal(d + hd, r) - normal(d - hd, r)) / (2.0 * hd)
        n_r = (normal(d, r + hr) - normal(d, r - hr)) / (2.0 * hr)
        return n_d * r + n_r * r_rate

    def slide_exit(self, phase, y):
        """``sigma dF_trial/dt - mu dN/dt`` [N/s]: sliding goes on while >= 0 (in an
        elastic slide, the elastic force's rate instead of the trial force's)."""
        x1, v1, x2, v2, vt, w, _ = y[:7]
        d, r = x2 - x1, v2 - v1
        n = self.normal(d, r)
        cap = _sign(phase) * self.law.friction * max(n, 0.0)
        lever = self.arm(d)
        slip = vt - lever * w
        a1, a2 = self._normal_accelerations(x1, v1, n)
        rate = self.law.friction * self._normal_force_rate(d, r, a2 - a1)
        if abs(phase) == ELASTIC_SLIDE:
            history = self.law.history_of(cap, d)
            return _sign(phase) * self.law.elastic_force_rate(history, d, r, slip) - rate
        history = self.law.history_on_cap(cap, d, slip)
        # s' = F (1/m + arm**2/I) - arm' w, and arm' = -d' for the contact arm
        slip_rate = cap * (1.0 / self.system.m2 + lever**2 / self.inertia)
        if self.contact_arm:
            slip_rate += r * w
        return _sign(phase) * self.law.trial_force_rate(history, d, r, slip, slip_rate) - rate

    def events(self, phase):
        """Event functions ``values(y) -> list`` and their crossing directions.

        Event 0 is the contact end; in sticking, events 1 and 2 are the trial force
        reaching ``+mu N`` and ``-mu N``; in sliding, the cap's
        (:mod:`contactlab.solver.coulomb_cap`; LAMMPS': event 1 is the end of sliding).
        """
        normal, mu = self.normal, self.law.friction

        if phase == STICK:

            def values(y):
                x1, v1, x2, v2 = y[:4].tolist()
                n = normal(x2 - x1, v2 - v1)
                force = self.tangential_force(STICK, y[:7].tolist())
                return [_contact_value(n, x2 - x1), force - mu * n, -force - mu * n]

            return values, [-1, +1, +1]

        return self.cap_rules.events(phase, _contact_value)

    def touch_phase(self, y0, first_step, rtol, atol):
        """Phase at a touch: the limit ``t -> 0+`` of LAMMPS' rule.

        The history starts at the touch and the force is capped only once the trial force
        exceeds ``mu N``. A trial force already above the cap at the touch itself (a
        damped spring's ``-eta s`` against a cap that starts at zero) slides. Otherwise
        the contact sticks unless the trial force along a sticking path from the touch's
        state exceeds the cap just after it: that path is followed for one short DOP853
        step (a millionth of the first step); the ratio of an elastic trial force to the
        cap is a power of time near the touch (constant for Hertz-Mindlin, growing for a
        damped normal force), so the probe's length does not matter. (Reading a damped
        spring at the probe instead chose sticking wherever the cap had outgrown
        ``eta s`` by then, and broke Coulomb before it: issue 21's matrix.)
        """
        start = list(y0)
        if self.slip(start) == 0.0:
            return STICK
        force = self.tangential_force(STICK, start)
        cap = self.law.friction * max(self.normal(start[2] - start[0], start[3] - start[1]), 0.0)
        if abs(force) > cap:
            return self.cap_rules.slide_phase(+1 if force > 0.0 else -1, start)
        probe_time = _PROBE * first_step
        stepper = Stepper(self.rhs(STICK), 0.0, y0, rtol, atol, first_step=probe_time)
        stepper.step(probe_time)
        probe = stepper.y.tolist()
        force = self.tangential_force(STICK, probe)
        cap = self.law.friction * max(self.normal(probe[2] - probe[0], probe[3] - probe[1]), 0.0)
        if abs(force) <= cap:
            return STICK
        return self.cap_rules.slide_phase(+1 if force > 0.0 else -1, probe)


def _contact_value(normal_force, overlap):
    """Contact-end event value: the normal force while the overlap is positive, a negative
    value once it is not (one-sided contact: no force at ``d <= 0``).

    The raw formulas keep their sign change at ``d = 0`` through signed powers, but
    Hunt-Crossley's ``k d**n (1 + 1.5 chi d')`` has its second factor decay towards zero
    exponentially on unloading (it never reaches it while ``d > 0``); with that factor a
    rounding below zero, both factors change sign at ``d = 0`` and the force stays
    positive, so the contact end was missed (found by the audit matrix, issue 21).
    """
    return normal_force if overlap > 0.0 else min(normal_force, 0.0) + overlap


class ContactPiece:
    """One phase of the contact: local dense states (n, 7) and the phase code."""

    def __init__(self, t0, t1, phase, states):
        self.t0, self.t1, self.phase, self.states = t0, t1, phase, states


def _solve_contact(model, y0, rtol, scale):
    """Integrate the contact from the touch to the separation; returns (contact phases,
    y_end): compiled (:func:`contactlab.solver.oblique_phases.compiled_contact`) for
    LAMMPS' Coulomb cap, in Python (:func:`contactlab.solver.adaptive.integrate_piece`)
    for Kratos' elastic cap (:mod:`contactlab.solver.coulomb_cap`), not compiled yet."""
    velocity, force_scale = scale
    force_history = model.law.history_kind == "force"
    atol = tolerances(rtol, velocity, y0[3], force_scale, force_history, model.radius)
    if not (atol > 0.0).all():  # a velocity near 1e-300 m/s: its scales underflow to 0
        raise ParameterError(
            f"velocity = {velocity!r} m/s is too small for the integrator's absolute "
            "tolerances, which scale with it (they underflow to 0)"
        )
    if model.law.coulomb_cap == "total":
        return compiled_contact(model, y0, rtol, atol, velocity)
    first = Stepper(model.rhs(STICK), 0.0, y0, rtol, atol).initial_step()
    phase = model.touch_phase(y0, first, rtol, atol)
    pieces, t, y, touch = [], 0.0, np.asarray(y0, dtype=float), True
    for _ in range(MAX_PHASES):
        values, directions = model.events(phase)
        start, steps, switch, hit = integrate_piece(
            model.rhs(phase), t, y, 1.0, rtol, atol, values, directions, touch
        )
        if hit is None:
            raise ParameterError(
                f"the contact had not ended after {t + 1.0:.4g} s, so this is not an impact: "
                f"check the units of the grain (mass {model.system.m2:.4g} kg), the laws' "
                f"parameters and the velocity ({velocity:.4g} m/s)"
            )
        states = DenseStates(t, steps, start, switch, size=7)
        pieces.append(ContactPiece(t, hit[0], _sign(phase), states))
        y = states(hit[0] - t)[0]
        t, touch = hit[0], False
        if hit[1] == 0:
            return piece_phases(model.pack(), pieces), y
        if phase == STICK:
            phase = model.cap_rules.slide_phase(+1 if hit[1] == 1 else -1, y)
        else:
            phase = model.cap_rules.after_slide(phase, hit[1], y)
    raise RuntimeError(f"more than {MAX_PHASES} stick/slip switches in one contact")


def _check_inputs(grain, sensor, normal_law, tangential_law, velocity, angle, spin):
    if not isinstance(grain, Grain):
        raise ParameterError(f"grain must be a contactlab.Grain; got {type(grain).__name__}")
    if not isinstance(sensor, Sensor):
        raise ParameterError(f"sensor must be a contactlab.Sensor; got {type(sensor).__name__}")
    if not isinstance(normal_law, SmoothLaw):
        raise ParameterError(
            "normal_law must be a normal contact law without history (LinearViscoelastic, "
            f"Hertz, HertzDamped, KuwabaraKono, HuntCrossley); got {type(normal_law).__name__}"
        )
    if not isinstance(tangential_law, TangentialLaw):
        raise ParameterError(
            "tangential_law must be a tangential law from contactlab.laws (TangentialSpring, "
            f"Mindlin); got {type(tangential_law).__name__}"
        )
    velocity = check_number("velocity", velocity, low=0.0, high=SPEED_OF_LIGHT, unit="m/s")
    check_plausible("impact_velocity", velocity, "velocity")
    angle = check_number(
        "angle", angle, low=0.0, high=math.pi / 2, low_open=False, high_open=True, unit="rad"
    )
    spin = check_number("spin", spin, unit="rad/s")
    if abs(spin) * grain.radius > SPEED_OF_LIGHT:
        raise ParameterError(
            f"spin = {spin!r} rad/s moves the grain's surface faster than light (radius "
            f"{grain.radius!r} m)"
        )
    return velocity, angle, spin


@keyword_checked
def simulate_oblique(
    grain,
    sensor,
    normal_law,
    tangential_law,
    velocity,
    angle,
    *,
    spin=0.0,
    duration=None,
    sample_rate=None,
    rtol=1e-9,
    inertia_factor=SOLID_SPHERE_INERTIA,
    lever_arm="radius",
    audit=True,
):
    """Simulate a spinning sphere striking a flat or a force sensor at an angle.

    The normal motion is :func:`contactlab.simulate_impact`'s two-mass model; the grain's
    tangential velocity, spin and the tangential law's history ride on it, phase by phase
    (stick, slide), solved compiled (:mod:`contactlab.kernels.oblique_kernel`) and read on
    the output grid in one compiled pass (:mod:`contactlab.kernels.oblique_sample`).

    Parameters
    ----------
    grain : Grain
        The grain (mass ``m``, radius ``R``).
    sensor : Sensor
        The sensor along the normal (``m1, k1, c1``), or ``Sensor.rigid()`` for a flat.
        It does not move tangentially.
    normal_law : SmoothLaw
        Normal contact law (Hertz, HertzDamped, LinearViscoelastic, KuwabaraKono,
        HuntCrossley).
    tangential_law : TangentialLaw
        Tangential law (:class:`~contactlab.laws.TangentialSpring`,
        :class:`~contactlab.laws.Mindlin`).
    velocity : float
        Impact speed [m/s], > 0.
    angle : float
        Angle of incidence from the surface normal [rad], in [0, pi/2).
    spin : float, default 0
        Initial angular velocity [rad/s] about the axis normal to the plane of incidence,
        signed so that the contact point slides at ``vt - R spin`` (a ball rolling forward
        has positive spin).
    duration : float, optional
        Output window [s]; default the contact and five sensor periods of ringing
        (at least 1.5 contact times), as :func:`contactlab.simulate_impact`.
    sample_rate : float, optional
        Output sample rate [Hz]; default 20 001 samples over the window.
    rtol : float, default 1e-9
        Relative tolerance of the DOP853 integration.
    inertia_factor : float, default 0.4
        ``I / (m R**2)`` [-] (0.4: a homogeneous solid sphere).
    lever_arm : {"radius", "contact"}, default "radius"
        Arm of the tangential force's torque and of the contact-point slip: the radius
        ``R`` (LAMMPS at a wall), or the centre-to-contact distance ``R - d`` (Kratos).
        Each DEM code's arm, history and damping rules: :data:`DEM_CONVENTIONS
        <contactlab.solver.conventions.DEM_CONVENTIONS>`.
    audit : bool, default True
        Run the cheap audit (:meth:`ObliqueResult.audit` with ``full=False``: energy and
        angular momentum from the end states, one-sided force and Coulomb on the output
        grid) and issue an :class:`~contactlab.errors.AuditWarning` if an invariant the
        model keeps fails beyond tolerance.

    Returns
    -------
    ObliqueResult

    Notes
    -----
    The solver follows the first contact; if the sensor's plate strikes the grain again
    within the window a :class:`~contactlab.errors.WindowWarning` says when.
    See :mod:`contactlab.solver.oblique` for the equations and events.
    """
    from contactlab.oblique_result import ObliqueResult, ObliqueSetup

    velocity, angle, spin = _check_inputs(
        grain, sensor, normal_law, tangential_law, velocity, angle, spin
    )
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    kappa = check_inertia_factor("inertia_factor", inertia_factor)
    lever_arm = check_choice("lever_arm", lever_arm, LEVER_ARMS)
    if duration is not None:
        duration = check_number("duration", duration, low=0.0, unit="s")
    if sample_rate is not None:
        sample_rate = check_number("sample_rate", sample_rate, low=0.0, unit="Hz")
    audit = check_flag("audit", audit)
    system = System(grain, sensor)
    radius = grain.radius
    inertia = kappa * grain.mass * radius**2
    model = ObliqueModel(system, normal_law, tangential_law, radius, inertia, lever_arm)
    vn, vt = velocity * math.cos(angle), velocity * math.sin(angle)
    y0 = np.array([0.0, 0.0, 0.0, vn, vt, spin, 0.0])
    force_scale = grain.mass * velocity / 1e-6  # momentum over 1 us [N]
    contact, y_end = _solve_contact(model, y0, rtol, (velocity, force_scale))
    t_end = contact.end
    window = auto_window(system, t_end) if duration is None else duration
    if window < t_end:
        warnings.warn(
            f"duration = {window:.4g} s is shorter than the contact; it must be at least "
            f"{t_end:.4g} s (the results beyond the window are still exact)",
            WindowWarning,
            stacklevel=2,
        )
    free, _, recontact = free_flight(
        system, normal_law, 0.0, t_end, y_end[:4], max(window - t_end, 0.0)
    )
    if recontact is not None:
        warnings.warn(
            f"the sensor strikes the grain again at t = {free.t1:.4g} s; simulate_oblique "
            "follows the first contact only (the signals after it assume free flight)",
            WindowWarning,
            stacklevel=2,
        )
    if sample_rate is None:
        sample_rate = (DEFAULT_SAMPLES - 1) / window
    check_output_size(window, sample_rate)
    setup = ObliqueSetup(
        grain, sensor, normal_law, tangential_law, velocity, angle, spin, lever_arm, rtol
    )
    result = ObliqueResult(
        setup,
        inertia=inertia,
        contact=contact,
        signals=grid_signals(contact, None if system.rigid else free, y_end, window, sample_rate),
        final_state=y_end,
        duration=window,
        sample_rate=sample_rate,
    )
    if audit:
        warn_if_broken(result.audit(full=False), "simulate_oblique's result")
    return result
