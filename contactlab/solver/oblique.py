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
(the adaptive solver's stepper, started in ``s = t**(1/4)`` at the touch), ended by events
located on the step interpolant:

* the normal force falls to zero (contact end);
* sticking: the trial force reaches ``+mu N`` or ``-mu N``;
* sliding: sticking becomes admissible, i.e. ``sigma dF_trial/dt < mu dN/dt`` along a
  sticking path (the limit of LAMMPS' rule "increment the history, then cap" as the time
  step vanishes). ``dN/dt`` comes from central differences of the normal law (relative step
  1e-7: about 1e-13 relative error on smooth laws), the rest is exact. Kratos' cap of the
  elastic force alone (``coulomb_cap="elastic"``) has slides of its own
  (:mod:`contactlab.kernels.elastic_cap_rhs`).

At the touch (``N = 0``) the phase is that of LAMMPS' rule in the limit ``t -> 0+``: the
history starts from zero and the contact slides only if the trial force along a sticking
path exceeds ``mu N`` already (:func:`contactlab.kernels.oblique_kernel._touch_phase`).

The phase loop, equations, events and touch rule run compiled on the normal solver's
DOP853 kernel (:mod:`contactlab.kernels.oblique_kernel`,
:mod:`contactlab.kernels.oblique_rhs`, :mod:`contactlab.kernels.oblique_events`; issue 25),
shared with the batch (:func:`contactlab.batch.oblique_impacts`); Kratos' elastic cap has
its own phase loop on the same pieces (:mod:`contactlab.kernels.elastic_cap`).
"""

import math
import warnings

import numpy as np

from contactlab.analytic.tangential import SOLID_SPHERE_INERTIA
from contactlab.audit import warn_if_broken
from contactlab.bodies import Grain, Sensor
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError, WindowWarning
from contactlab.kernels.elastic_cap_rhs import pack as pack_elastic_cap
from contactlab.kernels.oblique_kernel import tolerances
from contactlab.kernels.oblique_rhs import pack
from contactlab.kernels.power import pack as pack_normal
from contactlab.laws import SmoothLaw, TangentialLaw
from contactlab.plausibility import check_plausible
from contactlab.solver.conventions import LEVER_ARMS
from contactlab.solver.exact import free_flight
from contactlab.solver.impact import (
    DEFAULT_SAMPLES,
    SPEED_OF_LIGHT,
    auto_window,
    check_output_size,
)
from contactlab.solver.oblique_phases import compiled_contact, grid_signals
from contactlab.solver.system import System
from contactlab.validation import check_choice, check_inertia_factor, check_number, keyword_checked

__all__ = ["ObliqueModel", "simulate_oblique"]


class ObliqueModel:
    """The oblique impact's bodies and laws, packed for the compiled phase loops.

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
        self._form = normal_law.branch("load").power
        self.radius, self.inertia = radius, inertia
        self.contact_arm = lever_arm == "contact"

    def pack(self):
        """Packed parameters of the compiled solver (:func:`kernels.oblique_rhs.pack`, with
        Kratos' cap :func:`kernels.elastic_cap_rhs.pack`; without tangential damping
        Kratos' cap is LAMMPS' rule, the elastic force being the total, and LAMMPS' loop
        takes it)."""
        sys_ = self.system
        normal = pack_normal(self._form, sys_.m1, sys_.k1, sys_.c1, sys_.m2, sys_.rigid)
        form = self.law.form()
        par = pack(normal, form, self.radius, self.inertia, self.contact_arm)
        kratos = self.law.coulomb_cap == "elastic" and form.damping > 0.0
        return pack_elastic_cap(par) if kratos else par


def _solve_contact(model, y0, rtol, scale):
    """Integrate the contact from the touch to the separation; returns (contact phases,
    y_end), compiled (:func:`contactlab.solver.oblique_phases.compiled_contact`)."""
    velocity, force_scale = scale
    force_history = model.law.history_kind == "force"
    atol = tolerances(rtol, velocity, y0[3], force_scale, force_history, model.radius)
    if not (atol > 0.0).all():  # a velocity near 1e-300 m/s: its scales underflow to 0
        raise ParameterError(
            f"velocity = {velocity!r} m/s is too small for the integrator's absolute "
            "tolerances, which scale with it (they underflow to 0)"
        )
    return compiled_contact(model, y0, rtol, atol, velocity)


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
