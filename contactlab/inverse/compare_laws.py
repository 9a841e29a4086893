"""Which contact law does a trace support? Every fittable law fitted, ranked by BIC.

Each law of :data:`~contactlab.inverse.fit_models.FIT_MODELS` is fitted to the same
samples with the same noise (:func:`~contactlab.inverse.fit.fit_contact`), so their
chi-squared values are comparable. With Gaussian noise of known level, ``-2 ln L`` is the
chi-squared plus a constant, and the Bayesian information criterion is

    BIC = chi^2 + p ln n

(``p`` fitted quantities, ``n`` fitted samples; Schwarz 1978). The law with the smallest
BIC is the best supported; a difference above :data:`DISFAVOURED_DELTA_BIC` is "very
strong" evidence against the other (Kass & Raftery 1995). BIC, not AIC: the laws are
nested (``hertz`` is ``hertz_damped`` with e = 1), and BIC's penalty of ``ln n`` (8 for
3000 samples) keeps a needless parameter out where AIC's 2 lets one in about once in six
traces. Independently of the ranking, each law's own judgement
(:class:`~contactlab.inverse.fit_quality.FitQuality`) says whether the data reject it:
the best-ranked law can be rejected too, when no candidate describes the trace.

References
----------
Schwarz G. (1978) Estimating the dimension of a model. Ann. Stat. 6, 461-464.
DOI 10.1214/aos/1176344136.
Kass R.E., Raftery A.E. (1995) Bayes factors. J. Am. Stat. Assoc. 90, 773-795.
DOI 10.1080/01621459.1995.10476572.
"""

import math
import warnings
from dataclasses import dataclass

from contactlab.blas import with_one_blas_thread
from contactlab.entry_checks import check_names
from contactlab.errors import ParameterError
from contactlab.inverse.fit import IdentifiabilityWarning, fit_contact
from contactlab.inverse.fit_models import FIT_MODELS
from contactlab.inverse.fit_quality import FitQualityWarning

__all__ = [
    "COMPARED_FIT_OPTIONS",
    "DISFAVOURED_DELTA_BIC",
    "LawComparison",
    "RankedLaw",
    "compare_laws",
]

COMPARED_FIT_OPTIONS = ("baseline_window", "window", "max_nfev", "crosstalk")
"""The keywords of :func:`~contactlab.inverse.fit.fit_contact` that :func:`compare_laws`
passes to every fit (``fixed`` names one law's parameters, so it is not among them)."""

DISFAVOURED_DELTA_BIC = 10.0
"""BIC difference to the best law above which a law is disfavoured [-] (Kass & Raftery
1995: "very strong" evidence, a Bayes factor above 150)."""

FORMAT = "contactlab-law-comparison-1"
"""Tag of the JSON layout of :meth:`LawComparison.to_dict`."""


def _fitted_quantities(fit):
    """``p``: the quantities the fit adjusted (law parameters, velocity, onset, offset)."""
    return fit.t.size - fit.quality.degrees_of_freedom


@dataclass(frozen=True)
class RankedLaw:
    """One candidate law: its fit, criterion and verdict."""

    fit: object
    """The :class:`~contactlab.inverse.fit_result.ContactFit`."""
    bic: float
    """``chi^2 + p ln n`` [-]."""
    delta_bic: float
    """BIC minus the best law's [-] (0 for the best)."""
    notes: tuple
    """Warnings of the fit (identifiability, convergence), as text."""

    @property
    def verdict(self):
        """``"rejected"`` (the data reject it, :attr:`FitQuality.consistent` is False),
        ``"disfavoured"`` (consistent but ``delta_bic`` above
        :data:`DISFAVOURED_DELTA_BIC`), ``"best"`` or ``"supported"``."""
        if not self.fit.quality.consistent:
            return "rejected"
        if self.delta_bic > DISFAVOURED_DELTA_BIC:
            return "disfavoured"
        return "best" if self.delta_bic == 0.0 else "supported"

    def to_dict(self):
        quality = self.fit.quality
        return {
            "law": self.fit.law_name,
            "verdict": self.verdict,
            "fitted_quantities": _fitted_quantities(self.fit),
            "bic [-]": self.bic,
            "delta_bic [-]": self.delta_bic,
            "reduced_chi_squared [-]": quality.reduced_chi_squared,
            "consistent": quality.consistent,
            "reasons": quality.reasons,
            "notes": list(self.notes),
            "fit": self.fit.to_dict(),
        }


@dataclass(frozen=True)
class LawComparison:
    """Candidate laws fitted to one trace, best (smallest BIC) first."""

    ranking: tuple
    """:class:`RankedLaw` items, smallest BIC first."""
    samples: int
    """Fitted samples ``n`` (the same for every law)."""

    @property
    def best(self):
        """The :class:`~contactlab.inverse.fit_result.ContactFit` of the smallest BIC."""
        return self.ranking[0].fit

    @property
    def rejected(self):
        """Names of the laws the data reject."""
        return [r.fit.law_name for r in self.ranking if r.verdict == "rejected"]

    def to_dict(self):
        """JSON-ready: criterion, the best law, the rejected ones, one entry per law."""
        return {
            "format": FORMAT,
            "criterion": "BIC = chi^2 + p ln n",
            "samples": self.samples,
            "best": self.best.law_name,
            "best_consistent": self.best.quality.consistent,
            "rejected": self.rejected,
            "laws": [r.to_dict() for r in self.ranking],
        }

    def summary(self):
        """The ranking as a text table, then the best fit's :meth:`ContactFit.summary`."""
        lines = [
            f"laws ranked by BIC = chi^2 + p ln n ({self.samples} samples):",
            f"  {'law':<14} {'p':>2} {'reduced chi^2':>14} {'delta BIC':>11}  verdict",
        ]
        for r in self.ranking:
            lines.append(
                f"  {r.fit.law_name:<14} {_fitted_quantities(r.fit):>2} "
                f"{r.fit.quality.reduced_chi_squared:>14.4g} {r.delta_bic:>11.4g}  {r.verdict}"
            )
            lines += [f"      {reason}" for reason in r.fit.quality.reasons]
            lines += [f"      note: {note}" for note in r.notes]
        if not self.best.quality.consistent:
            lines.append("no candidate law is consistent with the trace")
        lines += ["", f"best: {self.best.summary()}"]
        return "\n".join(lines)


def _fit_recording_warnings(*args, **kwargs):
    """A fit and the texts of its identifiability warnings (kept in the result, not issued
    once per law). A :class:`FitQualityWarning` is not kept: the entry's verdict and
    ``reasons`` say the same."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", IdentifiabilityWarning)
        warnings.simplefilter("ignore", FitQualityWarning)
        fit = fit_contact(*args, **kwargs)
    for w in caught:
        if not issubclass(w.category, IdentifiabilityWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    notes = tuple(str(w.message) for w in caught if issubclass(w.category, IdentifiabilityWarning))
    return fit, notes


@with_one_blas_thread
def compare_laws(t, signal, grain, sensor, laws=None, velocity=None, **fit_options):
    """Fit every candidate law to a trace and rank them by BIC.

    Parameters
    ----------
    t, signal, grain, sensor, velocity
        As for :func:`~contactlab.inverse.fit.fit_contact`.
    laws : str or sequence of str, optional
        Keys of :data:`FIT_MODELS` (default all of them; a name given twice is fitted
        once).
    **fit_options
        The keywords of :func:`~contactlab.inverse.fit.fit_contact` named in
        :data:`COMPARED_FIT_OPTIONS` (``baseline_window``, ``window``, ``max_nfev``,
        ``crosstalk``), passed to every fit; the noise window and the fitted samples
        found for the first law are used for every law.

    Returns
    -------
    LawComparison

    Raises
    ------
    ParameterError
        As :func:`~contactlab.inverse.fit.fit_contact`, an unknown law, or a keyword not
        in :data:`COMPARED_FIT_OPTIONS`.

    Notes
    -----
    The fits' :class:`IdentifiabilityWarning` messages are kept in each entry's
    ``notes`` instead of being issued; a :class:`FitQualityWarning` is not issued either
    (each entry's ``verdict`` and ``reasons`` hold it).
    """
    unknown = sorted(set(fit_options) - set(COMPARED_FIT_OPTIONS))
    if unknown:
        raise ParameterError(
            f"compare_laws takes no {', '.join(unknown)}; its fit options are "
            f"{', '.join(COMPARED_FIT_OPTIONS)}"
        )
    laws = tuple(FIT_MODELS) if laws is None else check_names("laws", laws, tuple(FIT_MODELS))
    first, notes = _fit_recording_warnings(
        t, signal, grain, sensor, laws[0], velocity=velocity, **fit_options
    )
    same = {
        **fit_options,
        "baseline_window": first.quality.noise_window,
        "window": (float(first.t[0]), float(first.t[-1])),
    }
    fits = [(first, notes)]
    fits += [
        _fit_recording_warnings(t, signal, grain, sensor, law, velocity=velocity, **same)
        for law in laws[1:]
    ]
    n = first.t.size
    bics = [
        fit.quality.reduced_chi_squared * fit.quality.degrees_of_freedom
        + _fitted_quantities(fit) * math.log(n)
        for fit, _ in fits
    ]
    best = min(bics)
    ranking = sorted(
        (
            RankedLaw(fit, bic, bic - best, notes)
            for (fit, notes), bic in zip(fits, bics, strict=True)
        ),
        key=lambda r: r.bic,
    )
    return LawComparison(tuple(ranking), n)
