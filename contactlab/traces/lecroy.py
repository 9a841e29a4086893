"""LeCroy CSV::

    LECROYWR6100A,12345,Waveform
    Segments,1,SegmentSize,10002
    Segment,TrigTime,TimeSinceSegment1
    #1,16-Nov-2012 12:35:47,0
    Time,Ampl
    -5.0e-06,0.001

A 5-row header (model, segment count and size, one row per segment with its trigger
time stamp, ``Time,Ampl``), then time and amplitude. The file states no units: LeCroy
writes seconds and the channel's vertical unit, volts for a voltage input; the reader
reads volts and records ``metadata["units_stated"] = False``. ``SegmentSize`` is checked
against the sample count. Segmented (sequence-mode) exports restart time in every
segment and are refused.
"""

from contactlab.errors import ParameterError
from contactlab.traces.textblock import Block, Column
from contactlab.traces.textwrite import write_text
from contactlab.traces.units import parse_unit

__all__ = ["parse_header", "sniff", "write"]

_COLUMNS = ["Time", "Ampl"]


def sniff(head):
    """``Segments,...`` on row 2 and a ``Time,Ampl`` row."""
    return head.cells(1)[:1] == ["Segments"] and _COLUMNS in [head.cells(i) for i in range(8)]


def _count(head, cells, position, what):
    text = cells[position] if len(cells) > position else ""
    if not text.isdigit():
        raise head.fail(2, f"{what} {text!r} is not a whole number")
    return int(text)


def parse_header(head):
    """Describe the data of a LeCroy CSV file.

    Returns
    -------
    Block
    """
    cells = head.cells(1)
    if cells[:1] != ["Segments"] or cells[2:3] != ["SegmentSize"]:
        raise head.fail(2, "expected 'Segments,<n>,SegmentSize,<samples>'")
    segments = _count(head, cells, 1, "Segments")
    size = _count(head, cells, 3, "SegmentSize")
    if segments != 1:
        raise head.fail(2, f"{segments} segments: segmented exports (time restarts) unsupported")
    if head.cells(4) != _COLUMNS:
        raise head.fail(5, "expected the column row 'Time,Ampl'")
    stamp = head.cells(3)
    return Block(
        fmt="lecroy",
        first_line=6,
        time=Column("Time", 0, parse_unit("s")),
        channels=(Column("Ampl", 1, parse_unit("V")),),
        channel_line=5,
        n_fields=2,
        record_length=(size, 2),
        metadata={
            "instrument": head.cells(0)[0],
            "trigger_timestamp": stamp[1] if len(stamp) > 1 else None,
            "units_stated": False,
            "header": {"lines": list(head.lines[:5])},
        },
    )


def write(
    path, trace, *, instrument="LECROYWR6100A", serial="00000", timestamp="01-Jan-2024 00:00:00"
):
    """Write a volt trace in the LeCroy CSV layout.

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    instrument, serial : str
        Row 1: model and serial number.
    timestamp : str
        Trigger time stamp of the segment (row 4).
    """
    if trace.unit != "V":
        raise ParameterError(f"LeCroy CSV states no unit and is read as volts; got {trace.unit!r}")
    header = [
        f"{instrument},{serial},Waveform",
        f"Segments,1,SegmentSize,{len(trace)}",
        "Segment,TrigTime,TimeSinceSegment1",
        f"#1,{timestamp},0",
        ",".join(_COLUMNS),
    ]
    write_text(path, header, [trace.t, trace.values])
