"""Strict JSON (RFC 8259) from results that may hold NaN or infinity.

``json.dumps`` writes ``NaN`` and ``Infinity``, which are not JSON: strict parsers
(JavaScript's ``JSON.parse``, ``jq``, Go, Rust's serde) refuse the whole file. Here a
non-finite number becomes ``null`` and the reason goes beside it: a top-level
``"null_reasons"`` object maps the path of every such value to what it was, e.g.
``{"sensor.resonance [Hz]": "+inf (not a finite number; JSON has none)"}``.
"""

import json
import math

import numpy as np

__all__ = ["NULL_REASONS", "dumps", "finite_or_null"]

NULL_REASONS = "null_reasons"
"""Top-level key listing why each ``null`` of a document is null."""


def _reason(x):
    if math.isnan(x):
        return "NaN (not defined for this case; JSON has no NaN)"
    return f"{'+' if x > 0 else '-'}inf (not a finite number; JSON has no infinity)"


def _clean(obj, path, reasons):
    if isinstance(obj, dict):
        return {k: _clean(v, f"{path}.{k}" if path else str(k), reasons) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [_clean(v, f"{path}[{i}]", reasons) for i, v in enumerate(obj)]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        reasons[path] = _reason(obj)
        return None
    return obj


def finite_or_null(data):
    """``data`` with every NaN and infinity replaced by ``None``, and the reasons.

    Parameters
    ----------
    data : dict, list or scalar
        Nested dicts, lists, tuples, numpy arrays and scalars.

    Returns
    -------
    (object, dict)
        The cleaned data (numpy scalars and arrays as Python numbers and lists) and
        ``{path: reason}`` for every value replaced.
    """
    reasons = {}
    return _clean(data, "", reasons), reasons


def dumps(data, indent=2):
    """``data`` as strict JSON text: NaN and infinity as ``null``, reasons beside.

    Parameters
    ----------
    data : object
        What :func:`finite_or_null` accepts.
    indent : int, default 2
        Indentation.

    Returns
    -------
    str
        JSON that strict parsers accept (``json.dumps`` with ``allow_nan=False``). A dict
        gains a ``"null_reasons"`` key when some value was replaced; any other document
        is wrapped as ``{"value": ..., "null_reasons": ...}`` in that case.
    """
    clean, reasons = finite_or_null(data)
    if reasons:
        if isinstance(clean, dict):
            clean = {**clean, NULL_REASONS: reasons}
        else:
            clean = {"value": clean, NULL_REASONS: reasons}
    return json.dumps(clean, indent=indent, allow_nan=False)
