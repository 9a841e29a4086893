"""The result of a contact-law fit: fitted parameters with intervals, FIT.json layout."""

import json
import math
from dataclasses import dataclass, field

import numpy as np

from contactlab.bodies import Grain, Sensor
from contactlab.inverse.fit_models import FIT_MODELS
from contactlab.inverse.fit_quality import FitQuality
from contactlab.solver.wall import wall_restitution
from contactlab.validation import check_path

__all__ = ["FORMAT", "ContactFit", "FittedParameter"]

FORMAT = "contactlab-fit-1"
"""Tag of the JSON layout written by :meth:`ContactFit.to_dict` (read by the exporter)."""


def _finite_or_none(value):
    """JSON has no infinity: an unbounded limit is written as null."""
    return float(value) if math.isfinite(value) else None


@dataclass(frozen=True)
class FittedParameter:
    """One fitted quantity with its uncertainty (SI units)."""

    value: float
    """Best-fit value."""
    stderr: float
    """Standard error (delta method from the transformed coordinate)."""
    ci95: tuple
    """95 % confidence interval ``(low, high)``: +-1.96 standard errors of the
    transformed coordinate, mapped back (asymmetric for ln p and logit e)."""
    unit: str
    """Unit of ``value``."""
    identifiable: bool
    """False when the trace does not determine it (see :data:`MAX_TRANSFORMED_STDERR`)."""

    def to_dict(self):
        """As a JSON-ready dict."""
        return {
            "value": self.value,
            "stderr": _finite_or_none(self.stderr),
            "ci95": [_finite_or_none(v) for v in self.ci95],
            "unit": self.unit,
            "identifiable": self.identifiable,
        }


@dataclass(frozen=True, eq=False)
class ContactFit:
    """A contact law fitted to a sensor trace (see :func:`fit_contact`).

    ``parameters`` maps each fitted name (the law's, ``velocity`` unless it was
    measured, ``onset``) to a :class:`FittedParameter`; ``fixed`` holds the law
    parameters that were given instead of fitted; ``law`` is the fitted law
    object; ``simulation`` the model at the best fit (its ``contact_force`` is the
    fitted S2). ``t``, ``signal``, ``model`` and ``residuals`` [N] are on the fitted
    samples, ``model`` including ``baseline_offset``, the fitted correction [N] to the
    noise window's mean (subtracted from ``signal``). ``quality`` judges whether the
    law is consistent with the trace (:class:`~contactlab.inverse.fit_quality.FitQuality`).
    """

    law: object
    law_name: str
    parameters: dict
    fixed: dict
    velocity: float
    velocity_measured: bool
    onset: float
    grain: Grain
    sensor: Sensor
    t: np.ndarray
    signal: np.ndarray
    model: np.ndarray
    goodness: dict
    quality: FitQuality
    baseline_offset: FittedParameter
    simulation: object = field(repr=False, default=None)
    baseline_status: str = "ok"
    """The local baseline's status (:class:`contactlab.inverse.pulse.PulseBaseline`):
    ``ok``, ``drifting baseline``, ``not free ringing``."""
    baseline_notes: tuple = ()
    """Why the baseline's status is not ``ok``, with the numbers."""

    @property
    def residuals(self):
        """Model minus signal at the fitted samples [N]."""
        return self.model - self.signal

    @property
    def not_identifiable(self):
        """Names of the parameters the trace does not determine."""
        return [name for name, p in self.parameters.items() if not p.identifiable]

    @property
    def rebound(self):
        """Rebound of the fitted parameters on a rigid wall at the fitted velocity [-].

        ``"fitted_law [-]"``: the law's own (its force never pulls, contact ends at zero
        force; LAMMPS, LIGGGHTS and YADE realise it); ``"overlap_end [-]"``: what a DEM
        code whose damper may pull until zero overlap realises from the same inputs
        (MercuryDPM, the convention of the restitution mappings), None for a law without
        a viscous damper, whose rebound does not depend on the convention.
        """
        values = {name: p.value for name, p in self.parameters.items()} | self.fixed
        overlap = FIT_MODELS[self.law_name].overlap_rebound
        return {
            "fitted_law [-]": float(wall_restitution(self.law, self.grain.mass, self.velocity)),
            "overlap_end [-]": None if overlap is None else float(overlap(values, self.grain)),
        }

    def summary(self):
        """The fit as text: parameters with 95 % intervals, rebounds, quality."""
        lines = [f"fitted law: {self.law_name}"]
        for name, p in self.parameters.items():
            low, high = p.ci95
            note = "" if p.identifiable else "  NOT IDENTIFIABLE"
            lines.append(
                f"  {name} = {p.value:.6g} {p.unit}  (95 % interval {low:.6g} .. {high:.6g})" + note
            )
        lines += [f"  {name} = {value:.6g} (fixed)" for name, value in self.fixed.items()]
        low, high = self.baseline_offset.ci95
        lines.append(
            f"  baseline offset = {self.baseline_offset.value:.3g} N  (95 % interval "
            f"{low:.3g} .. {high:.3g}; added to the noise window's mean)"
        )
        if not self.goodness["converged"]:
            lines.append("  the optimiser did NOT converge")
        rebound = self.rebound
        own, overlap = rebound["fitted_law [-]"], rebound["overlap_end [-]"]
        lines.append(
            f"rebound on a rigid wall: {own:.4f} (the fitted law: contact ends at zero force)"
        )
        if overlap is not None and abs(overlap - own) > 5e-4:
            lines.append(
                f"  {overlap:.4f} in a DEM code whose damper pulls until zero overlap "
                "(MercuryDPM) with the same parameters"
            )
        lines.append(self.quality.summary())
        lines.append(f"baseline: {self.baseline_status}")
        lines += [f"  note: {note}" for note in self.baseline_notes]
        return "\n".join(lines)

    def to_dict(self):
        """Everything needed to reuse the fit (FIT.json layout, JSON-ready)."""
        return {
            "format": FORMAT,
            "law": self.law_name,
            "law_parameters": self.law.parameters(),
            "parameters": {k: p.to_dict() for k, p in self.parameters.items()},
            "fixed": dict(self.fixed),
            "velocity [m/s]": self.velocity,
            "velocity_measured": self.velocity_measured,
            "onset [s]": self.onset,
            "grain": self.grain.to_dict(),
            "sensor": self.sensor.to_dict(),
            "goodness_of_fit": dict(self.goodness),
            "quality": self.quality.to_dict(),
            "baseline_offset": self.baseline_offset.to_dict(),
            "baseline_status": self.baseline_status,
            "baseline_notes": list(self.baseline_notes),
            "rebound_on_wall": self.rebound,
            "contact_time_on_sensor [s]": self.simulation.contact_time,
            "restitution_on_sensor [-]": self.simulation.restitution,
            "not_identifiable": self.not_identifiable,
        }

    def to_json(self, path=None):
        """The :meth:`to_dict` layout as JSON text; also written to ``path`` if given."""
        if path is not None:
            check_path("path", path)
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text + "\n")
        return text

    def plot(self, ax=None):
        """Trace, fitted signal and fitted contact force; returns (fig, ax).

        See :func:`contactlab.inverse.plots.plot_fit`.
        """
        from contactlab.inverse.plots import plot_fit

        return plot_fit(self, ax=ax)

    def __repr__(self):
        fitted = ", ".join(
            f"{k}={p.value:.4g}{'' if p.identifiable else ' (not identifiable)'}"
            for k, p in self.parameters.items()
        )
        chi2 = self.quality.reduced_chi_squared
        verdict = "consistent" if self.quality.consistent else "NOT consistent"
        return f"ContactFit({self.law_name}: {fitted}; reduced chi2={chi2:.3g}, {verdict})"
