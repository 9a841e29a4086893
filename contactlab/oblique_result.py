"""The result of one oblique impact (see :func:`contactlab.simulate_oblique`)."""

import math
from functools import cached_property
from typing import NamedTuple

import numpy as np

from contactlab.audit import (
    Audit,
    Check,
    EnergyLedger,
    elastic_energy,
    energy_check,
    worst_of,
)
from contactlab.bodies import Grain, Sensor
from contactlab.entry_checks import check_flag
from contactlab.kernels.oblique_sample import grid_worst
from contactlab.laws import SmoothLaw, TangentialLaw
from contactlab.quadrature import gauss_rule
from contactlab.quantities import column

__all__ = ["HEADLINE", "SIGNALS", "ObliqueResult", "ObliqueSetup"]

HEADLINE = (
    "velocity",
    "angle",
    "spin",
    "contact_time",
    "restitution",
    "tangential_velocity",
    "angular_velocity",
    "rebound_angle",
    "tangential_restitution",
    "peak_normal_force",
    "peak_tangential_force",
)
"""An oblique impact's headline numbers, in ``summary()`` order (:mod:`contactlab.quantities`)."""

SIGNALS = (
    "t",
    "normal_force",
    "tangential_force",
    "sensor_force",
    "x1",
    "v1",
    "x2",
    "v2",
    "tangential_velocity",
    "angular_velocity",
    "slip",
)
"""An oblique impact's signals, the columns of ``to_frame()`` (:mod:`contactlab.quantities`)."""

_SIGNAL_ATTRIBUTES = {
    "tangential_velocity": "tangential_velocity_signal",
    "angular_velocity": "angular_velocity_signal",
}
"""Signals whose attribute is not their name (the name is the number after the contact)."""

_PEAK_SAMPLES = 513
"""Points per contact phase on which the peak forces are read (besides the output grid)."""

_PHASE_NAMES = {0: "stick", 1: "slide+", -1: "slide-"}

FORCE_ROUNDING = 1e-9
"""Tolerance of the ``one_sided`` and ``coulomb`` checks [-] of the peak normal force: a
sliding force is ``mu N`` to the last bit and every switch is an event located to machine
precision, so only the rounding of the state at a root remains (measured <= 2e-16)."""

STEP_ERRORS = 1e4
"""Tolerance of the ledger's residual, the damper's work [-] of the impact energy and of
the momentum balances [-] of ``m V``, in units of ``rtol``. The integrals are Gauss-Legendre
on graded panels of the dense output (converged to 1e-9 there) against the end states;
they differ by the dense output's error, which ``rtol`` bounds per step but which a
damper's ``c d'`` amplifies: an overdamped linear contact on a 0.1 g sensor has its end
state within 1e-13 of the exact solver and its force integral 2.5e-6 of ``m V`` away at
rtol 1e-9 (5.8e-7, 4.2e-7, 6.6e-8 at rtol 1e-9, 1e-10, 1e-11 on a neighbour):
docs/verification.md."""

ENERGY_ROUNDING = 100.0
"""Tolerance of the ``energy`` and angular-momentum checks in units of ``rtol``: the end
states carry the solver's error, up to ``rtol`` per step (worst measured over the matrix:
23 rtol, an elastic Hertz contact without slip; docs/verification.md)."""

MINDLIN_ENERGY = (
    "Mindlin's stiffness kt = k_mindlin sqrt(d) changes with the overlap while the history "
    "is held: the total form's force -kt h does work kt' h**2 / 2, the incremental form "
    "unloads at another stiffness than it loaded, so both can return more energy than they "
    "stored (LAMMPS' mindlin and mindlin/force rules do the same; docs/verification.md)"
)


class ObliqueSetup(NamedTuple):
    """The checked arguments of one oblique impact, as :func:`contactlab.simulate_oblique`
    passes them to its :class:`ObliqueResult` (units there)."""

    grain: Grain
    sensor: Sensor
    normal_law: SmoothLaw
    tangential_law: TangentialLaw
    velocity: float
    angle: float
    spin: float
    lever_arm: str
    rtol: float


class ObliqueResult:
    """One oblique impact: rebound numbers from the exact events, signals on a grid.

    Data only, computed by :func:`contactlab.simulate_oblique`: the signals on the output
    grid, the end state, and the solved contact as arrays
    (:class:`~contactlab.kernels.oblique_sample.ContactPhases`: phases, steps, packed
    parameters), which the peaks and the audit sample with the compiled sampler below
    this module; no solver object and no law is called to read them.

    Signs: ``velocity`` is the impact speed and ``angle`` its angle from the normal; the
    normal axis points into the flat (``v2 > 0`` approaching), the tangential axis along
    the incoming tangential velocity; ``spin`` is signed so that the contact point slips
    at ``vt - R spin``. All rebound quantities use the same axes.

    Parameters
    ----------
    setup : ObliqueSetup
        The impact's checked arguments (its fields are attributes of the result).
    inertia : float
        Grain moment of inertia [kg*m**2].
    contact : contactlab.kernels.oblique_sample.ContactPhases
        The solved contact.
    signals : tuple
        Times, states, the normal law's unclipped formula, normal and tangential force and
        slip on the output grid (:func:`contactlab.solver.oblique_phases.grid_signals`).
    final_state : numpy.ndarray
        State (7,) at the separation.
    duration, sample_rate : float
        Output window [s] and sample rate [Hz].

    Attributes
    ----------
    t : numpy.ndarray
        Output times [s], contact starting at 0.
    normal_force, tangential_force, sensor_force : numpy.ndarray
        Normal contact force S2 (>= 0), tangential force on the grain, sensor signal S1 [N].
    x1, v1, x2, v2 : numpy.ndarray
        Sensor and grain normal displacement [m] and velocity [m/s].
    tangential_velocity_signal, angular_velocity_signal, slip : numpy.ndarray
        Grain tangential velocity [m/s], spin [rad/s], contact-point slip [m/s].
    """

    def __init__(self, setup, *, inertia, contact, signals, final_state, duration, sample_rate):
        self.grain, self.sensor, self.normal_law, self.tangential_law = setup[:4]
        self.velocity, self.angle, self.spin, self.lever_arm, self.rtol = setup[4:]
        self.duration, self.sample_rate, self.inertia = duration, sample_rate, inertia
        self._contact = contact
        self._final = np.asarray(final_state, dtype=float)
        self.t, states, self._raw, self.normal_force, self.tangential_force, self.slip = signals
        self.x1, self.v1, self.x2, self.v2 = states[:, :4].T
        self.tangential_velocity_signal, self.angular_velocity_signal = states[:, 4], states[:, 5]
        # a wall's signal is the contact force itself; the solver's states need no checks
        rigid, force = self.sensor.is_rigid, self.normal_force
        self.sensor_force = force if rigid else self.sensor.signal(states[:, :2], None)

    # -- rebound ---------------------------------------------------------------------------
    @property
    def contact_time(self):
        """Duration of the contact [s] (exact event time)."""
        return self._contact.end

    @property
    def normal_velocity(self):
        """Normal component of the impact velocity [m/s]."""
        return self.velocity * math.cos(self.angle)

    @property
    def incident_tangential_velocity(self):
        """Tangential component of the impact velocity [m/s]."""
        return self.velocity * math.sin(self.angle)

    @property
    def rebound_normal_velocity(self):
        """Grain speed away from the flat after the contact [m/s]."""
        return -float(self._final[3])

    @property
    def restitution(self):
        """Normal coefficient of restitution: rebound over impact normal speed [-]."""
        return self.rebound_normal_velocity / self.normal_velocity

    @property
    def tangential_velocity(self):
        """Tangential velocity of the grain's centre after the impact [m/s]."""
        return float(self._final[4])

    @property
    def angular_velocity(self):
        """Spin after the impact [rad/s] (signed as ``spin``)."""
        return float(self._final[5])

    @property
    def rebound_angle(self):
        """Angle of the centre's rebound velocity from the normal [rad]."""
        return math.atan2(self.tangential_velocity, self.rebound_normal_velocity)

    @property
    def contact_rebound_angle(self):
        """Angle of the contact point's rebound velocity from the normal [rad].

        ``atan(slip_after / rebound normal speed)``: the "rebound angle" of Chung & Ooi's
        test 4 (contact-patch velocity, Maw et al. 1976).
        """
        return math.atan2(self.slip_after, self.rebound_normal_velocity)

    @property
    def slip_before(self):
        """Contact-point slip at the touch ``vt - R spin`` [m/s]."""
        return self.incident_tangential_velocity - self.grain.radius * self.spin

    @property
    def slip_after(self):
        """Contact-point slip after the impact [m/s]."""
        return self.tangential_velocity - self.grain.radius * self.angular_velocity

    @property
    def tangential_restitution(self):
        """Contact-point slip after over before [-] (nan without initial slip)."""
        return self.slip_after / self.slip_before if self.slip_before != 0.0 else math.nan

    @property
    def normal_impulse(self):
        """Normal impulse on the grain, from its momentum change [N*s]."""
        return self.grain.mass * (self.normal_velocity + self.rebound_normal_velocity)

    @property
    def tangential_impulse(self):
        """Tangential impulse on the grain, from its momentum change [N*s]."""
        return self.grain.mass * (self.tangential_velocity - self.incident_tangential_velocity)

    @property
    def phases(self):
        """Contact phases ``[(start [s], end [s], "stick" | "slide+" | "slide-"), ...]``."""
        return [(t0, t1, _PHASE_NAMES[code]) for t0, t1, code in self._contact.phases()]

    @cached_property
    def _peaks(self):
        return self._contact.peaks(_PEAK_SAMPLES)

    @property
    def peak_normal_force(self):
        """Largest normal contact force [N]."""
        return max(self._peaks[0], float(self.normal_force.max()))

    @property
    def peak_tangential_force(self):
        """Largest magnitude of the tangential force [N]."""
        return max(self._peaks[1], float(np.abs(self.tangential_force).max()))

    @cached_property
    def energy_balance(self):
        """Energy before and after the contact [J].

        Keys: ``kinetic_in`` (translation and spin), ``grain_kinetic_out``,
        ``sensor_energy_out`` (the sensor's kinetic and elastic energy at the contact end),
        and ``dissipated`` (in minus out: friction, damping, the sensor's damper; >= 0 for
        a model that does not create energy).
        """
        final = self._final
        m, inertia = self.grain.mass, self.inertia
        out = {
            "kinetic_in": 0.5 * m * self.velocity**2 + 0.5 * inertia * self.spin**2,
            "grain_kinetic_out": 0.5 * m * (final[3] ** 2 + final[4] ** 2)
            + 0.5 * inertia * final[5] ** 2,
        }
        out["sensor_energy_out"] = self.sensor.energy(final[0], final[1])
        out["dissipated"] = out["kinetic_in"] - out["grain_kinetic_out"] - out["sensor_energy_out"]
        return out

    # -- audit -----------------------------------------------------------------------------
    def audit(self, full=True):
        """Energy ledger and invariants of this impact (:mod:`contactlab.audit`).

        Parameters
        ----------
        full : bool, default True
            With the ledger, the momentum balances and the checks on Gauss-Legendre nodes
            of every contact phase; False: the cheap part :func:`contactlab.simulate_oblique`
            runs by default (energy and angular momentum from the end states, one-sided
            force and Coulomb on the output grid).

        Returns
        -------
        contactlab.audit.Audit
        """
        full = check_flag("full", full)
        checks = list(self._end_checks())
        if not full:
            inside = int(np.searchsorted(self.t, self.contact_time, side="left"))
            friction, peak = self.tangential_law.friction, self.peak_normal_force
            worst = grid_worst(
                self.t, inside, self._raw, self.normal_force, self.tangential_force, friction
            )
            scale = "peak normal force"
            checks += [
                Check(name, value / peak, FORCE_ROUNDING, scale, at)
                for name, value, at in (("one_sided", *worst[:2]), ("coulomb", *worst[2:]))
            ]
            return Audit(None, tuple(checks))
        ledger, dense = self._ledger()
        return Audit(ledger, tuple(checks + dense))

    def _end_checks(self):
        """``energy`` and ``momentum_angular`` from the states before and after the contact."""
        ledger, rtol = self._end_energies(), self.rtol
        allowed = MINDLIN_ENERGY if self.tangential_law.name == "mindlin" else ""
        yield energy_check(ledger, ENERGY_ROUNDING * rtol, allowed)
        m, radius, inertia = self.grain.mass, self.grain.radius, self.inertia
        change = inertia * (self.angular_velocity - self.spin) + m * radius * (
            self.tangential_velocity - self.incident_tangential_velocity
        )
        change -= self._arm_shortening_moment()
        yield Check(
            "momentum_angular",
            abs(change) / (m * self.velocity * radius),
            ENERGY_ROUNDING * rtol,
            "m V R (angular momentum about the contact point)",
        )

    def _gauss_nodes(self):
        """Per contact phase, Gauss-Legendre nodes [s] and weights graded at both ends and
        at most a sensor period apart (:func:`contactlab.quadrature.gauss_rule`), with the
        states and forces there (:meth:`_contact`)."""
        for t0, t1, _ in self._contact.phases():
            nodes, weights = gauss_rule(t0, t1, self._panel_period, graded=True, graded_end=True)
            yield nodes, weights, *self._contact(nodes)

    def _arm_shortening_moment(self):
        """``integral d F dt`` [N*m*s] over the contact with ``lever_arm="contact"`` (the
        torque arm ``R - d`` adds it to ``I dw + m R dvt``), 0 with the radius arm:
        Gauss-Legendre phase by phase in one compiled pass
        (:func:`contactlab.kernels.oblique_sample.arm_moment`)."""
        if self.lever_arm != "contact":
            return 0.0
        return self._contact.arm_moment(self._panel_period)

    @property
    def _panel_period(self):
        """Longest quadrature panel [s]: the sensor's period (a wall's is infinite)."""
        return math.inf if self.sensor.is_rigid else self.sensor.period

    def _end_energies(self, **spent):
        """:class:`EnergyLedger` from the end states plus the integrals in ``spent`` [J]."""
        m, inertia, final = self.grain.mass, self.inertia, self._final
        sensor = self.sensor.energy(final[0], final[1])
        return EnergyLedger(
            kinetic_in=0.5 * m * self.velocity**2 + 0.5 * inertia * self.spin**2,
            translation_out=0.5 * m * (final[3] ** 2 + final[4] ** 2),
            rotation_out=0.5 * inertia * final[5] ** 2,
            sensor_left=sensor,
            **spent,
        )

    def _ledger(self):
        """The full ledger and the checks on Gauss-Legendre nodes of every phase."""
        sensor, mu = self.sensor, self.tangential_law.friction
        sums = np.zeros(5)  # N d', -T s, c1 v1**2, N, T
        raw_worst, excess_worst = [], []
        peak = self.peak_normal_force
        for nodes, weights, st, raw, normal, tangential, slip in self._gauss_nodes():
            integrands = (
                normal * (st[:, 3] - st[:, 1]),
                -tangential * slip,
                sensor.damping * st[:, 1] ** 2 if not sensor.is_rigid else np.zeros(nodes.size),
                normal,
                tangential,
            )
            sums += [weights @ f for f in integrands]
            raw_worst.append(worst_of(-raw / peak, nodes))
            excess = np.abs(tangential) - mu * normal
            excess_worst.append(worst_of(excess / peak, nodes))
        final = self._final
        left = elastic_energy(self.normal_law, final[2] - final[0])
        ledger = self._end_energies(
            sensor_damper=sums[2],
            normal_damper=sums[0] - left,
            normal_elastic_left=left,
            friction=sums[1],
        )
        m, speed, tolerance = self.grain.mass, self.velocity, STEP_ERRORS * self.rtol
        energy_in, momentum = ledger.kinetic_in, m * speed
        scale_force, scale_momentum = "peak normal force", "impact momentum m V"
        checks = [
            _check("one_sided", max(raw_worst), FORCE_ROUNDING, scale_force),
            _check("coulomb", max(excess_worst), FORCE_ROUNDING, scale_force),
            Check("damper", -ledger.normal_damper / energy_in, tolerance, "impact energy"),
            Check(
                "momentum_normal",
                abs(sums[3] - self.normal_impulse) / momentum,
                tolerance,
                scale_momentum,
            ),
            Check(
                "momentum_tangential",
                abs(sums[4] - self.tangential_impulse) / momentum,
                tolerance,
                scale_momentum,
            ),
            Check("residual", abs(ledger.residual) / energy_in, tolerance, "impact energy"),
        ]
        return ledger, checks

    # -- output ----------------------------------------------------------------------------
    def summary(self):
        """Headline numbers as a dict with unit-bearing keys (JSON-ready)."""
        return {
            "normal_law": type(self.normal_law).__name__,
            "normal_law_parameters": self.normal_law.parameters(),
            "tangential_law": type(self.tangential_law).__name__,
            "tangential_law_parameters": self.tangential_law.parameters(),
            "grain": self.grain.to_dict(),
            "sensor": self.sensor.to_dict(),
            **{column(name): getattr(self, name) for name in HEADLINE},
            "phases": [list(p) for p in self.phases],
            "energy_balance [J]": self.energy_balance,
        }

    def to_pandas(self):
        """Signals as a pandas DataFrame with unit-bearing column names."""
        import pandas as pd

        return pd.DataFrame(
            {column(name): getattr(self, _SIGNAL_ATTRIBUTES.get(name, name)) for name in SIGNALS}
        )

    to_frame = to_pandas

    def plot(self, ax=None, **kwargs):
        """Normal and tangential contact forces and the sensor signal against time.

        Returns
        -------
        (matplotlib.figure.Figure, matplotlib.axes.Axes)
        """
        from contactlab.plotting import plot_oblique

        return plot_oblique(self, ax=ax, **kwargs)

    def __repr__(self):
        return (
            f"ObliqueResult({type(self.normal_law).__name__}+{type(self.tangential_law).__name__}"
            f", angle={math.degrees(self.angle):.4g} deg, contact_time="
            f"{self.contact_time * 1e6:.4g} us, restitution={self.restitution:.4g}, "
            f"tangential_velocity={self.tangential_velocity:.4g} m/s, "
            f"angular_velocity={self.angular_velocity:.4g} rad/s)"
        )


def _check(name, worst_at, tolerance, scale):
    """A :class:`Check` from a ``(worst, time)`` pair."""
    return Check(name, worst_at[0], tolerance, scale, worst_at[1])
