"""Golden references checked by name: the store, and comparisons at regression tolerances.

:class:`GoldenStore` checks a run against a reference (a
:class:`~contactlab.testing.golden_trace.GoldenTrace`) by name. References are written
only on request (``update=True``; in pytest, ``--contactlab-update-golden``), and every
write is recorded in :attr:`GoldenStore.log`; a missing reference fails with a message
saying how to create it. Nothing is rewritten silently. Comparisons are
:func:`contactlab.compare.compare`'s, quantity by quantity, at :data:`REGRESSION_RTOL`
unless told otherwise.
"""

import math
from pathlib import Path

from contactlab.compare import QUANTITIES, compare
from contactlab.entry_checks import check_flag
from contactlab.errors import ParameterError, TraceFormatError
from contactlab.testing.golden_trace import (
    DEFAULT_MAX_SAMPLES,
    REGRESSION_RTOL,
    UPDATE_FLAG,
    GoldenMissingError,
    GoldenTrace,
    reference_paths,
)
from contactlab.validation import check_count, check_path

__all__ = ["GoldenStore", "compare_impacts", "regression_tolerances"]

_LABELS = ("this run", "golden")
"""Column names of the two sides in a golden comparison's table."""


def regression_tolerances(tolerances=None):
    """Tolerances for :func:`contactlab.compare.compare`: every quantity at
    :data:`REGRESSION_RTOL`, updated with ``tolerances`` (quantity name -> tolerance)."""
    if tolerances is not None and not isinstance(tolerances, dict):
        raise ParameterError(
            f"tolerances must be a dict of quantity -> tolerance; got {tolerances!r}"
        )
    return {**dict.fromkeys(QUANTITIES, REGRESSION_RTOL), **(tolerances or {})}


def compare_impacts(actual, reference, tolerances=None, align=None, labels=("actual", "reference")):
    """Compare an impact with a reference at regression tolerances; never raises on a mismatch.

    Delegates to :func:`contactlab.compare.compare` after reading ``actual`` on the
    reference's grid when the reference is a :class:`GoldenTrace`.

    Parameters
    ----------
    actual, reference : ImpactResult, GoldenTrace or dem_check Trace
        The impact under test and its reference.
    tolerances : dict, optional
        Quantity name (from :data:`contactlab.compare.QUANTITIES`) -> tolerance, replacing
        :data:`REGRESSION_RTOL` for that quantity.
    align : {None, "onset", "xcorr"}, default None
        Time alignment of the waveforms (None: the time axes as they are, right for a
        rerun; align a measured trace with ``"onset"``).
    labels : (str, str)
        Names of the two sides in the table.

    Returns
    -------
    contactlab.compare.Comparison
        ``.passed``, ``.failed`` and ``.table``; ``str()`` gives the table.

    Raises
    ------
    ParameterError
        For an unknown quantity name, or signals in different units.
    """
    units = [getattr(side, "unit", "N") for side in (actual, reference)]
    if units[0] != units[1]:
        raise ParameterError(
            f"cannot compare signals in {units[0]!r} with signals in {units[1]!r}; convert "
            "the trace to force first (contactlab.traces.to_force)"
        )
    if isinstance(reference, GoldenTrace) and not isinstance(actual, GoldenTrace):
        actual = reference.on_grid(actual)
    return compare(actual, reference, regression_tolerances(tolerances), align, labels=labels)


def _flatten(value, prefix=""):
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            out.update(_flatten(item, f"{prefix}{key}."))
        return out
    return {prefix.rstrip("."): value}


def _same(a, b):
    both_nan = isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)
    return a == b or both_nan


def _setup_changes(old, new):
    """``"key: old -> new"`` for every set-up entry that differs."""
    old, new = _flatten(old), _flatten(new)
    return [
        f"{key}: {old.get(key, '(absent)')!r} -> {new.get(key, '(absent)')!r}"
        for key in sorted(old.keys() | new.keys())
        if not _same(old.get(key), new.get(key))
    ]


class GoldenStore:
    """Golden references in one directory, checked by name and written only on request.

    Parameters
    ----------
    directory : str or os.PathLike
        Folder of the reference files.
    update : bool, default False
        Write references that are missing, unreadable, fail the comparison or were made
        from another set-up (references that still match are left untouched, so an
        update run does not churn files). Otherwise a missing reference fails.
    log : list of str, optional
        List to which a line is appended for every file written (the pytest plugin
        prints it at the end of the session). Default: a new list, :attr:`log`.
    max_samples : int, default :data:`DEFAULT_MAX_SAMPLES`
        Samples kept per written reference.
    """

    def __init__(self, directory, update=False, log=None, max_samples=DEFAULT_MAX_SAMPLES):
        check_path("directory", directory)
        self.directory = Path(directory)
        self.update = check_flag("update", update)
        if log is not None and not (
            isinstance(log, list) and all(isinstance(line, str) for line in log)
        ):
            raise ParameterError(f"log must be a list of text lines (or None); got {log!r}")
        self.log = [] if log is None else log
        self.max_samples = check_count("max_samples", max_samples, low=2)

    def check(self, name, impact, tolerances=None):
        """Compare an impact with the reference ``name`` (or write it, when updating).

        Parameters
        ----------
        name : str
            Reference name (file stem in :attr:`directory`).
        impact : ImpactResult or dem_check Trace
            The impact under test.
        tolerances : dict, optional
            Quantity -> tolerance, replacing :data:`REGRESSION_RTOL` (see
            :func:`compare_impacts`).

        Returns
        -------
        contactlab.compare.Comparison
            The comparison with the reference (after writing it, when updating).

        Raises
        ------
        GoldenMissingError
            If the reference does not exist and ``update`` is False.
        AssertionError
            If the impact differs from the reference and ``update`` is False; the message
            holds the comparison table and the set-up changes.
        """
        candidate = GoldenTrace.of(name, impact, self.max_samples)
        try:
            reference = GoldenTrace.read(self.directory, name)
        except GoldenMissingError:
            if not self.update:
                raise
            return self._write(candidate, impact, tolerances, "created", "it did not exist")
        except TraceFormatError as exc:
            if not self.update:
                raise
            return self._write(candidate, impact, tolerances, "rewrote", f"unreadable: {exc}")
        comparison = compare_impacts(impact, reference, tolerances, labels=_LABELS)
        changes = _setup_changes(reference.setup, candidate.setup)
        if not self.update:
            if not comparison.passed:
                raise AssertionError(self._failure(reference, comparison, changes))
            return comparison
        if comparison.passed and not changes:
            return comparison
        reason = "; ".join(
            part
            for part in (
                f"outside tolerance: {', '.join(comparison.failed)}" if comparison.failed else "",
                f"set-up changed: {', '.join(changes)}" if changes else "",
            )
            if part
        )
        return self._write(candidate, impact, tolerances, "rewrote", reason)

    def _write(self, candidate, impact, tolerances, verb, reason):
        json_path, npz_path = candidate.write(self.directory)
        self.log.append(f"{verb} {json_path} and {npz_path.name} ({reason})")
        return compare_impacts(impact, candidate, tolerances, labels=_LABELS)

    def _failure(self, reference, comparison, changes):
        json_path, _ = reference_paths(self.directory, reference.name)
        meta = reference.metadata
        lines = [
            f"impact differs from golden reference {reference.name!r} ({json_path}, created "
            f"{meta.get('created')} with contactlab {meta.get('contactlab_version')}):",
            str(comparison),
        ]
        if changes:
            lines.append("set-up changes since the reference: " + "; ".join(changes))
        lines.append(
            f"If the change is intended, rerun pytest with {UPDATE_FLAG}, review the "
            "rewritten files and commit them."
        )
        return "\n".join(lines)
