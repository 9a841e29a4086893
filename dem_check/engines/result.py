"""What an engine's drop test returns: :class:`EngineResult`, read like the reduced model.

Every engine of :mod:`dem_check.engines` records its steps and hands them to
:class:`EngineResult`, whose headline numbers are those of
:class:`contactlab.ImpactResult` (:class:`~contactlab.result.ImpactSignals`), so
:func:`contactlab.compare` takes either. :func:`contact_crossings` locates contacts between
steps.
"""

from functools import cached_property

import numpy as np

from contactlab import metrics
from contactlab.result import ImpactSignals

__all__ = ["EngineResult", "contact_crossings"]


class EngineResult(ImpactSignals):
    """One impact run in an engine (see :func:`dem_check.engines.drop_test`).

    The same signals and headline numbers as :class:`contactlab.ImpactResult`, read from
    the engine's steps instead of an exact solution.

    Signals (numpy arrays, one sample per engine step, time ``t`` [s] from the first touch,
    negative before it): ``contact_force`` (S2, the engine's contact normal force) [N],
    ``sensor_force`` (S1 from the sensor's state) [N], ``x1``, ``x2`` [m], ``v1``, ``v2``
    [m/s] and ``overlap`` [m].

    Headline numbers: ``contact_time`` [s], ``peak_contact_force`` [N],
    ``sensor_response_time`` [s], ``peak_sensor_force`` [N], ``impulse`` [N*s],
    ``restitution`` [-], ``rebound_velocity`` [m/s], ``contact_intervals`` [(start, end) s],
    ``numerical_damping`` [N*s/m], and ``metadata`` (engine settings, steps, wall time).

    ``method`` names the engine (``"pybullet"``), as :attr:`contactlab.ImpactResult.method`
    names the solver; ``metadata`` must hold ``"time_step [s]"`` and
    ``"numerical_damping [N*s/m]"`` (0 for an engine whose contact adds none).

    Notes
    -----
    The engine's reader gives the contact intervals. In pybullet the contact lasts while
    the overlap and the engine's spring-damper force ``k2 d + c d'`` (``c`` as passed to the
    engine) are both positive; its start and end are located by linear interpolation
    between steps of ``k2 d + c min(d', 0)`` (:func:`contact_crossings`). With ``c = 0``
    these are the overlap's sign changes. Peaks are the largest step values (500
    steps per contact put them within ~1e-5 of the continuous peak), the impulse is the sum
    of the engine's per-step impulses, and the sensor signal's first lobe is read with
    :func:`contactlab.metrics.pulse_metrics`, as for a measured trace.
    """

    def __init__(
        self, *, method, grain, sensor, law, velocity, t, signals, intervals, metadata, threshold
    ):
        self.method = method
        self.grain, self.sensor, self.law = grain, sensor, law
        self.velocity = velocity
        self.threshold = threshold
        self.t = t
        self.x1, self.v1, self.x2, self.v2, self.contact_force, self.sensor_force = signals
        self.overlap = self.x2 - self.x1
        self.contact_intervals = intervals
        self.metadata = metadata

    @property
    def time_step(self):
        """Engine step [s]."""
        return self.metadata["time_step [s]"]

    @property
    def numerical_damping(self):
        """Damping the engine's contact solver adds [N*s/m] (pybullet: ``k2 * dt``, compensated
        or not)."""
        return self.metadata["numerical_damping [N*s/m]"]

    @cached_property
    def _contact_peak(self):
        """``(time [s], force [N])`` of the first contact's largest force, read on the
        engine's steps (no dense solution between them)."""
        start, end = self.contact_intervals[0]
        return metrics.peak(self.t, self.contact_force, start, end)

    @cached_property
    def sensor_pulse(self):
        """:class:`contactlab.metrics.PulseMetrics` of the sensor signal's first lobe."""
        return metrics.pulse_metrics(self.t, self.sensor_force, self.threshold)

    @property
    def sensor_lobe(self):
        """(start, end) [s] of the sensor signal's first lobe above ``threshold``."""
        return self.sensor_pulse.start, self.sensor_pulse.end

    @property
    def sensor_response_time(self):
        """Duration of the sensor signal's first lobe [s] (nan if it does not end)."""
        return self.sensor_pulse.duration

    @property
    def peak_sensor_force(self):
        """Largest sensor signal S1 in its first lobe [N]."""
        return self.sensor_pulse.peak

    @property
    def impulse(self):
        """Sum of the engine's contact impulses ``dt * S2`` over all steps [N*s]."""
        return self.time_step * float(np.sum(self.contact_force))

    @property
    def rebound_velocity(self):
        """Grain speed away from the sensor at the end of its last contact [m/s]."""
        end = self.contact_intervals[-1][1]
        return -float(np.interp(end, self.t, self.v2))

    def audit(self):
        """Energy, one-sided force and momentum of the first contact, with tolerances set
        by the engine's step (:func:`dem_check.engines.audit.audit_engine`).

        Returns
        -------
        contactlab.audit.Audit
        """
        from dem_check.engines.audit import audit_engine

        return audit_engine(self)

    def summary(self):
        """Headline numbers and engine settings as a dict with unit-bearing keys (JSON-ready)."""
        return {**self._headline(), **self.metadata}

    def __repr__(self):
        return (
            f"EngineResult({type(self.law).__name__}, engine={self.method!r}, "
            f"time_step={self.time_step:.3g} s, "
            f"contact_time={self.contact_time * 1e6:.4g} us, "
            f"peak_contact_force={self.peak_contact_force:.4g} N, "
            f"sensor_response_time={self.sensor_response_time * 1e6:.4g} us, "
            f"peak_sensor_force={self.peak_sensor_force:.4g} N, "
            f"restitution={self.restitution:.4g}, "
            f"numerical_damping={self.numerical_damping:.3g} N*s/m, "
            f"contacts={len(self.contact_intervals)})"
        )


def contact_crossings(indicator, t):
    """(rise, fall) times [s] where ``indicator`` changes sign, linearly interpolated.

    Parameters
    ----------
    indicator : numpy.ndarray
        A quantity positive in contact, one value per engine step (e.g. the contact force
        [N]).
    t : numpy.ndarray
        Time of each step [s].

    Returns
    -------
    rises, falls : numpy.ndarray
        Start and end times [s] of each contact; a trailing ``nan`` fall marks a contact
        still open at the end.
    """
    positive = indicator > 0.0
    edges = np.flatnonzero(positive[1:] != positive[:-1]) + 1
    y0, y1 = indicator[edges - 1], indicator[edges]
    times = t[edges - 1] + (t[edges] - t[edges - 1]) * y0 / (y0 - y1)
    rises = times[positive[edges]]
    falls = times[~positive[edges]]
    if positive[-1]:
        falls = np.append(falls, np.nan)
    return rises, falls
