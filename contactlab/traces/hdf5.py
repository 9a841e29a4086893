"""HDF5 traces through h5py (optional extra).

HDF5 has no standard for traces, so this module reads (and writes) one documented
convention:

- every 1-D numeric dataset not named ``t`` or ``time`` is a channel, named by its path
  (``"trace/sensor"``), with a ``unit`` attribute (``"V"``, ``"mV"``, ``"N"``, ...);
- its time is either the attributes ``start_time`` and ``sample_interval`` [s] on the
  dataset (``t = start_time + n * sample_interval``), or a 1-D dataset ``t`` or ``time``
  in the same group, of the same length, with a ``unit`` attribute (``"s"``, ``"ms"``);
- optional attributes ``instrument`` and ``trigger_time`` [s] on the dataset.

A dataset without a unit or a time axis is an error: nothing is assumed.

Hostile files: a dataset stored in external files or assembled from other files (a
virtual dataset) is refused, since reading it would return bytes of other files on the
machine; a dataset declaring more than :data:`~contactlab.traces.checks.MAX_SAMPLES` or
more bytes than :data:`MAX_COMPRESSION_RATIO` times the file's size is refused before it
is read; any error h5py raises on a damaged file becomes a TraceFormatError naming the
file and the dataset.
"""

import os

import numpy as np

from contactlab.errors import TraceFormatError
from contactlab.traces.binary import require
from contactlab.traces.checks import (
    MAX_SAMPLES,
    check_samples,
    fail,
    header_number,
    select_channel,
    uniform_interval,
)
from contactlab.traces.isolate import run_isolated
from contactlab.traces.textwrite import output_units
from contactlab.traces.trace import Trace
from contactlab.traces.units import SI_VALUE_UNITS, parse_unit
from contactlab.validation import check_choice

__all__ = ["read", "sniff", "write"]

SIGNATURE = b"\x89HDF\r\n\x1a\n"
_TIME_NAMES = ("t", "time")

MAX_COMPRESSION_RATIO = 200
"""Most bytes a dataset may declare per byte of the file: gzip packs a block of zeros ~800
to 1, a measured trace with noise (16-bit samples stored as float64) under 10; beyond 200
a file is taken for a decompression bomb."""


def sniff(head):
    """The HDF5 signature at the start of the file."""
    return head.raw.startswith(SIGNATURE)


def _h5py():
    return require("h5py", "HDF5 files")


def _text(value):
    return value.decode() if isinstance(value, bytes | np.bytes_) else str(value)


def _unit(path, where, attrs, kinds):
    unit = parse_unit(_text(attrs["unit"])) if "unit" in attrs else None
    if unit is None or unit.si not in kinds:
        raise fail(path, where, f"needs a 'unit' attribute in {'/'.join(kinds)}")
    return unit


def _channels(h5py, h5file):
    """Paths of the channel datasets: 1-D, numeric, not a time axis."""
    found = []

    def visit(name, obj):
        if (
            isinstance(obj, h5py.Dataset)
            and obj.ndim == 1
            and obj.dtype.kind in "iuf"
            and name.rsplit("/", 1)[-1] not in _TIME_NAMES
        ):
            found.append(name)

    h5file.visititems(visit)
    return found


def _load(path, dataset):
    """A dataset's values as float64, after refusing external, virtual and oversized ones."""
    where = f"dataset {dataset.name!r}"
    if dataset.is_virtual:
        raise fail(path, where, "is a virtual dataset (data from other files): refused")
    if dataset.external:
        raise fail(path, where, "is stored in external files: refused")
    if dataset.size > MAX_SAMPLES:
        raise fail(path, where, f"declares {dataset.size} samples (limit {MAX_SAMPLES})")
    declared = dataset.size * dataset.dtype.itemsize
    if declared > MAX_COMPRESSION_RATIO * max(os.path.getsize(path), 1):
        raise fail(
            path,
            where,
            f"declares {declared} bytes, over {MAX_COMPRESSION_RATIO} times the "
            "file's size (a decompression bomb?)",
        )
    return dataset[()].astype(np.float64)


def _time(path, dataset, n):
    where = f"dataset {dataset.name!r}"
    attrs = dataset.attrs
    if "sample_interval" in attrs and "start_time" in attrs:
        interval = header_number(
            path, where, "sample_interval", attrs["sample_interval"], positive=True
        )
        start = header_number(path, where, "start_time", attrs["start_time"])
        t = np.arange(n) * interval
        t += start
        return t, interval, "header"
    group = dataset.parent
    name = next((k for k in _TIME_NAMES if k in group), None)
    if name is None:
        raise fail(path, where, "no start_time/sample_interval attributes and no 't' dataset")
    time = group[name]
    if time.shape != (n,):
        raise fail(path, f"dataset {time.name!r}", f"has shape {time.shape}; the channel {n}")
    t = _unit(path, f"dataset {time.name!r}", time.attrs, ("s",)).to_si(_load(path, time))
    return t, (t[-1] - t[0]) / (n - 1) if n > 1 else None, "time column (mean spacing)"


def read(head, channel):
    """Read one channel of an HDF5 file (see the module docstring for the convention).

    The HDF5 library runs in a child process (:func:`~contactlab.traces.isolate.run_isolated`):
    a file that crashes it is refused instead of ending this process.

    Returns
    -------
    Trace
    """
    _h5py()  # the ImportError for a missing extra comes from this process
    return run_isolated(head.path, _read_path, head.path, channel)


def _read_path(path, channel):
    """Read one channel of the HDF5 file ``path`` (in the child process)."""
    h5py = _h5py()
    try:
        h5file = h5py.File(path, "r")
    except Exception as exc:  # h5py reports a corrupt file through several exception types
        raise fail(path, "binary", f"not a readable HDF5 file ({exc})") from exc
    try:
        with h5file:
            return _read_open(path, h5py, h5file, channel)
    except TraceFormatError:
        raise
    except Exception as exc:  # h5py: RuntimeError, KeyError, OSError, TypeError, decoding
        raise fail(path, "binary", f"damaged HDF5 file ({type(exc).__name__}: {exc})") from exc


def _read_open(path, h5py, h5file, channel):
    """Read one channel of an open HDF5 file."""
    names = _channels(h5py, h5file)
    if not names:
        raise fail(path, "binary", "no 1-D numeric dataset (channel)")
    name = names[select_channel(names, channel, path, "dataset list")]
    dataset = h5file[name]
    unit = _unit(path, f"dataset {name!r}", dataset.attrs, SI_VALUE_UNITS)
    values = unit.to_si(_load(path, dataset))
    t, interval, source = _time(path, dataset, values.size)
    attrs = {k: _text(v) if isinstance(v, bytes | str) else v for k, v in dataset.attrs.items()}
    trigger = attrs.get("trigger_time")
    if trigger is not None:
        trigger = header_number(path, f"dataset {name!r}", "trigger_time", trigger)
    metadata = {
        "format": "hdf5",
        "source": path,
        "instrument": attrs.get("instrument"),
        "channel": name,
        "channels": names,
        "sample_interval": interval,
        "sample_interval_source": source,
        "trigger_time": trigger,
        "time_unit": "s",
        "vertical_unit": unit.text,
        "header": attrs,
        "overrange": check_samples(t, values, path, lambda i: f"sample {i}"),
    }
    return Trace(t, values, unit.si, metadata)


def write(path, trace, *, name="trace/value", time="dataset", value_unit=None):
    """Write a trace to HDF5 in this module's convention.

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    name : str, default "trace/value"
        Dataset path of the channel.
    time : {"dataset", "attrs"}
        Store the times as a ``t`` dataset beside the channel (exact for any trace), or as
        ``start_time`` and ``sample_interval`` attributes (uniform sampling only).
    value_unit : str, optional
        Unit to store the values in (``"mV"``); default the trace's SI unit.
    """
    check_choice("time", time, ("dataset", "attrs"))
    h5py = _h5py()
    _, v_unit = output_units(trace, "s", value_unit)
    with h5py.File(path, "w") as h5file:
        dataset = h5file.create_dataset(name, data=v_unit.from_si(trace.values))
        dataset.attrs["unit"] = v_unit.text
        for key in ("instrument", "trigger_time"):
            if trace.metadata.get(key) is not None:
                dataset.attrs[key] = trace.metadata[key]
        if time == "attrs":
            dataset.attrs["sample_interval"] = uniform_interval(trace)
            dataset.attrs["start_time"] = trace.t[0]
        else:
            group = dataset.parent
            group.create_dataset("t", data=trace.t).attrs["unit"] = "s"
