"""Tektronix CSV: the TDS1000/2000 layout and the MSO/MDO/DPO layout.

TDS (``"tektronix-tds"``): one channel per file. Columns 0-2 of the first 18 rows hold a
key/value header (``Record Length``, ``Sample Interval``, ``Trigger Point``, ``Source``,
``Vertical Units``, ..., ``Firmware Version``); columns 3-4 of every row, from the first,
hold time and value; rows end with a comma::

    Record Length,2.500000e+03,,-0.000500000000,0.00400,
    Sample Interval,4.000000e-07,,-0.000499600000,0.00400,
    ...
    ,,,0.000499600000,0.00800,

MSO/MDO/DPO (``"tektronix-mso"``): a key/value header (``Model``, ``Firmware Version``,
blank line, ``Sample Interval``, ``Record Length``, ``Vertical Units`` with one value per
channel, ...), a ``Label`` row, then ``TIME,CH1,...`` and the data.

Both keep the file's own time column (time relative to the trigger); the declared
``Sample Interval`` and ``Record Length`` are checked against it. The TDS envelope point
format (``Pt Fmt ENV``: min/max pairs at the same time) is refused, not flattened.
"""

import numpy as np

from contactlab.errors import ParameterError
from contactlab.traces.checks import uniform_interval
from contactlab.traces.textblock import Block, Column, require_unit
from contactlab.traces.textwrite import write_text

__all__ = ["parse_mso", "parse_tds", "sniff_mso", "sniff_tds", "write_mso", "write_tds"]

TDS_HEADER_ROWS = 18
TDS_FIELDS = 6
"""Cells of a TDS data row: header key, header value, blank, time, value, blank."""
"""Rows of the TDS key/value header (columns 0-2)."""


def sniff_tds(head):
    """TDS layout: the first row starts ``Record Length,`` beside data."""
    cells = head.cells(0)
    return len(cells) >= 5 and cells[0] == "Record Length"


def sniff_mso(head):
    """MSO/MDO/DPO layout: ``Model,`` first, a ``TIME,`` row later."""
    return head.cells(0)[:1] == ["Model"] and _time_row(head) is not None


def _time_row(head):
    return next((i for i, line in enumerate(head.lines) if line.startswith("TIME,")), None)


def _fields(head, rows, value):
    """Header ``{key: value}`` and ``{key: 1-based line}`` of some rows.

    ``value(cells, rest)`` picks the value from the row's cells or the verbatim rest of
    the line after the key.
    """
    fields, lines = {}, {}
    for i in rows:
        cells = head.cells(i)
        if cells[0]:
            fields[cells[0]] = value(cells, head.lines[i].partition(",")[2])
            lines[cells[0]] = i + 1
    return fields, lines


def _number(head, fields, lines, key, *, integer=False):
    """A numeric header field, or fail naming its line."""
    if key not in fields:
        raise head.fail(1, f"Tektronix header lacks {key!r}")
    text = fields[key].split(",")[0].strip()
    try:
        value = float(text)
    except ValueError:
        raise head.fail(lines[key], f"{key} {text!r} is not a number") from None
    if integer and not value.is_integer():
        raise head.fail(lines[key], f"{key} {text!r} is not a whole number")
    return int(value) if integer else value


def _declared(head, fields, lines, key, *, integer=False):
    """``(value, line)`` of a required numeric header field."""
    return _number(head, fields, lines, key, integer=integer), lines[key]


def _text(head, fields, lines, key):
    if key not in fields:
        raise head.fail(1, f"Tektronix header lacks {key!r}")
    return fields[key].split(",")[0].strip()


def parse_tds(head):
    """Describe the data of a TDS1000/2000 CSV file.

    Returns
    -------
    Block
    """
    rows = range(min(TDS_HEADER_ROWS, len(head.lines)))
    fields, lines = _fields(head, rows, lambda cells, rest: cells[1] if len(cells) > 1 else "")
    point_format = fields.get("Pt Fmt", "Y")
    if point_format != "Y":
        raise head.fail(
            lines["Pt Fmt"], f"Pt Fmt {point_format!r} (envelope min/max pairs) is not supported"
        )
    time_unit, value_unit = (
        require_unit(head, lines.get(key, 1), fields.get(key, ""), kind)
        for key, kind in (("Horizontal Units", "time"), ("Vertical Units", "value"))
    )
    source = fields.get("Source") or "unknown"  # the file does not say: no guess
    metadata = {
        "instrument": fields.get("Model Number"),
        "header": fields,
    }
    if "Trigger Point" in fields:
        metadata["trigger_index"] = _number(head, fields, lines, "Trigger Point", integer=True)
    return Block(
        fmt="tektronix-tds",
        first_line=1,
        time=Column("time", 3, time_unit),
        channels=(Column(source, 4, value_unit),),
        channel_line=lines.get("Source", 1),
        max_fields=TDS_FIELDS,
        record_length=_declared(head, fields, lines, "Record Length", integer=True),
        interval=_declared(head, fields, lines, "Sample Interval"),
        metadata=metadata,
    )


def parse_mso(head):
    """Describe the data of an MSO/MDO/DPO-series CSV file.

    Returns
    -------
    Block
    """
    index = _time_row(head)
    if index is None:
        raise head.fail(1, "no 'TIME,<channels>' row in the header")
    fields, lines = _fields(head, range(index), lambda cells, rest: rest)
    cells = head.cells(index)
    names = cells[1:-1] if cells[-1] == "" else cells[1:]
    if not names or "" in names:
        raise head.fail(index + 1, f"channel names missing in {head.lines[index]!r}")
    units = [u.strip() for u in fields.get("Vertical Units", "").split(",")][: len(names)]
    if len(units) != len(names) or "" in units:
        raise head.fail(
            lines.get("Vertical Units", index + 1),
            f"need one Vertical Units entry per channel ({len(names)})",
        )
    line = lines["Vertical Units"]
    time_unit = require_unit(
        head,
        lines.get("Horizontal Units", 1),
        _text(head, fields, lines, "Horizontal Units"),
        "time",
    )
    return Block(
        fmt="tektronix-mso",
        first_line=index + 2,
        time=Column("TIME", 0, time_unit),
        channels=tuple(
            Column(name, i + 1, require_unit(head, line, unit, "value"))
            for i, (name, unit) in enumerate(zip(names, units, strict=True))
        ),
        channel_line=index + 1,
        n_fields=len(cells),
        record_length=_declared(head, fields, lines, "Record Length", integer=True),
        interval=_declared(head, fields, lines, "Sample Interval"),
        metadata={"instrument": fields.get("Model"), "header": fields},
    )


def write_tds(path, trace, *, instrument="TDS2012B", source="CH1", serial="", firmware=""):
    """Write a trace in the TDS1000/2000 CSV layout.

    Times are written at full precision (a TDS prints ~12 digits); the trace must be
    uniformly sampled and hold at least 18 samples (the header sits beside the data).

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    instrument, source, serial, firmware : str
        ``Model Number``, ``Source``, ``Serial Number`` and ``Firmware Version`` fields.
    """
    n = len(trace)
    if n < TDS_HEADER_ROWS:
        raise ParameterError(f"the TDS layout needs at least {TDS_HEADER_ROWS} samples; got {n}")
    interval = uniform_interval(trace)
    header = [
        ("Record Length", f"{n:.6e}"),
        ("Sample Interval", repr(interval)),
        ("Trigger Point", f"{int(np.searchsorted(trace.t, 0.0)):.12e}"),
        ("", ""),
        ("", ""),
        ("Source", source),
        ("Vertical Units", trace.unit),
        ("Vertical Scale", "1.000000e+00"),
        ("Vertical Offset", "0.000000e+00"),
        ("", ""),
        ("Horizontal Units", "s"),
        ("Horizontal Scale", f"{n * interval / 10:.6e}"),
        ("Pt Fmt", "Y"),
        ("Yzero", "0.000000e+00"),
        ("Probe Atten", "1.000000e+00"),
        ("Model Number", instrument),
        ("Serial Number", serial),
        ("Firmware Version", firmware),
    ]
    keys = np.full(n, "", dtype=object)
    values = np.full(n, "", dtype=object)
    keys[:TDS_HEADER_ROWS], values[:TDS_HEADER_ROWS] = zip(*header, strict=True)
    empty = np.full(n, "", dtype=object)
    write_text(path, [], [keys, values, empty, trace.t, trace.values], trailing=True)


def write_mso(path, trace, *, instrument="MDO3024", channel="CH1", firmware="1.03"):
    """Write a trace in the MSO/MDO/DPO-series CSV layout (one channel).

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    instrument, channel, firmware : str
        ``Model``, the channel name in the ``TIME`` row, and ``Firmware Version``.
    """
    interval = uniform_interval(trace)
    header = [
        f"Model,{instrument}",
        f"Firmware Version,{firmware}",
        "",
        "Waveform Type,ANALOG",
        "Point Format,Y",
        "Horizontal Units,s",
        f"Horizontal Scale,{len(trace) * interval / 10:g}",
        "Horizontal Delay,0",
        f"Sample Interval,{interval!r}",
        f"Record Length,{len(trace)}",
        "Gating,0.0% to 100.0%",
        "Probe Attenuation,1",
        f"Vertical Units,{trace.unit}",
        "Vertical Offset,0",
        "Vertical Scale,1",
        "Vertical Position,0",
        "",
        "",
        "",
        "Label,",
        f"TIME,{channel}",
    ]
    write_text(path, header, [trace.t, trace.values])
