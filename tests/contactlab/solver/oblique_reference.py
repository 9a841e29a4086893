"""An independent reference for the oblique impact: scipy's ``solve_ivp`` on the same
equations, written here in Python from the laws' own methods.

The equations are those of :mod:`contactlab.solver.oblique` (normal two-mass model, the
tangential law's stick rate, the sliding force ``sigma mu N``), the integrator is
scipy's DOP853 with its own event location (terminal events, ``direction``), and the
phase at the touch is read a picosecond after it on the sticking path: none of the
compiled kernel's code is used. Shared by the tests and ``benchmarks/bench_oblique.py``.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from contactlab.solver.system import System

STICK = 0


class ObliqueReference:
    """The oblique impact of ``grain`` on ``sensor`` (see :func:`contactlab.simulate_oblique`),
    radius lever arm, solved phase by phase with ``solve_ivp``."""

    def __init__(self, grain, sensor, normal_law, tangential_law, inertia_factor=0.4):
        self.system = System(grain, sensor)
        self.m, self.radius = grain.mass, grain.radius
        self.inertia = inertia_factor * grain.mass * grain.radius**2
        self.normal = normal_law.branch("load").force
        self.law = tangential_law.for_contact(normal_law, grain.mass)

    def _normal(self, y):
        x1, v1, x2, v2 = y[:4]
        return float(self.normal(x2 - x1, v2 - v1))

    def _accelerations(self, y, n):
        sys_ = self.system
        a1 = 0.0 if sys_.rigid else (n - sys_.k1 * y[0] - sys_.c1 * y[1]) / sys_.m1
        return a1, -n / self.m

    def tangential(self, phase, y):
        """Tangential force [N] in ``phase`` at state ``y``."""
        d = y[2] - y[0]
        if phase == STICK:
            return self.law.trial_force(y[6], d, y[4] - self.radius * y[5])
        return phase * self.law.friction * max(self._normal(y), 0.0)

    def rhs(self, phase, y):
        """``y'`` in ``phase``."""
        n = self._normal(y)
        d, r = y[2] - y[0], y[3] - y[1]
        force = self.tangential(phase, y)
        slip = y[4] - self.radius * y[5]
        dh = self.law.history_rate(y[6], d, r, slip) if phase == STICK else 0.0
        a1, a2 = self._accelerations(y, n)
        return np.array(
            [y[1], a1, y[3], a2, force / self.m, -self.radius * force / self.inertia, dh]
        )

    def _slide_exit(self, phase, y):
        """``sigma dF_trial/dt - mu dN/dt`` along a sticking path: sliding goes on while >= 0."""
        n = self._normal(y)
        d, r = y[2] - y[0], y[3] - y[1]
        slip = y[4] - self.radius * y[5]
        cap = phase * self.law.friction * max(n, 0.0)
        history = self.law.history_on_cap(cap, d, slip)
        slip_rate = cap * (1.0 / self.m + self.radius**2 / self.inertia)
        a1, a2 = self._accelerations(y, n)
        rate = self.law.trial_force_rate(history, d, r, slip, slip_rate)
        step_d = 1e-6 * abs(d) if d != 0.0 else 1e-300  # central differences
        step_r = 1e-6 * max(abs(r), 1e-12)
        n_d = (self.normal(d + step_d, r) - self.normal(d - step_d, r)) / (2.0 * step_d)
        n_r = (self.normal(d, r + step_r) - self.normal(d, r - step_r)) / (2.0 * step_r)
        return phase * rate - self.law.friction * (n_d * r + n_r * (a2 - a1))

    def _events(self, phase):
        mu = self.law.friction

        def end(_t, y):
            return self._normal(y) if y[2] - y[0] > 0.0 else y[2] - y[0]

        found = [(end, -1)]
        if phase == STICK:
            found += [
                (lambda _t, y: self.tangential(STICK, y) - mu * self._normal(y), 1),
                (lambda _t, y: -self.tangential(STICK, y) - mu * self._normal(y), 1),
            ]
        else:
            found += [(lambda _t, y: self._slide_exit(phase, y), -1)]
        for fn, direction in found:
            fn.terminal, fn.direction = True, direction
        return [fn for fn, _ in found]

    def touch_phase(self, y0, probe, atol):
        """Stick, or the sign of sliding, read ``probe`` [s] after the touch on the sticking
        path (solve_ivp's DOP853 from the touch)."""
        path = solve_ivp(
            lambda _t, z: self.rhs(STICK, z), (0.0, probe), y0, "DOP853", rtol=1e-12, atol=atol
        )
        y = path.y[:, -1]
        force, cap = self.tangential(STICK, y), self.law.friction * max(self._normal(y), 0.0)
        if abs(force) <= cap:
            return STICK
        return 1 if force > 0.0 else -1

    def solve(self, velocity, angle, spin, rtol, atol):
        """End state ``[x1, v1, x2, v2, vt, w, h]`` and the phases ``[(t0, t1, code)]``."""
        y = np.array(
            [0.0, 0.0, 0.0, velocity * math.cos(angle), velocity * math.sin(angle), spin, 0.0]
        )
        phase, t, phases = self.touch_phase(y, 1e-12, atol), 0.0, []
        while len(phases) < 100:
            sol = solve_ivp(
                lambda _t, z, phase=phase: self.rhs(phase, z),
                (t, t + 1e-3),
                y,
                method="DOP853",
                rtol=rtol,
                atol=atol,
                events=self._events(phase),
                dense_output=True,
                first_step=1e-10 if t == 0.0 else None,
            )
            hits = [(ts[0], j) for j, ts in enumerate(sol.t_events) if ts.size and ts[0] > t]
            t_hit, j = min(hits)
            phases.append((t, t_hit, phase))
            t, y = t_hit, sol.sol(t_hit)
            if j == 0:
                return y, phases
            if phase == STICK:
                phase = +1 if j == 1 else -1
            else:
                cap = phase * self.law.friction * max(self._normal(y), 0.0)
                y[6] = self.law.history_on_cap(cap, y[2] - y[0], y[4] - self.radius * y[5])
                phase = STICK
        raise RuntimeError("more than 100 phases")
