"""The data block every text layout shares, read into a :class:`Trace`.

A text layout module only reads its header (from
:class:`~contactlab.traces.texthead.Head`) and describes the data block that follows as a
:class:`Block`: where it starts, which column holds time (or a sample number), which hold
channels and in what units. :func:`read_block` then does the rest for every layout alike:
it parses the block (:func:`~contactlab.traces.textparse.parse_block`: a fast vectorised
path, an exact line parser for what it refuses) and validates with vectorised numpy: no
NaN, strictly increasing time, declared record length and sample interval honoured.

Rows map one to one to lines (no quoting, ``\\n`` line ends, blank lines kept), so a
sample index ``i`` is line ``first_line + i``.
"""

from dataclasses import dataclass, field

import numpy as np

from contactlab.traces.checks import UNIFORM_RTOL, check_samples, select_channel
from contactlab.traces.textparse import parse_block
from contactlab.traces.trace import Trace
from contactlab.traces.units import SI_VALUE_UNITS, Unit, parse_unit

__all__ = ["Block", "Column", "Sequence", "named_columns", "read_block", "require_unit"]


@dataclass(frozen=True)
class Column:
    """A column of the data block: its name, 0-based position and unit."""

    name: str
    index: int
    unit: Unit


@dataclass(frozen=True)
class Sequence:
    """Time given as ``start + n * increment`` [s], ``n`` read from the time column."""

    start: float
    increment: float


@dataclass(frozen=True)
class Block:
    """What a layout's header says about the data block that follows it."""

    fmt: str
    """Registry name of the layout."""
    first_line: int
    """1-based line of the first data row."""
    time: Column
    """Time column (the sample-number column when ``sequence`` is set)."""
    channels: tuple
    """The channel columns (:class:`Column`)."""
    channel_line: int
    """1-based line naming the channels (for a wrong-channel message)."""
    n_fields: int | None = None
    """Cells per data row, enforced; ``None`` when rows carry extra cells (a trailing
    delimiter, a header beside the data) that are then not checked."""
    max_fields: int | None = None
    """Most cells a data row may have when ``n_fields`` is ``None`` (a trailing delimiter
    included), the cells after the last column being empty: a row with more cells, or a
    value after the last column, is refused, since a decimal comma (``0,125``) splits a
    number into two cells that would otherwise read as ``0`` and a stray cell."""
    delimiter: str = ","
    sequence: Sequence | None = None
    record_length: tuple | None = None
    """``(samples, line)`` when the header declares the record length."""
    interval: tuple | None = None
    """``(sample interval [s], line)`` when the header declares it."""
    specials: dict = field(default_factory=dict)
    """Layout-specific cell tokens and their values, e.g. ``{"∞": inf}``."""
    metadata: dict = field(default_factory=dict)
    """Reader metadata (``instrument``, ``header``, ``trigger_time``, ...)."""


def require_unit(head, line, text, kind):
    """Parse a unit from a header, or fail naming the line.

    Parameters
    ----------
    head : Head
    line : int
        1-based line where ``text`` was found.
    text : str
        The unit as written.
    kind : {"time", "value"}
        A time unit must be seconds-based; a value unit one of V, N, A.
    """
    unit = parse_unit(text)
    expected = ("s",) if kind == "time" else SI_VALUE_UNITS
    if unit is None or unit.si not in expected:
        known = "/".join(expected)
        raise head.fail(line, f"{text!r} is not a known {kind} unit (expected {known})")
    return unit


def named_columns(head, fmt, first_line, *, strict=True, **fields):
    """The block of a layout whose line 1 names the columns and line 2 gives their units.

    Column 0 is time; the others are channels (Keysight, PicoScope, older Rigol).

    Parameters
    ----------
    head : Head
    fmt : str
        Registry name of the layout.
    first_line : int
        1-based line of the first data row.
    strict : bool, default True
        Whether data rows have exactly as many cells as line 1; if not, trailing empty
        cells (a trailing delimiter) are ignored.
    **fields
        Further :class:`Block` fields (``specials``, ``metadata``).
    """
    names, units = head.cells(0), head.cells(1)
    if not strict:
        names, units = (c[:-1] if c[-1:] == [""] else c for c in (names, units))
        fields.setdefault("max_fields", len(names) + 1)  # a trailing delimiter allowed
    if len(names) < 2 or len(units) != len(names) or "" in names:
        raise head.fail(2, f"need a unit for each of the {len(names)} columns of line 1")
    columns = [
        Column(name, i, require_unit(head, 2, unit, "value" if i else "time"))
        for i, (name, unit) in enumerate(zip(names, units, strict=True))
    ]
    metadata = {"header": {"lines": list(head.lines[:2])}, **fields.pop("metadata", {})}
    return Block(
        fmt=fmt,
        first_line=first_line,
        time=columns[0],
        channels=tuple(columns[1:]),
        channel_line=1,
        n_fields=len(names) if strict else None,
        metadata=metadata,
        **fields,
    )


def read_block(head, block, channel):
    """Read the selected channel of a data block into a :class:`Trace`.

    Parameters
    ----------
    head : Head
    block : Block
    channel : str, int or None
        See :func:`~contactlab.traces.checks.select_channel`.
    """
    path = head.path
    names = [c.name for c in block.channels]
    column = block.channels[select_channel(names, channel, path, f"line {block.channel_line}")]
    start = block.first_line - 1
    if start >= len(head.lines) and head.at_eof:
        raise head.fail(block.first_line, "no data rows after the header")
    used = (block.time, column)
    raw_t, raw_v = parse_block(head, block, head.offsets[start], used)
    if not head.ends_with_line_end():
        raise head.fail(
            block.first_line + raw_t.size - 1,
            "the last line has no line end: the file was cut short or is still being "
            "written, so its last sample may be a cut number; refused",
        )
    t = _time_axis(head, block, raw_t)
    values = column.unit.to_si(raw_v)
    overrange = check_samples(t, values, path, lambda i: f"line {block.first_line + i}")
    interval, source = _check_counts(head, block, t)
    metadata = {
        "format": block.fmt,
        "source": path,
        "instrument": None,
        "channel": column.name,
        "channels": names,
        "sample_interval": interval,
        "sample_interval_source": source,
        "trigger_time": 0.0,
        "time_unit": block.time.unit.text,
        "vertical_unit": column.unit.text,
        "encoding": head.encoding,
        "first_data_line": block.first_line,
        **block.metadata,
        "overrange": overrange,
    }
    return Trace(t, values, column.unit.si, metadata)


def _time_axis(head, block, raw):
    """Times [s]: the file's time column in SI, or ``start + n * increment``."""
    if block.sequence is None:
        return block.time.unit.to_si(raw)
    bad = raw != np.floor(raw)
    if bad.any():
        i = int(np.argmax(bad))
        raise head.fail(block.first_line + i, f"sample number {float(raw[i])!r} is not an integer")
    steps = np.diff(raw)
    if raw.size > 1 and not (steps == 1).all():
        i = int(np.argmax(steps != 1)) + 1
        raise head.fail(
            block.first_line + i,
            f"sample number {raw[i]:.0f} does not follow {raw[i - 1]:.0f} "
            "(the header's Increment needs consecutive samples)",
        )
    t = raw * block.sequence.increment
    t += block.sequence.start
    return t


def _check_counts(head, block, t):
    """Check the declared record length and interval; return (interval [s], its source)."""
    if block.record_length is not None:
        declared, line = block.record_length
        if declared != t.size:
            raise head.fail(line, f"header declares {declared} samples; the file holds {t.size}")
    if block.sequence is not None:
        return block.sequence.increment, "header"
    spacing = (t[-1] - t[0]) / (t.size - 1) if t.size > 1 else None
    if block.interval is None:
        return spacing, "time column (mean spacing)" if spacing is not None else None
    declared, line = block.interval
    if spacing is not None and abs(spacing - declared) > UNIFORM_RTOL * declared:
        raise head.fail(
            line,
            f"declared sample interval {declared!r} s disagrees with the time column's "
            f"spacing {spacing!r} s (mixed or wrong units?)",
        )
    return declared, "header"
