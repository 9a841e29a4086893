"""The CSV machinery every text layout shares: file head, data block, writer.

A text layout module only reads its header (from :class:`Head`, the file's first
64 KiB split into lines) and describes the data block that follows as a :class:`Block`:
where it starts, which column holds time (or a sample number), which hold channels and
in what units. :func:`read_block` then does the rest for every layout alike:

- the fast path parses only the data block with ``pandas.read_csv(engine="c")`` straight
  into float64 columns (correctly rounded, so written reprs read back bit for bit) and
  validates with vectorised numpy: no NaN, strictly increasing time, declared record
  length and sample interval honoured;
- anything the fast path rejects (a non-numeric or missing cell, a wrong cell count, an
  undecodable byte, a layout's own overrange token such as ``∞``), and any block that
  holds the words ``true`` or ``false`` (pandas would read them as 1 and 0), goes through
  a line-by-line parser that either reads it (special tokens, trailing blank lines) or
  raises :class:`~contactlab.errors.TraceFormatError` naming the file and the 1-based line.
  The slow path costs time only on files that need it.

Rows map one to one to lines (no quoting, ``\\n`` line ends, blank lines kept), so a
sample index ``i`` is line ``first_line + i``.

Files are read as UTF-8, falling back to Latin-1 (which decodes any byte). A file that
starts with a UTF-16 or UTF-32 byte-order mark (as some Windows instrument software writes
it) is decoded whole and re-encoded as UTF-8 in memory, and both the header and the data
are read from that copy; such files are small, and without the mark the encoding would be
a guess.
"""

import codecs
import csv
import io
import math
import re
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from contactlab.errors import ParameterError
from dem_check.traces.checks import UNIFORM_RTOL, check_samples, fail, select_channel
from dem_check.traces.trace import Trace
from dem_check.traces.units import SI_VALUE_UNITS, Unit, parse_unit

__all__ = [
    "Block",
    "Column",
    "Head",
    "Sequence",
    "named_columns",
    "output_units",
    "read_block",
    "read_head",
    "require_unit",
    "write_text",
]

HEAD_BYTES = 1 << 16
"""Bytes read for detection and headers [B]; every supported header is far shorter."""

_WIDE_BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32"),  # before UTF-16 LE, whose mark it starts with
    (codecs.BOM_UTF32_BE, "utf-32"),
    (codecs.BOM_UTF16_LE, "utf-16"),
    (codecs.BOM_UTF16_BE, "utf-16"),
)
"""Byte-order marks of the wide Unicode encodings, and the codec that reads each."""

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_WITH_UNIT = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*[A-Za-zµμ]+")
_BOOLEAN_WORDS = (b"true", b"false")
"""Words pandas' C parser turns into 1.0 and 0.0 (in any case) in a column made of them:
a data block that holds one goes to the line parser, which refuses them as not numbers."""
_INFINITIES = {
    "inf": math.inf,
    "+inf": math.inf,
    "-inf": -math.inf,
    "infinity": math.inf,
    "+infinity": math.inf,
    "-infinity": -math.inf,
}


@dataclass(frozen=True)
class Head:
    """The first :data:`HEAD_BYTES` of a file, split into complete lines."""

    path: str
    raw: bytes
    lines: tuple
    """Decoded lines without their line ends (the partial last line is dropped)."""
    offsets: tuple
    """Byte offset where each line starts, plus one entry past the last line."""
    encoding: str
    """Encoding of the file (``"utf-8"``, ``"latin-1"``, ``"utf-16"`` or ``"utf-32"``)."""
    at_eof: bool
    """Whether the head holds the whole file."""
    transcoded: bytes | None = None
    """The whole file re-encoded as UTF-8 when it is UTF-16 or UTF-32 (``raw``, ``lines``
    and ``offsets`` then describe this copy); ``None`` for files read as they are."""

    @property
    def data_encoding(self):
        """Encoding of the bytes :meth:`open_data` returns."""
        return self.encoding if self.transcoded is None else "utf-8"

    def open_data(self):
        """A binary file object over the content: the file, or its UTF-8 copy."""
        return open(self.path, "rb") if self.transcoded is None else io.BytesIO(self.transcoded)

    @property
    def is_text(self):
        """Whether the head looks like text (no NUL byte)."""
        return b"\x00" not in self.raw

    def cells(self, index, delimiter=","):
        """Stripped cells of the 0-based line ``index`` (``[]`` beyond the head)."""
        if index >= len(self.lines):
            return []
        return [cell.strip() for cell in self.lines[index].split(delimiter)]

    def fail(self, line, message):
        """A TraceFormatError at the 1-based ``line`` of this file."""
        return fail(self.path, f"line {line}", message)


def read_head(path):
    """Read a file's head: its first 64 KiB as complete lines, with byte offsets.

    A UTF-16 or UTF-32 file (recognised by its byte-order mark) is read whole and
    re-encoded as UTF-8 (:attr:`Head.transcoded`); the head is then that copy's.

    Raises
    ------
    TraceFormatError
        A byte-order mark followed by bytes that are not valid in its encoding.
    """
    with open(path, "rb") as fh:
        raw = fh.read(HEAD_BYTES + 1)
        wide = next((codec for bom, codec in _WIDE_BOMS if raw.startswith(bom)), None)
        if wide is not None:
            raw += fh.read()
    transcoded = None
    if wide is not None:
        try:
            transcoded = raw.decode(wide).encode("utf-8")
        except UnicodeDecodeError as exc:
            raise fail(
                path,
                f"byte {exc.start}",
                f"starts with a {wide.upper()} byte-order mark but "
                f"is not valid {wide.upper()} ({exc.reason})",
            ) from None
        raw = transcoded[: HEAD_BYTES + 1]
    at_eof = len(raw) <= HEAD_BYTES
    raw = raw[:HEAD_BYTES]
    pieces = raw.split(b"\n")
    if not at_eof or pieces[-1] == b"":
        pieces.pop()
    offsets = np.cumsum([0] + [len(p) + 1 for p in pieces]).tolist()
    try:
        b"\n".join(pieces).decode("utf-8")
        encoding = "utf-8"
    except UnicodeDecodeError:
        encoding = "latin-1"  # decodes any byte; cells that matter are ASCII numbers
    lines = [p.rstrip(b"\r").decode(encoding) for p in pieces]
    if lines and lines[0].startswith("\ufeff"):
        lines[0] = lines[0][1:]
    return Head(str(path), raw, tuple(lines), tuple(offsets), wide or encoding, at_eof, transcoded)


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
        See :func:`~dem_check.traces.checks.select_channel`.
    """
    path = head.path
    names = [c.name for c in block.channels]
    column = block.channels[select_channel(names, channel, path, f"line {block.channel_line}")]
    start = block.first_line - 1
    if start >= len(head.lines) and head.at_eof:
        raise head.fail(block.first_line, "no data rows after the header")
    used = (block.time, column)
    raw_t, raw_v = _parse(head, block, head.offsets[start], used)
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


def _parse(head, block, offset, used):
    """Fast vectorised parse of the used columns; the line parser when it refuses."""
    indices = [c.index for c in used]
    options = {
        "header": None,
        "sep": block.delimiter,
        "engine": "c",
        "dtype": np.float64,
        "quoting": csv.QUOTE_NONE,
        "skip_blank_lines": False,
        "keep_default_na": False,
        "na_values": [""],
        "lineterminator": "\n",
        "encoding": head.data_encoding,
    }
    if block.n_fields is None:
        options["usecols"] = sorted(set(indices))
    try:
        with head.open_data() as fh:
            fh.seek(offset)
            booleans = _has_boolean_word(fh)
            fh.seek(offset)
            frame = None if booleans else pd.read_csv(fh, **options)
    except ValueError:  # pandas' ParserError, EmptyDataError and UnicodeDecodeError too
        frame = None
    if frame is None:
        return _parse_lines(head, block, offset, used)
    if block.n_fields is not None and frame.shape[1] != block.n_fields:
        return _parse_lines(head, block, offset, used)
    arrays = [frame[i].to_numpy() for i in indices]
    if any(np.isnan(a).any() for a in arrays):
        return _parse_lines(head, block, offset, used)
    # Keep only the used columns alive (the frame's block may hold other channels).
    return [a if frame.shape[1] <= 2 else a.copy() for a in arrays]


def _has_boolean_word(fh):
    """Whether the rest of ``fh`` holds ``true`` or ``false`` in any case (1 MiB chunks)."""
    tail = b""
    while chunk := fh.read(1 << 20):
        text = tail + chunk.lower()
        if any(word in text for word in _BOOLEAN_WORDS):
            return True
        tail = text[-4:]  # "false" may straddle two chunks
    return False


def _cell(token, specials):
    text = token.strip()
    if _NUMBER.fullmatch(text):
        return float(text)
    value = specials.get(text, _INFINITIES.get(text.casefold()))
    if value is not None:
        return value
    if not text:
        raise ValueError("missing cell")
    if _WITH_UNIT.fullmatch(text):
        raise ValueError(f"{text!r} carries a unit; units belong in the header (mixed units)")
    raise ValueError(f"{text!r} is not a number")


def _parse_lines(head, block, offset, used):
    """Parse the block line by line: slow, exact about where a fault lies."""
    columns = [[] for _ in used]
    blank = None
    with head.open_data() as fh:
        fh.seek(offset)
        for number, raw in enumerate(fh, start=block.first_line):
            text = raw.rstrip(b"\r\n").decode(head.data_encoding, errors="replace")
            if not text.strip():
                blank = blank or number
                continue
            if blank is not None:
                raise head.fail(blank, "blank line inside the data")
            cells = text.split(block.delimiter)
            if block.n_fields is not None and len(cells) != block.n_fields:
                raise head.fail(number, f"{len(cells)} cells where the header has {block.n_fields}")
            for out, column in zip(columns, used, strict=True):
                token = cells[column.index] if column.index < len(cells) else ""
                try:
                    out.append(_cell(token, block.specials))
                except ValueError as exc:
                    raise head.fail(number, f"column {column.name!r}: {exc}") from None
    if not columns[0]:
        raise head.fail(block.first_line, "no data rows after the header")
    return [np.array(c, dtype=np.float64) for c in columns]


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
