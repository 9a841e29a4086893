"""Writing text layouts: header lines, then delimited columns, in checked units."""

import pandas as pd

from contactlab.errors import ParameterError
from contactlab.traces.units import parse_unit

__all__ = ["output_units", "write_text"]


def write_text(path, header_lines, columns, *, delimiter=",", trailing=False):
    """Write header lines, then columns as delimited rows.

    Floats are written as their shortest round-trip repr, so a reader gets the same
    doubles back. Pre-formatted string columns are written as they are.

    Parameters
    ----------
    path : str or os.PathLike
    header_lines : sequence of str
    columns : sequence of array_like
    delimiter : str, default ","
    trailing : bool, default False
        End every data row with a delimiter (Rigol does).
    """
    frame = pd.DataFrame(dict(enumerate(columns)))
    if trailing:
        frame[len(columns)] = ""
    with open(path, "w", encoding="utf-8", newline="") as fh:
        fh.writelines(line + "\n" for line in header_lines)
        frame.to_csv(fh, header=False, index=False, sep=delimiter, lineterminator="\n")


def output_units(trace, time_unit="s", value_unit=None):
    """Parsed units a writer converts to, checked against the trace.

    Parameters
    ----------
    trace : Trace
    time_unit : str
        A time unit such as ``"s"`` or ``"ms"``.
    value_unit : str or None
        A unit with the trace's SI base (``"mV"`` for a volt trace); ``None`` for the
        trace's own unit.

    Returns
    -------
    (Unit, Unit)

    Raises
    ------
    ParameterError
        If a unit is unknown or does not match the trace.
    """
    t_unit = parse_unit(time_unit)
    v_unit = parse_unit(trace.unit if value_unit is None else value_unit)
    if t_unit is None or not t_unit.is_time:
        raise ParameterError(f"time_unit must be a unit of time such as 'ms'; got {time_unit!r}")
    if v_unit is None or v_unit.si != trace.unit:
        raise ParameterError(
            f"value_unit must be a unit of {trace.unit!r}, e.g. 'm{trace.unit}'; got {value_unit!r}"
        )
    return t_unit, v_unit
