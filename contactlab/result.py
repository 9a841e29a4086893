"""The result of one impact: signals on a uniform grid, exact events, and pulse metrics."""

import bisect
import math
from functools import cached_property

import numpy as np

from contactlab import metrics
from contactlab.entry_checks import check_flag
from contactlab.kernels.segments import segment_force
from contactlab.quadrature import gauss_rule
from contactlab.quantities import column
from contactlab.roots import ROOT_RTOL, locate_root

__all__ = ["HEADLINE", "SIGNALS", "SOLVER_READINGS", "ImpactResult", "ImpactSignals"]

HEADLINE = (
    "velocity",
    "contact_time",
    "peak_contact_force",
    "sensor_response_time",
    "peak_sensor_force",
    "impulse",
    "restitution",
    "rebound_velocity",
)
"""A normal impact's headline numbers, in ``summary()`` order (:mod:`contactlab.quantities`)."""

SIGNALS = ("t", "contact_force", "sensor_force", "x1", "v1", "x2", "v2")
"""A normal impact's signals, the columns of ``to_frame()`` (:mod:`contactlab.quantities`)."""

_ZOOMS = 5
"""Zoom levels of the peak search (:meth:`ImpactResult._refined_max`)."""


def _crossing(signal, level, lo, hi):
    """Where ``signal`` [N] crosses ``level`` [N] on [lo, hi] [s], to machine precision.

    A strict sign change of ``signal - level`` is a root of a continuous function
    (:func:`scipy.optimize.brentq`). Otherwise one end sits exactly on the level, as a
    clipped contact force does after separation (zero, and staying zero), and there is
    no sign change to find, only the boundary of ``signal > level``: bisection.
    """
    above_lo, above_hi = signal(lo) - level, signal(hi) - level
    if above_lo * above_hi < 0.0:
        return locate_root(lambda s: signal(s) - level, lo, hi)
    inside = above_lo > 0.0
    if (above_hi > 0.0) == inside:
        return 0.5 * (lo + hi)
    while hi - lo > ROOT_RTOL * max(abs(hi), 1e-300):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if (signal(mid) > level) == inside:
            lo = mid
        else:
            hi = mid
    return hi if inside else lo


class ImpactSignals:
    """What every impact result shares: its table, its plot, and the numbers that follow
    from its events.

    A subclass provides the arrays ``t`` [s], ``contact_force`` and ``sensor_force`` [N],
    ``x1``, ``x2`` [m] and ``v1``, ``v2`` [m/s], ``contact_intervals`` [(start, end) s],
    ``velocity`` and ``rebound_velocity`` [m/s], and ``_contact_peak`` (time [s], force
    [N]): :class:`ImpactResult` (exact solution) and
    :class:`dem_check.engines.EngineResult` (rigid-body engine) both do.
    """

    def _headline(self):
        """The set-up and headline numbers with unit-bearing keys (for ``summary()``)."""
        return {
            "method": self.method,
            "law": type(self.law).__name__,
            "law_parameters": self.law.parameters(),
            "grain": self.grain.to_dict(),
            "sensor": self.sensor.to_dict(),
            **{column(name): getattr(self, name) for name in HEADLINE},
            "contact_intervals [s]": [list(iv) for iv in self.contact_intervals],
        }

    @property
    def contact_time(self):
        """Duration of the first contact [s]."""
        start, end = self.contact_intervals[0]
        return end - start

    @property
    def contacts(self):
        """Number of contacts in the window [-] (a bounce back onto the sensor adds one)."""
        return len(self.contact_intervals)

    @property
    def separation_time(self):
        """Time of the first separation [s]."""
        return self.contact_intervals[0][1]

    @property
    def restitution(self):
        """Rebound speed over impact speed [-]."""
        return self.rebound_velocity / self.velocity

    @property
    def peak_contact_force(self):
        """Largest contact force S2 during the first contact [N]."""
        return self._contact_peak[1]

    @property
    def peak_contact_time(self):
        """Time of the largest contact force [s]."""
        return self._contact_peak[0]

    def to_frame(self):
        """Signals as a pandas DataFrame with unit-bearing column names."""
        import pandas as pd

        return pd.DataFrame({column(name): getattr(self, name) for name in SIGNALS})

    def plot(self, ax=None, **kwargs):
        """Contact force (thick) and sensor signal (thin), as in the paper's Figures 5-9.

        Returns
        -------
        (matplotlib.figure.Figure, matplotlib.axes.Axes)
        """
        from contactlab.plotting import plot_impact

        return plot_impact(self, ax=ax, **kwargs)


SOLVER_READINGS = ("_contact_peak", "sensor_lobe", "_sensor_peak", "impulse", "rebound_velocity")
"""Headline numbers a solver may hand to :class:`ImpactResult` already read (the compiled
impact loop reads them exactly as it solves, :mod:`contactlab.kernels.impact_loop`):
``(time [s], force [N])`` of the contact-force peak, the sensor lobe's ``(start, end)``
[s], ``(time [s], signal [N])`` of its peak, the impulse [N*s] and the rebound speed
[m/s]. Those not given are read from the dense solution below."""


class ImpactResult(ImpactSignals):
    """One simulated impact (see :func:`contactlab.simulate_impact`).

    Signals on the output grid (numpy arrays): ``t`` [s], ``contact_force`` (S2) [N],
    ``sensor_force`` (S1) [N], ``x1``, ``x2`` [m], ``v1``, ``v2`` [m/s].

    Headline numbers are computed from the exact (or dense) solution, not from the grid:
    ``contact_time`` [s], ``peak_contact_force`` [N], ``sensor_response_time`` [s],
    ``peak_sensor_force`` [N], ``impulse`` [N*s], ``restitution`` [-],
    ``rebound_velocity`` [m/s], ``contact_intervals`` [(start, end) s] and
    ``energy_balance`` [J]. The solver may hand some of them over already read
    (``headline``, keys of :data:`SOLVER_READINGS`).

    The dense solution is data: ``segments``, the solved pieces
    (:class:`contactlab.kernels.segments.Segment`: modal rates and weights, affine loads,
    DOP853 interpolants or Euler samples), evaluated by :mod:`contactlab.kernels.segments`;
    a contact piece's force is the law's branch formula (``law.branch(seg.branch,
    seg.overlap)``), clipped. Nothing of the solver is kept or called.
    """

    def __init__(
        self,
        *,
        grain,
        sensor,
        law,
        velocity,
        duration,
        sample_rate,
        method,
        segments,
        contact_intervals,
        events,
        threshold=0.0,
        rtol=None,
        time_step=None,
        headline=None,
    ):
        self.grain, self.sensor, self.law = grain, sensor, law
        self.velocity, self.duration, self.sample_rate = velocity, duration, sample_rate
        self.method, self.threshold, self.rtol = method, threshold, rtol
        self.time_step = time_step if method == "euler" else None
        self.segments = segments
        # the contact pieces' force formulas, the law's (the branch each piece followed)
        self._formulas = [
            law.branch(seg.branch, seg.overlap).force if seg.kind == "contact" else None
            for seg in segments
        ]
        self.contact_intervals = list(contact_intervals)
        self.events = list(events)
        self.verification = None
        self._starts = np.array([s.t0 for s in segments])
        n = math.floor(duration * sample_rate * (1 + 1e-12)) + 1
        self.t = np.arange(n, dtype=float)
        self.t /= sample_rate
        states, self.contact_force = self._evaluate_grid()
        self.x1, self.v1, self.x2, self.v2 = states.T
        self.sensor_force = sensor.signal(states, self.contact_force)
        # numbers the solver read while solving (see SOLVER_READINGS); the rest are read below
        self.__dict__.update(headline or {})

    def grid_reading(self):
        """The same solution with every headline number read from the output grid and the
        dense solution, none handed over by the solver (as for a law the compiled loop
        does not take): an independent reading, for checks.

        Returns
        -------
        ImpactResult
        """
        return ImpactResult(
            grain=self.grain,
            sensor=self.sensor,
            law=self.law,
            velocity=self.velocity,
            duration=self.duration,
            sample_rate=self.sample_rate,
            method=self.method,
            segments=self.segments,
            contact_intervals=self.contact_intervals,
            events=self.events,
            threshold=self.threshold,
            rtol=self.rtol,
            time_step=self.time_step,
        )

    # -- dense evaluation ----------------------------------------------------
    def _evaluate(self, times):
        """States (n, 4) and contact force (n,) at arbitrary times [s] inside the solution."""
        times = np.atleast_1d(np.asarray(times, dtype=float))
        states = np.empty((times.size, 4))
        force = np.empty(times.size)
        which = np.clip(np.searchsorted(self._starts, times, side="right") - 1, 0, None)
        for i in np.unique(which):
            seg = self.segments[i]
            mask = which == i
            tau = times[mask] - seg.t0
            st = seg.states(tau)
            states[mask] = st
            force[mask] = segment_force(seg, tau, st, self._formulas[i])
        return states, force

    def _evaluate_grid(self):
        """States (n, 4) and contact force (n,) on the output grid ``self.t``.

        Same segment choice as :meth:`_evaluate` (a sample on a segment start belongs to
        the segment that starts there), through each segment's uniform-grid path. The
        states are stored column by column, so ``x1`` ... ``v2`` are contiguous.
        """
        n, step = self.t.size, 1.0 / self.sample_rate
        states, force = np.empty((4, n)).T, np.empty(n)
        edges = np.searchsorted(self.t, self._starts, side="left")
        edges[0] = 0
        bounds = zip(self.segments, self._formulas, edges, [*edges[1:], n], strict=True)
        for seg, formula, lo, hi in bounds:
            if hi > lo:
                tau = self.t[lo:hi] - seg.t0
                st = seg.states_on_grid(tau, step, states[lo:hi])
                force[lo:hi] = segment_force(seg, tau, st, formula)
        return states, force

    def _segment_at(self, t):
        """The index of the segment holding time ``t`` [s] (the later one on a boundary),
        as in :meth:`_evaluate`."""
        return max(bisect.bisect_right(self._starts, t) - 1, 0)

    def _at(self, t):
        """State (1, 4) and contact force (1,) at one time [s]: the scalar fast path."""
        i = self._segment_at(t)
        seg = self.segments[i]
        tau = np.array([t - seg.t0])
        states = seg.states(tau)
        return states, segment_force(seg, tau, states, self._formulas[i])

    def _signal_at(self, t):
        if self.sensor.is_rigid:
            return self._force_at(t)
        seg = self.segments[self._segment_at(t)]
        return float(self.sensor.signal(seg.states(np.array([t - seg.t0])), None)[0])

    def _forces_on(self, times):
        """Contact force S2 [N] at several times [s]."""
        return self._evaluate(times)[1]

    def _signals_on(self, times):
        """Sensor signal S1 [N] at several times [s]."""
        return self.sensor.signal(*self._evaluate(times))

    def _force_at(self, t):
        return float(self._at(t)[1][0])

    def _integrate(self, integrand, start, end):
        """Gauss-Legendre integral of ``integrand(states, force)`` over [start, end] [s].

        Each piece is split into panels of at most one sensor period (the ringing is
        smooth but oscillatory), and contact pieces are graded geometrically towards
        their start, where damped Hertz laws behave like ``t**0.25``.
        """
        total = 0.0
        period = self._system_period()
        for seg, formula in zip(self.segments, self._formulas, strict=True):
            lo, hi = max(seg.t0, start), min(seg.t1, end)
            if hi <= lo:
                continue
            nodes, weights = gauss_rule(lo, hi, period, graded=seg.kind == "contact")
            tau = nodes - seg.t0  # every panel's nodes in one evaluation of the piece
            st = seg.states(tau)
            total += float(weights @ integrand(st, segment_force(seg, tau, st, formula)))
        return total

    def _system_period(self):
        return math.inf if self.sensor.is_rigid else self.sensor.period

    # -- events --------------------------------------------------------------
    @cached_property
    def rebound_velocity(self):
        """Grain speed away from the sensor after its last contact in the window [m/s]."""
        end = self.contact_intervals[-1][1]
        return -float(self._evaluate([end])[0][0, 3])

    # -- pulse metrics -------------------------------------------------------
    def _refined_max(self, values_on, grid_values, start, end):
        """Largest value of a dense signal on [start, end] [s], refined from the grid.

        Every local maximum of the grid samples (and the ends of the interval) is a
        candidate: a sensor ringing on a slow pulse has many nearly equal peaks, and
        the largest sample need not sit by the largest peak when the grid has few
        samples per period. Around each candidate, one sample interval each side is
        searched on 17 points of the dense solution, zoomed eightfold around the best
        point five times (all candidates at once): each peak's time to about 1e-5 of a
        sample interval, so its value to about 1e-10 relative on a smooth peak, and no
        smoothness assumed (a plateau or a kink is found just as well).

        Parameters
        ----------
        values_on : callable
            ``values_on(times) -> (n,)``: the signal on the dense solution.
        grid_values : numpy.ndarray
            The signal on the output grid ``self.t``.
        """
        inside = np.flatnonzero((self.t >= start) & (self.t <= end))
        v = grid_values[inside]
        peaks = inside[1:-1][(v[1:-1] > v[:-2]) & (v[1:-1] >= v[2:])]
        if v.size:
            peaks = np.append(peaks, inside[v.argmax()])
        candidates = np.concatenate(([start, end], self.t[peaks]))
        width = 1.0 / self.sample_rate
        offsets = np.linspace(-1.0, 1.0, 17)
        for _ in range(_ZOOMS):
            times = np.clip(candidates[:, None] + width * offsets, start, end)
            values = values_on(times.ravel()).reshape(times.shape)
            candidates = times[np.arange(times.shape[0]), values.argmax(axis=1)]
            width /= 8.0
        values = values_on(candidates)
        best = int(np.argmax(values))
        return float(candidates[best]), float(values[best])

    @cached_property
    def _contact_peak(self):
        """``(time [s], force [N])`` of the first contact's largest force, refined on the
        dense solution between the grid's samples."""
        start, end = self.contact_intervals[0]
        return self._refined_max(self._forces_on, self.contact_force, start, end)

    @cached_property
    def sensor_lobe(self):
        """(start, end) [s] of the sensor signal's first main lobe above ``threshold``.

        Read as an experimenter would, from the first rise above the threshold to the first
        return to it, with the crossings located on the dense solution.
        """
        start, end = metrics.first_lobe(self.t, self.sensor_force, self.threshold)
        h, level = 1.0 / self.sample_rate, self.threshold
        if np.isfinite(start) and start > self.t[0]:
            lo, hi = max(start - h, 0.0), min(start + h, self.duration)
            start = _crossing(self._signal_at, level, lo, hi)
        if np.isfinite(end):
            lo, hi = max(end - h, 0.0), min(end + h, self.duration)
            end = _crossing(self._signal_at, level, lo, hi)
        return float(start), float(end)

    @property
    def sensor_response_time(self):
        """Duration of the sensor signal's first main lobe [s] (nan if it does not end)."""
        start, end = self.sensor_lobe
        return end - start

    @cached_property
    def _sensor_peak(self):
        start, end = self.sensor_lobe
        if not np.isfinite(start):
            return math.nan, math.nan
        end = self.duration if not np.isfinite(end) else end
        return self._refined_max(self._signals_on, self.sensor_force, start, end)

    @property
    def peak_sensor_force(self):
        """Largest sensor signal S1 in its first main lobe [N]."""
        return self._sensor_peak[1]

    @cached_property
    def impulse(self):
        """Integral of the contact force S2 over all contacts [N*s] (Gauss-Legendre)."""
        return sum(
            self._integrate(lambda st, f: f, start, end) for start, end in self.contact_intervals
        )

    @cached_property
    def sensor_impulse(self):
        """Integral of the sensor signal S1 over the window [N*s]."""
        return self._integrate(lambda st, f: self.sensor.signal(st, f), 0.0, self.duration)

    @cached_property
    def energy_balance(self):
        """Where the grain's kinetic energy went by the end of the window [J].

        Keys: ``kinetic_in``, ``grain_kinetic_out``, ``sensor_energy_out`` (kinetic and
        elastic), ``sensor_damping_loss`` (``integral c1 v1**2``), ``contact_loss``
        (``integral S2 d'``, the work the contact absorbed), and ``residual`` (in minus
        the rest; zero up to the solver's accuracy). Integrals are Gauss-Legendre on the
        dense solution, independent of the solver's own bookkeeping.
        """
        sensor, m2, t_end = self.sensor, self.grain.mass, self.duration
        final = self._evaluate([t_end])[0][0]
        out = {"kinetic_in": 0.5 * m2 * self.velocity**2}
        out["grain_kinetic_out"] = 0.5 * m2 * final[3] ** 2
        contact_loss = self._integrate(lambda st, f: f * (st[:, 3] - st[:, 1]), 0.0, t_end)
        if sensor.is_rigid:
            out["sensor_energy_out"] = out["sensor_damping_loss"] = 0.0
        else:
            out["sensor_energy_out"] = sensor.energy(final[0], final[1])
            out["sensor_damping_loss"] = self._integrate(
                lambda st, f: sensor.damping * st[:, 1] ** 2, 0.0, t_end
            )
        out["contact_loss"] = contact_loss
        out["residual"] = out["kinetic_in"] - sum(
            out[k]
            for k in (
                "grain_kinetic_out",
                "sensor_energy_out",
                "sensor_damping_loss",
                "contact_loss",
            )
        )
        return out

    @cached_property
    def grain_work(self):
        """Work done by the contact force on the grain, ``-integral S2 v2 dt`` [J]."""
        return self._integrate(lambda st, f: -f * st[:, 3], 0.0, self.duration)

    def audit(self, full=True):
        """Energy ledger and invariants over the first contact (:mod:`contactlab.audit`).

        Parameters
        ----------
        full : bool, default True
            With the ledger, the one-sided force, the damper's work and the momentum
            balance; False: the ``energy`` check alone, which
            :func:`contactlab.simulate_impact` runs by default.

        Returns
        -------
        contactlab.audit.Audit
        """
        from contactlab.impact_audit import audit_impact

        return audit_impact(self, check_flag("full", full))

    # -- output ----------------------------------------------------------------
    def summary(self):
        """Headline numbers as a dict with unit-bearing keys (JSON-ready)."""
        out = {
            **self._headline(),
            "duration [s]": self.duration,
            "sample_rate [Hz]": self.sample_rate,
            "energy_balance [J]": self.energy_balance,
        }
        if self.verification is not None:
            out["verification [relative]"] = self.verification
        return out

    def __repr__(self):
        return (
            f"ImpactResult({type(self.law).__name__}, method={self.method!r}, "
            f"contact_time={self.contact_time * 1e6:.4g} us, "
            f"peak_contact_force={self.peak_contact_force:.4g} N, "
            f"sensor_response_time={self.sensor_response_time * 1e6:.4g} us, "
            f"peak_sensor_force={self.peak_sensor_force:.4g} N, "
            f"restitution={self.restitution:.4g}, contacts={len(self.contact_intervals)})"
        )
