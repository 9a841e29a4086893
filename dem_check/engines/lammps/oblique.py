"""Oblique impacts of a spinning sphere on a rigid wall in LAMMPS (``simulate_oblique``'s twin).

One sphere (``units si``, z up) starts a few steps above ``fix wall/gran granular ...
zplane 0.0 NULL`` with velocity ``(vt, 0, -vn)`` and angular velocity ``(0, spin, 0)``: its
contact point (at ``-R z``) moves at ``vt - R spin`` along x, the sign convention of
:func:`contactlab.simulate_oblique`. The normal law is mapped exactly by
:func:`~contactlab.laws.lammps.granular_model` (``m* = m``, ``R* = R`` at a plane
wall); the tangential law by :func:`tangential_words`:

====================================================  ====================================
contactlab                                            LAMMPS ``tangential`` sub-model
====================================================  ====================================
``Mindlin(k, mu, history="total")``                   ``mindlin kt 0 mu``, ``kt = k/sqrt(R*)``
``Mindlin(k, mu, history="incremental")``             ``mindlin/force kt 0 mu``
``Mindlin(k, mu, history="incremental_rescaled")``    ``mindlin_rescale/force kt 0 mu``
``TangentialSpring(k, mu)``                           ``linear_history k 0 mu``
====================================================  ====================================

LAMMPS' Mindlin force is ``kt a`` times the history with ``a = sqrt(R* d)``, so ``kt a =
k sqrt(d)``. ``kt`` is always given: ``mindlin NULL`` at a wall mixes the wall as if it
were the grain's material, ``G* = G / (2 (2 - nu))``, half of a rigid flat's
``G / (2 - nu)`` (``contactlab.laws.Mindlin.from_material``'s default), and would halve the
stiffness. No tangential damping (``x_gamma_t = 0``): LAMMPS scales it with the normal
damping, contactlab's spring damping is a constant; a :class:`TangentialSpring` with
damping is refused. ``limit_damping`` keeps the contact one-sided, as in contactlab.

The step defaults to the wall contact time over :data:`STEPS_PER_CONTACT`. Velocity Verlet
(``fix nve/sphere``) converges to contactlab's rebound to first order in the step: the
stick/slip switches fall inside steps, and ``mindlin/force`` increments its history with
the stiffness at the step's start (the total form in gross sliding converges to second
order). ``docs/benchmark.md`` gives the measured errors.
"""

import math
from dataclasses import dataclass

from contactlab.errors import ParameterError
from contactlab.laws import Mindlin, TangentialSpring
from contactlab.laws.lammps import granular_model
from contactlab.validation import check_number
from dem_check.engines.audit import STEP_ENERGY, audit_oblique_rebound
from dem_check.engines.lammps.scene import granular_setup
from dem_check.engines.lammps.session import LammpsSession
from dem_check.engines.rebound import ObliqueRebound, oblique_start

__all__ = ["STEPS_PER_CONTACT", "LammpsOblique", "lammps_oblique", "tangential_words"]

STEPS_PER_CONTACT = 2000
"""Default steps per (wall) contact time: rebound within 1e-4 of the impact speed (worst
measured 8.3e-5, ``mindlin/force`` at 5 deg; first order in the step)."""

_CHUNK = 1.6
"""Contact times run before the rebound is first read (more chunks if still touching)."""

_MAX_CHUNKS = 20
"""Chunks after which the contact is declared not to end."""


_MINDLIN_KEYWORDS = {
    "total": "mindlin",
    "incremental": "mindlin/force",
    "incremental_rescaled": "mindlin_rescale/force",
}
"""Mindlin's history rule -> LAMMPS' ``tangential`` keyword."""


def tangential_words(law, effective_radius):
    """The LAMMPS ``tangential`` words of a contactlab tangential law.

    Parameters
    ----------
    law : TangentialSpring or Mindlin
        The tangential law.
    effective_radius : float
        ``R*`` of the contact [m] (the grain's radius at a plane wall).

    Returns
    -------
    str
        E.g. ``"tangential mindlin 1.5e10 0 0.3"``.

    Raises
    ------
    ParameterError
        For another law, or a spring with damping (see the module docstring).
    """
    radius = check_number("effective_radius", effective_radius, low=0.0, unit="m")
    if type(law) is Mindlin:
        if law.damping_form != "none":
            raise ParameterError(
                "tangential_law Mindlin has damping='tied' (2 gamma sqrt(m* kt)); LAMMPS' "
                "xgamma_t scales its own normal damping coefficient: only damping='none' "
                "maps here"
            )
        model = _MINDLIN_KEYWORDS[law.history]
        return f"tangential {model} {law.k_mindlin / math.sqrt(radius)!r} 0 {law.friction!r}"
    if type(law) is TangentialSpring:
        if law.damping != 0.0:
            raise ParameterError(
                f"tangential_law TangentialSpring has damping = {law.damping:.6g} N*s/m; "
                "LAMMPS' linear_history damping is x_gamma_t times the normal damping, not "
                "a constant: only damping = 0 maps exactly"
            )
        return f"tangential linear_history {law.k!r} 0 {law.friction!r}"
    raise ParameterError(
        f"tangential_law must be Mindlin or TangentialSpring; got {type(law).__name__}"
    )


@dataclass(frozen=True)
class LammpsOblique(ObliqueRebound):
    """LAMMPS' rebound of one oblique impact: an
    :class:`~dem_check.engines.rebound.ObliqueRebound` and the deck.

    Attributes
    ----------
    script : str
        The input deck LAMMPS ran.
    grain, tangential_law : Grain, TangentialLaw or None
        What was run (for :meth:`audit`).
    contact_time : float
        The normal law's wall contact time [s] the step was set from (nan if not known).
    """

    script: str
    grain: object = None
    tangential_law: object = None
    contact_time: float = math.nan

    def audit(self):
        """Energy, angular momentum and Coulomb's integrated inequality of the rebound
        (:func:`dem_check.engines.audit.audit_oblique_rebound`); the energy tolerance is
        velocity Verlet's ``10 (pi dt / t_c)**2``, and a Mindlin law's gain is the model's
        (:data:`contactlab.oblique_result.MINDLIN_ENERGY`).

        Returns
        -------
        contactlab.audit.Audit
        """
        steps_share = (math.pi * self.time_step / self.contact_time) ** 2
        return audit_oblique_rebound(
            self.grain,
            self.tangential_law,
            self.velocity,
            self.angle,
            self.spin,
            (self.rebound_normal_velocity, self.tangential_velocity, self.angular_velocity),
            energy_tolerance=STEP_ENERGY * steps_share,
        )


def _deck(grain, normal_words, tangential, vn, vt, spin, time_step, gap):
    r = grain.radius
    side = 4.0 * r  # x and y are periodic: the grain slides any distance
    top = r + gap + 4.0 * r
    setup = "the LAMMPS box"
    return [
        *granular_setup("p p f", setup),
        (f"region box block {-side!r} {side!r} {-side!r} {side!r} {-r!r} {top!r}", setup),
        ("create_box 1 box", setup),
        (f"create_atoms 1 single 0.0 0.0 {r + gap!r}", "the grain's release gap"),
        (f"set atom 1 diameter {2.0 * r!r} mass {grain.mass!r}", "the grain's diameter, mass"),
        (f"velocity all set {vt!r} 0.0 {-vn!r}", "velocity, angle"),
        (f"set atom 1 omega 0.0 {spin!r} 0.0", "spin"),
        (f"neighbor {r!r} nsq", setup),
        ("fix integrate all nve/sphere", setup),
        (
            f"fix wall all wall/gran granular {normal_words} zplane 0.0 NULL",
            f"the laws: {tangential}",
        ),
        (f"timestep {time_step!r}", "time_step"),
    ]


def lammps_oblique(grain, normal_law, tangential_law, velocity, angle, *, spin=0.0, time_step=None):
    """Run one oblique impact on a rigid wall in LAMMPS.

    Parameters
    ----------
    grain : Grain
        The grain (mass, radius).
    normal_law : ContactLaw
        One of LAMMPS' exact normal mappings (Hertz, HertzDamped, LinearViscoelastic,
        KuwabaraKono).
    tangential_law : Mindlin or TangentialSpring
        See :func:`tangential_words`.
    velocity : float
        Impact speed [m/s].
    angle : float
        Angle from the wall normal [rad], in [0, pi/2).
    spin : float, default 0
        Initial spin [rad/s], signed as in :func:`contactlab.simulate_oblique`.
    time_step : float, optional
        LAMMPS' step [s]; default the wall contact time over :data:`STEPS_PER_CONTACT`.

    Returns
    -------
    LammpsOblique

    Raises
    ------
    ParameterError
        For a law LAMMPS cannot hold exactly, or bad numbers (named).
    ImportError
        Without the ``lammps`` extra.
    """
    start = oblique_start(grain, normal_law, velocity, angle, spin, time_step, STEPS_PER_CONTACT)
    time_step, contact_time = start.time_step, start.contact_time
    model = granular_model(normal_law, grain.mass, grain.radius)
    tangential = tangential_words(tangential_law, grain.radius)
    words = model.words(tangential)
    deck = _deck(grain, words, tangential, start.vn, start.vt, start.spin, time_step, start.gap)
    chunk = math.ceil((start.gap / start.vn + _CHUNK * contact_time) / time_step)
    with LammpsSession(context="oblique impact") as session:
        for line, what in deck:
            session.command(line, what)
        steps = 0
        for _ in range(_MAX_CHUNKS):
            session.command(f"run {chunk}")
            steps += chunk
            z = float(session.lmp.numpy.extract_atom("x")[0][2])
            v = session.lmp.numpy.extract_atom("v")[0]
            if z > grain.radius and v[2] > 0.0:  # left the wall, moving away
                break
        else:
            raise RuntimeError(f"the contact lasted more than {steps} steps")
        omega = session.lmp.numpy.extract_atom("omega")[0]
        return LammpsOblique(
            velocity=start.velocity,
            angle=start.angle,
            spin=start.spin,
            radius=grain.radius,
            rebound_normal_velocity=float(v[2]),
            tangential_velocity=float(v[0]),
            angular_velocity=float(omega[1]),
            time_step=time_step,
            steps=steps,
            script=session.script,
            grain=grain,
            tangential_law=tangential_law,
            contact_time=contact_time,
        )
