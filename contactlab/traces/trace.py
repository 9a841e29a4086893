"""The :class:`Trace`: one measured channel on its time axis, with where it came from."""

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from contactlab.errors import ParameterError
from contactlab.metrics import pulse_metrics
from contactlab.traces.units import SI_VALUE_UNITS
from contactlab.validation import check_samples

__all__ = ["Trace"]


@dataclass(frozen=True, eq=False, repr=False)
class Trace:
    """One channel of a measured (or synthetic) trace, in SI units.

    Readers return values in SI base units (``"V"``, ``"N"`` or ``"A"``) whatever the file
    wrote (``mV``, ``ms``, ...); the unit as written is kept in ``metadata``. The arrays are
    read-only: every processing step (:mod:`contactlab.traces.prepare`) returns a new
    ``Trace`` and appends itself to ``metadata["history"]``.

    Parameters
    ----------
    t : array_like
        Sample times [s]. Readers guarantee strictly increasing, finite times.
    values : array_like
        Samples in ``unit``. Overrange samples are ``+inf``/``-inf`` and their indices are
        listed in ``metadata["overrange"]``.
    unit : str
        SI unit of ``values``: ``"V"``, ``"N"`` or ``"A"``.
    metadata : dict
        What the file said and what was done. Keys set by every reader:

        ``format``
            Registry name of the layout read (e.g. ``"rigol-sequence"``).
        ``source``
            Path of the file.
        ``instrument``
            Model named by the file, or ``None``.
        ``channel``, ``channels``
            The channel read and all channels the file holds.
        ``sample_interval``
            Sample interval [s]; ``sample_interval_source`` says whether the file's header
            declared it or it is the mean spacing of the file's time column.
        ``trigger_time``
            Time of the trigger [s] (``0.0`` for oscilloscopes, which write time relative
            to it), or ``None`` when the file does not say.
        ``time_unit``, ``vertical_unit``
            Units exactly as written in the file.
        ``header``
            Header fields verbatim (``{key: value}`` strings, or the header lines).
        ``overrange``
            Indices (int array, empty if none) of samples at the instrument's limit.
        ``history``
            List of processing steps, each a dict naming the step and its parameters.
    """

    t: np.ndarray
    values: np.ndarray
    unit: str
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        t = check_samples("t", self.t, unit="s")
        values = check_samples("values", self.values, finite=False)  # overrange: inf
        if not isinstance(self.metadata, Mapping):
            raise ParameterError(f"metadata must be a dict; got {type(self.metadata).__name__}")
        if values.shape != t.shape:
            raise ParameterError(
                f"t and values must be 1-D arrays of equal length; got shapes {t.shape} "
                f"and {values.shape}"
            )
        if not isinstance(self.unit, str) or self.unit not in SI_VALUE_UNITS:  # "mV": volts?
            raise ParameterError(
                f"unit must be one of {', '.join(SI_VALUE_UNITS)} (SI base units; scale "
                f"the values instead); got {self.unit!r}"
            )
        for name, array in (("t", t), ("values", values)):
            if array.flags.writeable:
                array = array.view()
                array.flags.writeable = False
            object.__setattr__(self, name, array)
        metadata = dict(self.metadata)
        metadata["history"] = list(metadata.get("history", ()))
        if "overrange" not in metadata:
            metadata["overrange"] = np.flatnonzero(np.isinf(values))
        object.__setattr__(self, "metadata", metadata)

    def __len__(self):
        return self.t.size

    def __repr__(self):
        span = f"{self.t[0]:.6g} .. {self.t[-1]:.6g} s" if len(self) else "empty"
        name = self.metadata.get("channel")
        return (
            f"Trace({len(self)} samples, {span}, unit={self.unit!r}, channel={name!r}, "
            f"format={self.metadata.get('format')!r})"
        )

    @property
    def sample_interval(self):
        """Sample interval [s] as recorded in ``metadata`` (``None`` if unknown)."""
        return self.metadata.get("sample_interval")

    @property
    def value_label(self):
        """Column name of the values: ``"force [N]"`` or ``"value [<unit>]"``."""
        return "force [N]" if self.unit == "N" else f"value [{self.unit}]"

    def to_frame(self):
        """The trace as a DataFrame with columns ``t [s]`` and :attr:`value_label`."""
        return pd.DataFrame({"t [s]": self.t, self.value_label: self.values})

    def derive(self, step, **changes):
        """A new trace with ``changes`` applied and ``step`` appended to the history.

        Parameters
        ----------
        step : dict
            Description of the processing step; must contain ``"step"`` (its name).
        **changes
            New ``t``, ``values``, ``unit`` and/or ``metadata`` entries (a dict merged
            into a copy of this trace's metadata).

        Returns
        -------
        Trace

        Raises
        ------
        ParameterError
            ``step`` not a dict with a ``"step"`` name, an unknown change, or metadata
            that is not a dict.
        """
        if not isinstance(step, Mapping) or not isinstance(step.get("step"), str):
            raise ParameterError(
                f"step must be a dict naming the processing step as 'step'; got {step!r}"
            )
        unknown = set(changes) - {"t", "values", "unit", "metadata"}
        if unknown:
            raise ParameterError(
                f"derive changes t, values, unit and metadata only; got {sorted(unknown)}"
            )
        if not isinstance(changes.get("metadata", {}), Mapping):
            raise ParameterError(f"metadata must be a dict; got {changes['metadata']!r}")
        metadata = {**self.metadata, **changes.pop("metadata", {})}
        metadata["history"] = [*self.metadata["history"], step]
        if "values" in changes:
            metadata.pop("overrange")
        fields = {"t": self.t, "values": self.values, "unit": self.unit, **changes}
        return Trace(metadata=metadata, **fields)

    def metrics(self, threshold=0.0, hysteresis=0.0, least_peak=0.0):
        """Pulse metrics of the first lobe, read as for a simulation.

        Uses :func:`contactlab.metrics.pulse_metrics` on ``(t, values)``, so a measured
        and a simulated pulse are read identically. Remove the baseline first
        (:func:`~contactlab.traces.prepare.remove_baseline`); the metrics are in the trace's
        unit (N after a sensitivity conversion).

        Parameters
        ----------
        threshold : float, default 0.0
            Level defining the lobe, in the trace's unit, e.g. ``5 * noise_level(trace)``.
        hysteresis : float, default 0.0
            How far below the threshold the signal must fall to end the lobe, in the
            trace's unit (see :func:`contactlab.metrics.first_lobe`); e.g. the threshold
            itself, so that only a return to the baseline ends it.
        least_peak : float, default 0.0
            Lobes whose peak is under this fraction of the trace's largest value are
            passed over [-] (see :func:`contactlab.metrics.first_lobe`).

        Returns
        -------
        contactlab.metrics.PulseMetrics

        Raises
        ------
        ParameterError
            If the trace holds overrange samples (their true value is unknown).
        """
        overrange = self.metadata["overrange"]
        if len(overrange):
            raise ParameterError(
                f"the trace has {len(overrange)} overrange samples (first at index "
                f"{overrange[0]}); their true values are unknown, so no pulse metrics"
            )
        return pulse_metrics(self.t, self.values, threshold, self.unit, hysteresis, least_peak)
