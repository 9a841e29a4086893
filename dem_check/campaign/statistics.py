"""Population statistics of a campaign and regressions against joined metadata.

Statistics use the impacts with status ``"ok"`` only (the others have no reconstruction
to describe); the counts say how many that is per file. Regressions are ordinary least
squares of one response on one predictor at a time (``scipy.stats.linregress``): a lab
asking "does peak force rise with moisture?" wants that slope, its standard error and
its p-value, not a joint model of every column.
"""

import os
import re

import numpy as np
import pandas as pd
from scipy import stats

from contactlab.errors import ParameterError
from contactlab.quantities import columns
from dem_check.campaign.detection import ANALYSED

__all__ = [
    "QUANTILES",
    "RESPONSES",
    "STATISTIC_COLUMNS",
    "join_metadata",
    "population_statistics",
    "regressions",
    "statistic_quantities",
]

QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
"""Quantiles reported for every quantity [-]."""

STATISTIC_COLUMNS = (
    "group",
    "quantity",
    "count",
    "mean",
    "std",
    "min",
    "q05",
    "q25",
    "median",
    "q75",
    "q95",
    "max",
)
"""Columns of the statistics table: ``group`` is a file or ``"all"``; values are in the
quantity's unit (named in ``quantity``); ``std`` is the sample standard deviation."""

RESPONSES = ("peak_contact_force [N]", "contact_time [s]")
"""Responses regressed on every numeric metadata column."""

_MEASURED = columns(
    "peak_sensor_force",
    "sensor_response_time",
    "impulse",
    "peak_contact_force",
    "contact_time",
    "velocity_change",
)
_KEYS = ("file", "impact")


def statistic_quantities(impacts):
    """The numeric per-impact quantities present in ``impacts`` (fitted values too)."""
    fitted = [
        c
        for c in impacts.columns
        if c.startswith("fit_") and not re.search(r"_(low|high|identifiable)( \[|$)", c)
    ]
    return [c for c in _MEASURED if c in impacts.columns] + fitted


def _describe(frame, group, quantities):
    rows = []
    for quantity in quantities:
        values = pd.to_numeric(frame[quantity], errors="coerce").dropna()
        q = values.quantile(list(QUANTILES)).to_numpy() if len(values) else [np.nan] * 5
        rows.append(
            [
                group,
                quantity,
                int(values.size),
                values.mean(),
                values.std(ddof=1),
                values.min(),
                *q,
                values.max(),
            ]
        )
    return rows


def population_statistics(impacts):
    """Mean, spread and quantiles of every quantity, per file and over all files.

    Parameters
    ----------
    impacts : pandas.DataFrame
        The campaign's impact table.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`STATISTIC_COLUMNS`; one row per (group, quantity), the groups
        being each file with ok impacts, then ``"all"``.
    """
    ok = impacts[impacts["status"].isin(ANALYSED)] if len(impacts) else impacts
    quantities = statistic_quantities(impacts) if len(impacts) else []
    rows = []
    for file, frame in ok.groupby("file", sort=False):
        rows += _describe(frame, file, quantities)
    if len(ok):
        rows += _describe(ok, "all", quantities)
    return pd.DataFrame(rows, columns=list(STATISTIC_COLUMNS))


def _read_metadata(metadata):
    if isinstance(metadata, pd.DataFrame):
        return metadata.copy(), "the metadata table"
    path = os.fspath(metadata)
    try:
        return pd.read_csv(path), path
    except (OSError, ValueError) as exc:  # pandas' ParserError is a ValueError
        raise ParameterError(f"metadata: cannot read {path!r} as CSV: {exc}") from None


def join_metadata(impacts, metadata):
    """The impacts with the metadata's columns joined, and notes on what did not match.

    Parameters
    ----------
    impacts : pandas.DataFrame
        The impact table (columns ``file`` and ``impact``).
    metadata : str, os.PathLike or pandas.DataFrame
        A CSV (or table) with a ``file`` column naming each record by its path as given
        or its file name, an optional ``impact`` column (0-based index of the impact in
        its file) for per-impact values, and any other columns (e.g. ``moisture [%]``,
        ``drop_height [m]``).

    Returns
    -------
    joined : pandas.DataFrame
    notes : list of str
        Records without metadata and metadata rows naming no record.

    Raises
    ------
    ParameterError
        An unreadable CSV, no ``file`` column, a column named like an impact column,
        or two rows for the same key.
    """
    meta, name = _read_metadata(metadata)
    if "file" not in meta.columns:
        raise ParameterError(
            f"metadata: {name} has no 'file' column (columns: {', '.join(map(str, meta.columns))})"
        )
    keys = [k for k in _KEYS if k in meta.columns]
    clash = sorted(set(meta.columns) & set(impacts.columns) - set(keys))
    if clash:
        raise ParameterError(f"metadata: columns {clash} would replace the impacts' own columns")
    duplicated = meta.duplicated(keys)
    if duplicated.any():
        row = int(np.flatnonzero(duplicated)[0])
        raise ParameterError(
            f"metadata: {name} has two rows for {meta.loc[row, keys].to_dict()} (row {row + 2})"
        )
    names = {f: f for f in impacts["file"].unique()}
    names.update({os.path.basename(f): f for f in impacts["file"].unique()})
    meta = meta.assign(file=[names.get(str(f), str(f)) for f in meta["file"]])
    joined = impacts.merge(meta, on=keys, how="left", validate="many_to_one")
    notes = [
        f"metadata: no row for {f}" for f in impacts["file"].unique() if f not in set(meta["file"])
    ]
    notes += [
        f"metadata: {f} names no record of the campaign"
        for f in meta["file"].unique()
        if f not in set(impacts["file"])
    ]
    return joined, notes


def _unit(column):
    found = re.search(r"\[(.*)\]\s*$", str(column))
    unit = found.group(1) if found else "-"
    return f"({unit})" if re.search(r"[/*]", unit) else unit


def regressions(joined, predictors):
    """Least-squares line of each response on each predictor, over the ok impacts.

    Parameters
    ----------
    joined : pandas.DataFrame
        Impacts with metadata columns (:func:`join_metadata`).
    predictors : sequence of str
        Numeric columns to regress on.

    Returns
    -------
    pandas.DataFrame
        Columns ``response``, ``predictor``, ``n``, ``slope``, ``slope_stderr``,
        ``slope_unit``, ``intercept``, ``r``, ``p_value`` and ``note`` (why a line was
        not fitted: fewer than 3 impacts with both values, or a constant predictor).
    """
    ok = joined[joined["status"].isin(ANALYSED)]
    rows = []
    for response in (r for r in RESPONSES if r in ok.columns):
        for predictor in predictors:
            x = pd.to_numeric(ok[predictor], errors="coerce").to_numpy(dtype=float)
            y = pd.to_numeric(ok[response], errors="coerce").to_numpy(dtype=float)
            both = np.isfinite(x) & np.isfinite(y)
            row = {
                "response": response,
                "predictor": predictor,
                "n": int(both.sum()),
                "slope_unit": f"{_unit(response)}/{_unit(predictor)}",
            }
            if both.sum() < 3:
                row["note"] = "fewer than 3 ok impacts with both values"
            elif np.ptp(x[both]) == 0.0:
                row["note"] = "the predictor is constant over the ok impacts"
            else:
                line = stats.linregress(x[both], y[both])
                row.update(
                    slope=line.slope,
                    slope_stderr=line.stderr,
                    intercept=line.intercept,
                    r=line.rvalue,
                    p_value=line.pvalue,
                    note="",
                )
            rows.append(row)
    columns = ["response", "predictor", "n", "slope", "slope_stderr", "slope_unit"]
    columns += ["intercept", "r", "p_value", "note"]
    return pd.DataFrame(rows, columns=columns)


def numeric_predictors(joined, metadata_columns):
    """The metadata columns that hold numbers (keys excepted)."""
    return [
        c for c in metadata_columns if c not in _KEYS and pd.api.types.is_numeric_dtype(joined[c])
    ]
