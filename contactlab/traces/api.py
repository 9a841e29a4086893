"""Reading and writing traces: :func:`read_trace` and :func:`write_trace`."""

import difflib
import os
import stat

from contactlab.errors import ParameterError
from contactlab.traces.checks import fail
from contactlab.traces.detect import detect_head
from contactlab.traces.formats import FORMATS
from contactlab.traces.prepare import to_force
from contactlab.traces.texthead import read_head

__all__ = ["read_trace", "write_trace"]


def _format(name, *, writable=False):
    """The registry entry called ``name``, or a ParameterError listing the choices."""
    choices = [n for n, f in FORMATS.items() if f.write is not None or not writable]
    if name in choices:
        return FORMATS[name]
    near = difflib.get_close_matches(str(name), choices, n=1)
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    raise ParameterError(f"format must be one of {', '.join(choices)}; got {name!r}{hint}")


def read_trace(path, format="auto", channel=None, sensitivity=None):
    """Read one channel of an oscilloscope or DAQ export.

    The format is recognised from the content (a Rigol CSV named ``.txt`` reads as
    Rigol). Values come back in SI base units (V, N or A) and times in seconds; the
    sample count, first and last time and sample interval are those of the file, exactly:
    where the file gives ``start + n * increment`` the times are built from it, otherwise
    the file's own time column is kept.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    format : str, default "auto"
        ``"auto"`` or a key of :data:`~contactlab.traces.formats.FORMATS`.
    channel : str or int, optional
        Channel name (``"CH1"``, ``"Channel A"``, ``"trace/value"``) or 0-based index.
        Required when the file holds several channels: taking the first would be a guess.
    sensitivity : float, optional
        Sensor sensitivity [V/N]; converts a volt trace to newtons (recorded in
        ``metadata["history"]``). An error for a trace not in volts.

    Returns
    -------
    Trace

    Raises
    ------
    TraceFormatError
        The content is malformed (empty, header without data, missing or non-numeric
        cell, time not strictly increasing, declared length or interval contradicted,
        unknown unit) or the channel does not exist; the message names the file and the
        1-based line (or the sample for binary files).
    ParameterError
        An unknown ``format`` name or a bad ``sensitivity``.
    ImportError
        A binary format whose optional package is missing (``pip install
        contactlab[traces]``).
    OSError
        The file cannot be opened (``FileNotFoundError``, ``PermissionError``). A folder,
        FIFO, socket or device is refused at once with a TraceFormatError.
    """
    path = os.fspath(path)
    reader = None if format == "auto" else _format(format)
    check_regular_file(path)
    head = read_head(path)
    if not head.raw:
        raise fail(path, "line 1", "the file is empty")
    reader = reader or FORMATS[detect_head(head)]
    trace = reader.read(head, channel)
    return trace if sensitivity is None else to_force(trace, sensitivity)


def check_regular_file(path):
    """Refuse at once what is not a regular file (a FIFO or device would block or never end).

    Raises
    ------
    TraceFormatError
        Naming the file and what it is; ``FileNotFoundError`` if it does not exist.
    """
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "a FIFO, socket or device"
        raise fail(path, "file", f"is {kind}, not a regular file: refused")


def write_trace(path, trace, format="generic", **options):
    """Write a trace in one of the writable layouts.

    Every text layout has a writer, so tests round-trip each and sample data can be
    produced in each instrument's layout. Floats are written as their shortest exact
    representation, so reading back gives the same doubles (up to one rounding where a
    unit such as ms or mV is chosen).

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    format : str, default "generic"
        A registry name whose format has a writer.
    **options
        Layout options, documented with each writer (e.g.
        :func:`contactlab.traces.rigol.write_sequence` takes ``first_index``;
        :func:`contactlab.traces.picoscope.write` takes ``time_unit`` and ``value_unit``).
        Unknown options raise TypeError. Text options (names, units, comments) may not
        contain a line break, and names and units may not contain the comma that separates
        cells: the file would not read back (a ParameterError names the option).
    """
    writer = _format(format, writable=True)
    for name, value in options.items():
        _check_text_option(name, value)
    writer.write(os.fspath(path), trace, **options)


def _check_text_option(name, value, cells=True):
    """Refuse text that would break a text layout's lines or (``cells``) its cells."""
    if isinstance(value, dict):  # comments: one "# key: value" line each, commas allowed
        for key, item in value.items():
            _check_text_option(f"{name} key {key!r}", str(key), cells=False)
            _check_text_option(f"{name}[{key!r}]", str(item), cells=False)
        return
    forbidden = ",\r\n" if cells else "\r\n"
    if isinstance(value, str) and any(c in value for c in forbidden):
        what = "a comma or a line break" if cells else "a line break"
        raise ParameterError(
            f"{name} = {value!r} contains {what}, which would split the file's "
            f"{'cells or lines' if cells else 'lines'}; choose another text"
        )
