"""Binary files: the optional-extra import, and oscilloscope binaries through RigolWFM.

``"scope-binary"`` reads what `RigolWFM <https://RigolWFM.readthedocs.io>`_ reads:
Rigol ``.wfm``/``.bin``, Tektronix ``.isf``/``.wfm``, LeCroy ``.trc``, Keysight ``.bin``
and more, recognised by their signatures (not their extensions). Channels are named as
RigolWFM names them (``"CH 1"``; ``channel="CH1"`` also matches). Times are RigolWFM's
``start + n * increment`` [s] relative to the trigger; values are its calibrated volts
(or amperes), which for some formats it computes in float32 (relative rounding ~6e-8,
far below 8- to 16-bit quantisation).

The binary readers need packages outside the core install; they are imported only when
such a file is read, and a missing one raises an :class:`ImportError` naming the extra.
"""

import contextlib
import gc
import importlib
import io
import re
import warnings

import numpy as np

from contactlab.traces.checks import check_samples, fail, select_channel
from contactlab.traces.trace import Trace

__all__ = ["EXTRA", "read", "require", "sniff"]

EXTRA = "pip install contactlab[traces]"
"""How to install the optional readers."""

_ISF = re.compile(rb":CURVE? #\d")
_ISF_POINTS = re.compile(rb"(?:NR_PT|NR_P)\s+(\d+)")
_UNITS = {"v": "V", "a": "A"}


def require(module, purpose):
    """Import an optional module, or raise ImportError naming the extra that provides it."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(f"reading {purpose} needs the package {module!r}: {EXTRA}") from exc


def sniff(head):
    """Binary content, a Tektronix ISF curve block, or a LeCroy ``WAVEDESC``."""
    return not head.is_text or bool(_ISF.search(head.raw)) or b"WAVEDESC" in head.raw[:512]


def _isf_points(head):
    """Points a Tektronix ISF preamble declares (``NR_PT``/``NR_P``), or None.

    RigolWFM reads a curve cut short by a whole number of samples without complaint; the
    declared count catches it.
    """
    if not _ISF.search(head.raw):
        return None
    match = _ISF_POINTS.search(head.raw)
    return int(match.group(1)) if match else None


def _channels(wfm, path):
    """Instrument, header and per-channel data of a file, as plain Python and numpy."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        waveform = wfm.Wfm.from_file(path)
    file_header = {
        "parser": waveform.parser_name,
        "serial_number": waveform.serial_number,
        "firmware": waveform.firmware,
        "trigger": waveform.trigger_info,
    }
    return waveform.header_name, [
        {
            "name": c.name,
            "t": np.asarray(c.times, dtype=np.float64),
            "values": np.asarray(c.volts, dtype=np.float64),
            "unit": c.unit.name,
            "interval": float(c.seconds_per_point),
            "header": {
                **file_header,
                "coupling": c.coupling,
                "probe": c.probe_value,
                "volt_per_division": c.volt_per_division,
                "volt_offset": c.volt_offset,
                "time_scale": c.time_scale,
                "time_offset": c.time_offset,
            },
        }
        for c in waveform.channels
        if c.volts is not None and c.times is not None
    ]


def read(head, channel):
    """Read one channel of an oscilloscope binary file through RigolWFM.

    Returns
    -------
    Trace
    """
    wfm = require("RigolWFM.wfm", "oscilloscope binaries (Rigol wfm, Tektronix isf, LeCroy trc)")
    path = head.path
    with warnings.catch_warnings():
        # RigolWFM's generated parsers open files they never close. Only plain data leave
        # _channels, so the parser objects and their handles are collected (and closed)
        # here, where their ResourceWarning is expected.
        warnings.simplefilter("ignore", ResourceWarning)
        try:
            instrument, channels = _channels(wfm, path)
        except Exception as exc:  # a third-party parser of untrusted bytes: the file is bad
            raise fail(path, "binary", f"not a readable oscilloscope binary ({exc})") from None
        finally:
            gc.collect()
    if not channels:
        raise fail(path, "binary", "no analog channel with data")
    names = [c["name"] for c in channels]
    chosen = channels[select_channel(names, channel, path, "channel list")]
    unit = _UNITS.get(chosen["unit"])
    if unit is None:
        raise fail(path, "binary", f"channel {chosen['name']!r} has unit {chosen['unit']!r}")
    t, values = chosen["t"], chosen["values"]
    declared = _isf_points(head)
    if declared is not None and declared != values.size:
        raise fail(
            path,
            "binary",
            f"the header declares {declared} points (NR_PT) but the curve "
            f"holds {values.size}: the file is truncated or corrupt",
        )
    metadata = {
        "format": "scope-binary",
        "source": path,
        "instrument": instrument,
        "channel": chosen["name"],
        "channels": names,
        "sample_interval": chosen["interval"],
        "sample_interval_source": "header",
        "trigger_time": 0.0,
        "time_unit": "s",
        "vertical_unit": unit,
        "header": chosen["header"],
        "overrange": check_samples(t, values, path, lambda i: f"sample {i}"),
    }
    return Trace(t, values, unit, metadata)
