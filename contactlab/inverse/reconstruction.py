"""The result of :func:`contactlab.inverse.reconstruct_force`: the force, what was chosen
and how far the baseline under it can be trusted."""

from dataclasses import dataclass, field

import numpy as np

__all__ = ["ForceReconstruction"]


@dataclass(frozen=True, eq=False)
class ForceReconstruction:
    """An estimate of the contact force from a sensor signal (SI units).

    ``t`` [s] is the input time axis, ``signal`` [N] the input with its local baseline
    removed, ``force`` [N] the reconstructed contact force on ``t``. ``parameters``
    holds what was chosen (regularisation, cutoff, windows, noise, the baseline's drift
    across the pulse), ``metrics`` the pulse metrics of ``force``, its edges read by
    the rule ``parameters["contact_edges"]`` names (where the force is significant, or
    at ``parameters["threshold [N]"]``). ``status`` is ``"ok"`` or what makes the baseline
    doubtful (``short pre-trigger``, ``drifting baseline``, ``not free ringing``), and
    ``notes`` says it with the numbers (:func:`contactlab.inverse.pulse.pulse_baseline`).
    """

    t: np.ndarray
    signal: np.ndarray
    force: np.ndarray
    method: str
    parameters: dict = field(default_factory=dict)
    metrics: object = None
    status: str = "ok"
    notes: tuple = ()

    def to_frame(self):
        """Time, signal and reconstructed force as a DataFrame with unit-bearing columns."""
        import pandas as pd

        return pd.DataFrame(
            {"t [s]": self.t, "sensor_force [N]": self.signal, "contact_force [N]": self.force}
        )

    def summary(self):
        """Method, parameters and metrics as a dict with unit-bearing keys (JSON-ready)."""
        return {
            "method": self.method,
            "status": self.status,
            "notes": list(self.notes),
            "parameters": dict(self.parameters),
            "metrics": self.metrics.to_dict(),
        }

    def plot(self, ax=None, truth=None):
        """Signal, reconstruction and (optionally) the true force; returns (fig, ax).

        See :func:`contactlab.inverse.plots.plot_reconstruction`.
        """
        from contactlab.inverse.plots import plot_reconstruction

        return plot_reconstruction(self, truth=truth, ax=ax)

    def __repr__(self):
        m = self.metrics
        notes = "".join(f"\n  note: {note}" for note in self.notes)
        return (
            f"ForceReconstruction(method={self.method!r}, peak={m.peak:.4g} N, "
            f"duration={m.duration * 1e6:.4g} us, impulse={m.impulse:.4g} N*s, "
            f"status={self.status!r}){notes}"
        )
