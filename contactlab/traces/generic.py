"""Generic CSV: a header row naming each column with its unit, then numbers.

Layout::

    # instrument: synthetic two-mass model        <- optional "# key: value" comments
    t [s],sensor [V]                              <- every column carries a unit
    -1.0e-05,0.0012
    ...

Units are read from ``name [unit]`` or ``name (unit)`` (``t [s]``, ``Time (ms)``,
``Voltage [V]``, ``(mV)``). Exactly one column has a time unit; every other column is a
channel in V, N or A (with SI prefixes). Cells are separated by commas, or by tabs or
semicolons when the header uses them. A column without a unit is an error: the reader
does not guess.

This is the fallback for text that matches no instrument layout, so its header errors
say that no instrument layout was recognised.
"""

import re

from contactlab.traces.textblock import Block, Column, require_unit
from contactlab.traces.textwrite import output_units, write_text
from contactlab.traces.units import parse_unit
from contactlab.validation import check_choice

__all__ = ["parse_header", "sniff", "write"]

_CELL = re.compile(r"(?P<name>.*?)\s*(?:\[(?P<square>[^\[\]()]*)\]|\((?P<round>[^\[\]()]*)\))")


def sniff(head):
    """Any text file: the generic layout is the fallback for text."""
    return head.is_text


def _delimiter(line):
    if "\t" in line:
        return "\t"
    return ";" if ";" in line and "," not in line else ","


def _split_name(head, line, cell):
    match = _CELL.fullmatch(cell)
    what = "generic CSV header (no instrument layout recognised)"
    if cell.count("[") + cell.count("(") > 1:
        raise head.fail(line, f"{what}: column {cell!r} has more than one unit (mixed units)")
    if match is None:
        raise head.fail(line, f"{what}: column {cell!r} has no unit; write it as e.g. 't [s]'")
    unit = match["square"] if match["square"] is not None else match["round"]
    return match["name"] or cell, unit


def parse_header(head):
    """Describe the data block of a generic CSV file.

    Returns
    -------
    Block
    """
    comments = {}
    index = 0
    while index < len(head.lines) and head.lines[index].lstrip().startswith("#"):
        key, sep, value = (part.strip() for part in head.lines[index].lstrip()[1:].partition(":"))
        comments[key if sep else f"comment {index + 1}"] = value if sep else key
        index += 1
    if index >= len(head.lines):
        raise head.fail(index + 1, "empty file" if index == 0 else "no header row after comments")
    line = index + 1
    delimiter = _delimiter(head.lines[index])
    cells = head.cells(index, delimiter)
    named = [_split_name(head, line, cell) for cell in cells]
    times = [i for i, (_, unit) in enumerate(named) if _is_time(unit)]
    if len(times) != 1:
        raise head.fail(line, f"need exactly one time column (unit s, ms, ...); found {len(times)}")
    columns = [
        Column(name, i, require_unit(head, line, unit, "time" if i in times else "value"))
        for i, (name, unit) in enumerate(named)
    ]
    return Block(
        fmt="generic",
        first_line=line + 1,
        time=columns[times[0]],
        channels=tuple(c for c in columns if c.index != times[0]),
        channel_line=line,
        n_fields=len(cells),
        delimiter=delimiter,
        metadata={
            "instrument": comments.get("instrument"),
            "trigger_time": None,
            "header": {"comments": comments, "columns": cells},
        },
    )


def _is_time(text):
    unit = parse_unit(text)
    return unit is not None and unit.is_time


def write(path, trace, *, time_unit="s", value_unit=None, name=None, brackets="[]", comments=None):
    """Write a trace as generic CSV.

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    time_unit : str, default "s"
        Unit of the time column (``"ms"``, ``"us"``, ...).
    value_unit : str, optional
        Unit of the values (``"mV"``); default the trace's SI unit.
    name : str, optional
        Channel name; default ``"force"`` for newtons, else ``"value"``.
    brackets : {"[]", "()"}
        How units are written: ``t [s]`` or ``t (s)``.
    comments : dict, optional
        ``# key: value`` lines written before the header (e.g. provenance).
    """
    t_unit, v_unit = output_units(trace, time_unit, value_unit)
    name = name or ("force" if trace.unit == "N" else "value")
    left, right = check_choice("brackets", brackets, ("[]", "()"))
    header = [f"# {key}: {value}" for key, value in (comments or {}).items()]
    header.append(f"t {left}{t_unit.text}{right},{name} {left}{v_unit.text}{right}")
    write_text(path, header, [t_unit.from_si(trace.t), v_unit.from_si(trace.values)])
