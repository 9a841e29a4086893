"""NI TDMS files through npTDMS (optional extra).

Channels are named ``"group/channel"``. Time follows NI's waveform properties:
``t = wf_start_offset + n * wf_increment`` [s] (``wf_start_offset`` defaults to 0 as NI
defines it); a channel without ``wf_increment`` has no time axis and is an error. Units
come from the ``unit_string`` property (``"V"``, ``"Volts"``, ``"mV"``, ``"N"``); a channel
without one is an error. A declared ``wf_samples`` must equal the samples the file holds,
and any warning npTDMS gives while reading, through :mod:`warnings` or its loggers (a
truncated segment, "less data than expected", a name that is not UTF-8), refuses the
file: a cut file never reads as a shorter trace.
"""

import contextlib
import logging
import warnings

import numpy as np

from contactlab.traces.binary import require
from contactlab.traces.checks import (
    check_samples,
    fail,
    header_number,
    select_channel,
    uniform_interval,
)
from contactlab.traces.trace import Trace
from contactlab.traces.units import SI_VALUE_UNITS, parse_unit

__all__ = ["read", "sniff", "write"]


def sniff(head):
    """The TDMS segment tag ``TDSm`` at the start of the file."""
    return head.raw.startswith(b"TDSm")


def _nptdms():
    return require("nptdms", "NI TDMS files")


class _Complaints(logging.Handler):
    """Collects what npTDMS logs at WARNING or above while a file is read."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


@contextlib.contextmanager
def _nptdms_complaints():
    """Warnings and WARNING log records of npTDMS as a list (its loggers kept quiet)."""
    complaints = _Complaints()
    logger = logging.getLogger("nptdms")
    children = [
        logging.getLogger(name)
        for name in list(logging.root.manager.loggerDict)
        if name.startswith("nptdms.")
    ]
    saved = [(child, child.handlers[:]) for child in children]
    for child in children:  # npTDMS prints to stderr from each module's logger
        child.handlers = []
    logger.addHandler(complaints)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield complaints.messages
            complaints.messages += [str(w.message) for w in caught]
    finally:
        logger.removeHandler(complaints)
        for child, handlers in saved:
            child.handlers = handlers


def read(head, channel):
    """Read one channel of a TDMS file.

    Returns
    -------
    Trace
    """
    nptdms = _nptdms()
    path = head.path
    try:
        with _nptdms_complaints() as complaints:
            tdms = nptdms.TdmsFile.read(path)
            found = {f"{g.name}/{c.name}": c for g in tdms.groups() for c in g.channels()}
            names = [
                n for n, c in found.items() if len(c) and np.asarray(c[:1]).dtype.kind in "iuf"
            ]
    except Exception as exc:  # npTDMS reports corrupt segments through several types
        raise fail(path, "binary", f"not a readable TDMS file ({exc})") from exc
    if complaints:
        raise fail(path, "binary", f"damaged TDMS file: npTDMS says {complaints[0][:200]!r}")
    if not names:
        raise fail(path, "binary", "no numeric channel")
    name = names[select_channel(names, channel, path, "channel list")]
    props = dict(found[name].properties)
    where = f"channel {name!r}"
    unit = parse_unit(str(props.get("unit_string", "")))
    if unit is None or unit.si not in SI_VALUE_UNITS:
        raise fail(path, where, f"unit_string {props.get('unit_string')!r} is not V, N or A")
    if "wf_increment" not in props:
        raise fail(path, where, "no wf_increment property: the time axis is unknown")
    interval = header_number(path, where, "wf_increment", props["wf_increment"], positive=True)
    start = header_number(path, where, "wf_start_offset", props.get("wf_start_offset", 0.0))
    values = unit.to_si(np.asarray(found[name][:], dtype=np.float64))
    if "wf_samples" in props:
        declared = header_number(path, where, "wf_samples", props["wf_samples"], positive=True)
        if declared != values.size:
            raise fail(
                path,
                where,
                f"wf_samples declares {declared:.0f} samples; the file holds "
                f"{values.size} (cut short?)",
            )
    t = np.arange(values.size) * interval
    t += start
    metadata = {
        "format": "tdms",
        "source": path,
        "instrument": props.get("instrument"),
        "channel": name,
        "channels": names,
        "sample_interval": interval,
        "sample_interval_source": "header",
        "trigger_time": None,
        "time_unit": "s",
        "vertical_unit": unit.text,
        "header": {k: str(v) for k, v in props.items()},
        "overrange": check_samples(t, values, path, lambda i: f"sample {i}"),
    }
    return Trace(t, values, unit.si, metadata)


def write(path, trace, *, group="trace", channel="value"):
    """Write a uniformly sampled trace to TDMS with NI waveform properties."""
    nptdms = _nptdms()
    properties = {
        "wf_increment": uniform_interval(trace),
        "wf_start_offset": float(trace.t[0]),
        "wf_samples": len(trace),
        "unit_string": trace.unit,
    }
    with nptdms.TdmsWriter(path) as writer:
        writer.write_segment(
            [nptdms.ChannelObject(group, channel, np.asarray(trace.values), properties)]
        )
