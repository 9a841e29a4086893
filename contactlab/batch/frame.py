"""Column checks of the batch solvers' input frames.

A batch frame has one row per impact and one column per parameter, each named with its
unit (``m1 [kg]``, ``v0 [m/s]``, ...). Every column is checked before any impact is
solved; the first bad row of the first bad column raises a
:class:`~contactlab.errors.ParameterError` that names both, and nothing is dropped,
clipped or filled in.
"""

from dataclasses import dataclass

import numpy as np
import pandas as pd

from contactlab.errors import ParameterError
from contactlab.quantities import quantity

__all__ = ["Column", "check_frame", "chunk_bounds", "impact_columns", "input_column"]


@dataclass(frozen=True)
class Column:
    """One input column: its name (with unit) and the values it may hold.

    Attributes
    ----------
    name : str
        Column name with its unit, e.g. ``"k1 [N/m]"``.
    meaning : str
        What the column holds, for error messages.
    low_open : bool
        ``True``: values must be ``> 0``; ``False``: ``>= 0``.
    allow_inf : bool
        Whether ``+inf`` is allowed (an immovable wall's ``k1``).
    signed : bool
        Whether any finite number is allowed (``low_open`` then does not apply).
    below : float
        Values must be below it (an angle of incidence below ``pi/2``).
    """

    name: str
    meaning: str
    low_open: bool = True
    allow_inf: bool = False
    signed: bool = False
    below: float = np.inf

    def bad_rows(self, values):
        """Boolean mask of the values this column refuses."""
        with np.errstate(invalid="ignore"):
            bad = np.isnan(values)
            if not self.signed:
                bad |= values <= 0.0 if self.low_open else values < 0.0
            if self.below < np.inf:
                bad |= values >= self.below
        if not self.allow_inf:
            bad |= np.isinf(values)
        return bad

    def rule(self):
        """The allowed range, in words."""
        if self.signed:
            return "a finite number"
        bound = "> 0" if self.low_open else ">= 0"
        if self.below < np.inf:
            bound += f" and < {self.below!r}"
        return f"a number {bound}" + (" (inf allowed)" if self.allow_inf else ", finite")


def _row_label(frame, position):
    label = frame.index[position]
    return f"row {position} (index {label!r})"


def check_frame(frame, columns, chunk=1_000_000):
    """Check the parameter columns of a batch frame; return them as float arrays.

    Parameters
    ----------
    frame : pandas.DataFrame
        One row per impact.
    columns : sequence of Column
        The columns the batch solver needs.
    chunk : int, default 1 000 000
        Rows checked at a time (the masks of a check are ``chunk`` bytes, not one per
        row of the frame).

    Returns
    -------
    dict
        Column name -> float64 array (a view of the frame's data where it already is
        float64, otherwise a converted copy).

    Raises
    ------
    ParameterError
        If ``frame`` is not a DataFrame, a column is missing or not numeric, or a value
        is out of its range; the message names the column, the first bad row (position
        and index label) and its value.
    """
    if not isinstance(frame, pd.DataFrame):
        raise ParameterError(f"frame must be a pandas DataFrame; got {type(frame).__name__}")
    missing = [c.name for c in columns if c.name not in frame.columns]
    if missing:
        needed = ", ".join(repr(c.name) for c in columns)
        raise ParameterError(f"frame has no column(s) {missing}; a batch needs {needed}")
    arrays = {}
    for column in columns:
        series = frame[column.name]
        if series.dtype == bool or not pd.api.types.is_numeric_dtype(series.dtype):
            raise ParameterError(
                f"column {column.name!r} ({column.meaning}) must hold numbers; "
                f"its dtype is {series.dtype}"
            )
        values = series.to_numpy(dtype=float)
        for lo in range(0, values.size, chunk):
            bad = np.flatnonzero(column.bad_rows(values[lo : lo + chunk]))
            if bad.size:
                position = lo + int(bad[0])
                raise ParameterError(
                    f"column {column.name!r} ({column.meaning}) must be {column.rule()}; "
                    f"{_row_label(frame, position)} holds {float(values[position])!r}"
                )
        arrays[column.name] = values
    return arrays


def chunk_bounds(rows, chunk):
    """``(start, stop)`` of consecutive chunks of at most ``chunk`` rows."""
    return [(lo, min(lo + chunk, rows)) for lo in range(0, rows, chunk)]


def input_column(name, **rules):
    """The :class:`Column` of the quantity ``name`` of :mod:`contactlab.quantities` (its
    column name and meaning), with the value ``rules`` of :class:`Column`."""
    entry = quantity(name)
    return Column(entry.column, entry.meaning, **rules)


def impact_columns(*law):
    """A batch's input columns: the sensor and the grain, the law's ``law`` columns, the
    impact speed (in that order, the order of the kernels' arguments)."""
    return (
        input_column("m1", allow_inf=True),
        input_column("k1", allow_inf=True),
        input_column("c1", low_open=False),
        input_column("m2"),
        *law,
        input_column("v0"),
    )
