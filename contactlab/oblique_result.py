"""The result of one oblique impact (see :func:`contactlab.simulate_oblique`)."""

import math
from functools import cached_property

import numpy as np

__all__ = ["ObliqueResult"]

_PEAK_SAMPLES = 513
"""Points per contact phase on which the peak forces are read (besides the output grid)."""

_PHASE_NAMES = {0: "stick", 1: "slide+", -1: "slide-"}


class ObliqueResult:
    """One oblique impact: rebound numbers from the exact events, signals on a grid.

    Signs: ``velocity`` is the impact speed and ``angle`` its angle from the normal; the
    normal axis points into the flat (``v2 > 0`` approaching), the tangential axis along
    the incoming tangential velocity; ``spin`` is signed so that the contact point slips
    at ``vt - R spin``. All rebound quantities use the same axes.

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

    def __init__(
        self,
        *,
        grain,
        sensor,
        normal_law,
        tangential_law,
        velocity,
        angle,
        spin,
        model,
        pieces,
        free,
        final_state,
        duration,
        sample_rate,
    ):
        self.grain, self.sensor = grain, sensor
        self.normal_law, self.tangential_law = normal_law, tangential_law
        self.velocity, self.angle, self.spin = velocity, angle, spin
        self.duration, self.sample_rate = duration, sample_rate
        self._model, self._pieces, self._free = model, pieces, free
        self._final = np.asarray(final_state, dtype=float)
        n = math.floor(duration * sample_rate * (1 + 1e-12)) + 1
        self.t = np.arange(n, dtype=float) / sample_rate
        states, self.normal_force, self.tangential_force = self._evaluate(self.t)
        self.x1, self.v1, self.x2, self.v2 = states[:, :4].T
        self.tangential_velocity_signal, self.angular_velocity_signal = states[:, 4], states[:, 5]
        self.slip = states[:, 4] - grain.radius * states[:, 5]
        self.sensor_force = model.system.signal(states[:, :4], self.normal_force)

    # -- dense evaluation ------------------------------------------------------------------
    def _evaluate(self, times):
        """States (n, 7), normal and tangential force (n,) at times [s] (any order)."""
        model = self._model
        times = np.asarray(times, dtype=float)
        states = np.empty((times.size, 7))
        normal, tangential = np.zeros(times.size), np.zeros(times.size)
        after = times >= self.contact_time
        for piece in self._pieces:
            inside = (times >= piece.t0) & (times < piece.t1)
            if not inside.any():
                continue
            st = piece.states(times[inside] - piece.t0)
            states[inside] = st
            d, r = st[:, 2] - st[:, 0], st[:, 3] - st[:, 1]
            n = np.maximum(model.normal(d, r), 0.0)
            normal[inside] = n
            if piece.phase == 0:
                slip = st[:, 4] - model.radius * st[:, 5]
                tangential[inside] = model.law.trial_force(st[:, 6], d, slip)
            else:
                tangential[inside] = piece.phase * model.law.friction * n
        if after.any():
            states[after, :4] = self._free.states(times[after] - self._free.t0)
            states[after, 4:] = [self._final[4], self._final[5], 0.0]
        return states, normal, tangential

    # -- rebound ---------------------------------------------------------------------------
    @property
    def contact_time(self):
        """Duration of the contact [s] (exact event time)."""
        return self._pieces[-1].t1

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
        return [(p.t0, p.t1, _PHASE_NAMES[p.phase]) for p in self._pieces]

    @cached_property
    def _peaks(self):
        times = np.concatenate(
            [np.linspace(p.t0, p.t1, _PEAK_SAMPLES, endpoint=False) for p in self._pieces]
        )
        _, normal, tangential = self._evaluate(times)
        return float(normal.max()), float(np.abs(tangential).max())

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
        model, final = self._model, self._final
        m, inertia = self.grain.mass, model.inertia
        out = {
            "kinetic_in": 0.5 * m * self.velocity**2 + 0.5 * inertia * self.spin**2,
            "grain_kinetic_out": 0.5 * m * (final[3] ** 2 + final[4] ** 2)
            + 0.5 * inertia * final[5] ** 2,
        }
        sys_ = model.system
        out["sensor_energy_out"] = (
            0.0 if sys_.rigid else 0.5 * sys_.m1 * final[1] ** 2 + 0.5 * sys_.k1 * final[0] ** 2
        )
        out["dissipated"] = out["kinetic_in"] - out["grain_kinetic_out"] - out["sensor_energy_out"]
        return out

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
            "velocity [m/s]": self.velocity,
            "angle [rad]": self.angle,
            "spin [rad/s]": self.spin,
            "contact_time [s]": self.contact_time,
            "restitution [-]": self.restitution,
            "tangential_velocity [m/s]": self.tangential_velocity,
            "angular_velocity [rad/s]": self.angular_velocity,
            "rebound_angle [rad]": self.rebound_angle,
            "tangential_restitution [-]": self.tangential_restitution,
            "peak_normal_force [N]": self.peak_normal_force,
            "peak_tangential_force [N]": self.peak_tangential_force,
            "phases": [list(p) for p in self.phases],
            "energy_balance [J]": self.energy_balance,
        }

    def to_pandas(self):
        """Signals as a pandas DataFrame with unit-bearing column names."""
        import pandas as pd

        return pd.DataFrame(
            {
                "t [s]": self.t,
                "normal_force [N]": self.normal_force,
                "tangential_force [N]": self.tangential_force,
                "sensor_force [N]": self.sensor_force,
                "x1 [m]": self.x1,
                "v1 [m/s]": self.v1,
                "x2 [m]": self.x2,
                "v2 [m/s]": self.v2,
                "tangential_velocity [m/s]": self.tangential_velocity_signal,
                "angular_velocity [rad/s]": self.angular_velocity_signal,
                "slip [m/s]": self.slip,
            }
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
