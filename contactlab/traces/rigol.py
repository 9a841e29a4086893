"""Rigol CSV in its two layouts.

``"rigol-sequence"`` (DS1000Z and later)::

    X,CH1,Start,Increment,
    Sequence,Volt,-6.000000e-03,2.000000e-06
    0,1.20e-02,
    1,1.16e-02,

Time is ``Start + n * Increment`` [s] with ``n`` the sample number in column 0, which need
not start at 0; the sample numbers must be consecutive integers (the header's single
increment describes nothing else). ``"rigol-seconds"`` (older models)::

    X,CH1
    Second,Volt
    -6.000000e-03,1.20e-02

keeps the file's time column. Both may hold several channels (``X,CH1,CH2,...``); rows
may end with a comma. Time is relative to the trigger.
"""

import numpy as np

from contactlab.errors import ParameterError
from contactlab.traces.checks import UNIFORM_RTOL, grid_deviation, uniform_interval
from contactlab.traces.textblock import Block, Column, Sequence, named_columns, require_unit
from contactlab.traces.textwrite import write_text
from contactlab.traces.units import parse_unit

__all__ = ["parse_seconds", "parse_sequence", "sniff_seconds", "sniff_sequence"]
__all__ += ["write_seconds", "write_sequence"]

_SECONDS = parse_unit("s")


def sniff_sequence(head):
    """``X,...`` then ``Sequence,...``."""
    return head.cells(0)[:1] == ["X"] and head.cells(1)[:1] == ["Sequence"]


def sniff_seconds(head):
    """``X,...`` then ``Second,...``."""
    return head.cells(0)[:1] == ["X"] and head.cells(1)[:1] == ["Second"]


def _float(head, line, text, what):
    try:
        value = float(text)
    except ValueError:
        raise head.fail(line, f"{what} {text!r} is not a number") from None
    if not np.isfinite(value):
        raise head.fail(line, f"{what} {text!r} is not finite")
    return value


def parse_sequence(head):
    """Describe the data of a Rigol ``X,CH1,Start,Increment`` file.

    Returns
    -------
    Block
    """
    names, units = head.cells(0), head.cells(1)
    if "Start" not in names or "Increment" not in names:
        raise head.fail(1, "Rigol sequence header lacks 'Start' or 'Increment'")
    i_start, i_increment = names.index("Start"), names.index("Increment")
    if max(i_start, i_increment) >= len(units) or min(i_start, i_increment) < 2:
        raise head.fail(2, "need Sequence, a unit per channel, then the Start and Increment values")
    start = _float(head, 2, units[i_start], "Start")
    increment = _float(head, 2, units[i_increment], "Increment")
    if increment <= 0:
        raise head.fail(2, f"Increment {increment!r} must be > 0")
    return Block(
        fmt="rigol-sequence",
        first_line=3,
        time=Column("Sequence", 0, _SECONDS),
        channels=tuple(
            Column(name, i, require_unit(head, 2, units[i], "value"))
            for i, name in enumerate(names[: min(i_start, i_increment)])
            if i > 0
        ),
        channel_line=1,
        max_fields=min(i_start, i_increment) + 1,  # the columns, a trailing delimiter
        sequence=Sequence(start, increment),
        metadata={"header": {"lines": list(head.lines[:2])}},
    )


def parse_seconds(head):
    """Describe the data of a Rigol ``X,CH1`` / ``Second,Volt`` file.

    Returns
    -------
    Block
    """
    return named_columns(head, "rigol-seconds", 3, strict=False)


def _volts(trace):
    if trace.unit != "V":
        raise ParameterError(f"Rigol CSV stores volts; the trace is in {trace.unit!r}")


def write_sequence(path, trace, *, first_index=0, start=None, increment=None, channel="CH1"):
    """Write a volt trace in the Rigol ``X,CH1,Start,Increment`` layout.

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
        Uniformly sampled, in V.
    first_index : int, default 0
        Sample number of the first row.
    start, increment : float, optional
        ``Start`` and ``Increment`` [s]; default from the trace, ``Start`` being the time
        of sample number 0. They must reproduce the trace's times.
    channel : str, default "CH1"
    """
    _volts(trace)
    if isinstance(first_index, bool) or not isinstance(first_index, int | np.integer):
        raise ParameterError(f"first_index must be an integer sample number; got {first_index!r}")
    increment = uniform_interval(trace) if increment is None else float(increment)
    start = float(trace.t[0] - first_index * increment if start is None else start)
    deviation = grid_deviation(trace.t, start, increment, first_index)
    if not deviation <= UNIFORM_RTOL * increment:
        raise ParameterError(
            f"start={start!r} s and increment={increment!r} s miss the trace's times by up "
            f"to {deviation!r} s"
        )
    header = [f"X,{channel},Start,Increment,", f"Sequence,Volt,{start!r},{increment!r}"]
    n = np.arange(first_index, first_index + len(trace))
    write_text(path, header, [n, trace.values], trailing=True)


def write_seconds(path, trace, *, channel="CH1"):
    """Write a volt trace in the older Rigol ``X,CH1`` / ``Second,Volt`` layout."""
    _volts(trace)
    write_text(path, [f"X,{channel}", "Second,Volt"], [trace.t, trace.values])
