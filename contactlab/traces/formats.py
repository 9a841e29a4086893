"""The registry of trace formats: one entry per layout, in detection order.

Each :class:`Format` knows how to recognise its content (``sniff``), read it and, where
the layout can be written, write it. Detection (:mod:`contactlab.traces.detect`) asks the
entries in order: binary signatures first, then the instrument text layouts, each of which
recognises its own header rows, and last ``generic``, the fallback for any text.
"""

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from contactlab.traces import binary, generic, hdf5, keysight, lecroy, picoscope, rigol, tdms
from contactlab.traces import tektronix as tek
from contactlab.traces.textblock import read_block

__all__ = ["FORMATS", "Format"]


@dataclass(frozen=True)
class Format:
    """One trace format."""

    description: str
    sniff: Callable
    """``sniff(head) -> bool``: whether a file's head has this format's content."""
    read: Callable
    """``read(head, channel) -> Trace``."""
    write: Callable | None = None
    """``write(path, trace, **options)``, or ``None`` if this toolkit does not write it."""


def _read_text(description, sniff, parse_header, head, channel):
    if not sniff(head):
        raise head.fail(1, f"the header rows are not those of a {description} file")
    return read_block(head, parse_header(head), channel)


def _text(description, sniff, parse_header, write):
    read = partial(_read_text, description, sniff, parse_header)
    return Format(description, sniff, read, write)


FORMATS = {
    "hdf5": Format("HDF5 (h5py; see contactlab.traces.hdf5)", hdf5.sniff, hdf5.read, hdf5.write),
    "tdms": Format("NI TDMS (npTDMS)", tdms.sniff, tdms.read, tdms.write),
    "scope-binary": Format(
        "oscilloscope binaries via RigolWFM (Rigol wfm, Tektronix isf/wfm, LeCroy trc, ...)",
        binary.sniff,
        binary.read,
    ),
    "tektronix-tds": _text(
        "Tektronix TDS1000/2000 CSV", tek.sniff_tds, tek.parse_tds, tek.write_tds
    ),
    "tektronix-mso": _text(
        "Tektronix MSO/MDO/DPO CSV", tek.sniff_mso, tek.parse_mso, tek.write_mso
    ),
    "rigol-sequence": _text(
        "Rigol CSV, X,CH1,Start,Increment",
        rigol.sniff_sequence,
        rigol.parse_sequence,
        rigol.write_sequence,
    ),
    "rigol-seconds": _text(
        "Rigol CSV, X,CH1 / Second,Volt",
        rigol.sniff_seconds,
        rigol.parse_seconds,
        rigol.write_seconds,
    ),
    "keysight": _text(
        "Keysight InfiniiVision CSV", keysight.sniff, keysight.parse_header, keysight.write
    ),
    "picoscope": _text("PicoScope CSV", picoscope.sniff, picoscope.parse_header, picoscope.write),
    "lecroy": _text("LeCroy CSV", lecroy.sniff, lecroy.parse_header, lecroy.write),
    "generic": _text(
        "generic CSV with units in the header", generic.sniff, generic.parse_header, generic.write
    ),
}
"""Format name -> :class:`Format`, in detection order."""
