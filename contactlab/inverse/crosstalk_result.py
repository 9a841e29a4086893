"""What :mod:`contactlab.inverse.crosstalk` returns: the structure modes removed from an
impact, the crosstalk's values and its fitted model, whose share of any linear reading
of the record (an impulse) and that share's propagated error it gives."""

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Crosstalk", "StructureMode"]


@dataclass(frozen=True)
class StructureMode:
    """One structure mode removed from an impact."""

    frequency: float
    """Damped frequency [Hz]."""
    damping_ratio: float
    """[-]."""
    amplitude: float
    """Initial amplitude of the mode's response to this impact (unit of the record, N)."""


@dataclass(frozen=True, eq=False)
class Crosstalk:
    """The structure's crosstalk in a stretch of a record (see :func:`fit_crosstalk`)."""

    modes: tuple
    """:class:`StructureMode` of each mode removed (empty when none was significant)."""
    values: np.ndarray
    """The crosstalk at every sample of the stretch (responses to this impact and free
    ringing from earlier ones), to be subtracted (unit of the record)."""
    columns: np.ndarray = None
    """``(samples, k)``: each fitted column of the crosstalk's model on the stretch
    (``values = columns @ coefficients``); None when no mode was removed."""
    coefficients: np.ndarray = None
    """``(k,)``: the columns' fitted coefficients; None when no mode was removed."""
    covariance: np.ndarray = None
    """``(k, k)``: their covariance under the noise (unit of the record squared); None
    when no mode was removed."""

    def describe(self):
        """``"730 Hz (zeta 0.010): 0.041 N; ..."``, or ``""`` when no mode was removed."""
        return "; ".join(
            f"{m.frequency:.0f} Hz (zeta {m.damping_ratio:.3f}): {m.amplitude:.3g} N"
            for m in self.modes
        )

    def share(self, readings):
        """What the crosstalk adds to a linear reading of the record, and that share's
        standard error under the noise of its fit.

        Parameters
        ----------
        readings : array_like
            ``(k,)``: a linear reading of the record (e.g. its impulse [N*s] read with a
            local baseline) applied to each of :attr:`columns`.

        Returns
        -------
        (float, float)
            The reading of :attr:`values`, ``g @ coefficients``, and its standard error
            ``sqrt(g' C g)`` (``g`` the readings, ``C`` :attr:`covariance`; exact for a
            linear reading); ``(0, 0)`` when no mode was removed.
        """
        if self.columns is None:
            return 0.0, 0.0
        g = np.asarray(readings, dtype=float)
        variance = float(g @ self.covariance @ g)
        return float(g @ self.coefficients), math.sqrt(max(variance, 0.0))

    def cropped(self, part):
        """The crosstalk on ``part`` (a slice) of its stretch."""
        columns = None if self.columns is None else self.columns[part]
        return Crosstalk(self.modes, self.values[part], columns, self.coefficients, self.covariance)
