"""Fuzzing the readers: whatever the bytes, a Trace or a TraceFormatError, nothing else.

A returned trace must still keep the readers' promises (equal lengths, strictly
increasing finite time, no NaN), so a mutation can never slip through half-read.
"""

import re
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from contactlab.errors import TraceFormatError
from contactlab.traces import Trace, read_trace, write_trace

TEXT_LAYOUTS = [
    "generic",
    "tektronix-tds",
    "tektronix-mso",
    "rigol-sequence",
    "rigol-seconds",
    "keysight",
    "picoscope",
    "lecroy",
]
SETTINGS = settings(
    max_examples=200,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)


def _valid_files():
    """Small valid files of every text layout, as bytes."""
    n = 24
    t = np.arange(n) * 1e-6
    t += -5e-6
    values = np.sin(np.arange(n)) * 1e-2
    values[7] = np.inf  # an overrange sample (written as ∞ by the PicoScope writer)
    trace = Trace(t, values, "V", {"sample_interval": 1e-6})
    finite = Trace(t, np.nan_to_num(values, posinf=0.5), "V", {"sample_interval": 1e-6})
    files = {}
    with tempfile.TemporaryDirectory() as directory:
        for fmt in TEXT_LAYOUTS:
            path = Path(directory) / fmt
            write_trace(path, trace if fmt == "picoscope" else finite, fmt)
            files[fmt] = path.read_bytes()
    return files


VALID = _valid_files()


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz") / "trace.csv"


def _check(path, fmt="auto", channel=None):
    try:
        trace = read_trace(path, format=fmt, channel=channel)
    except TraceFormatError as exc:
        assert str(path) in str(exc)
        return
    assert trace.t.shape == trace.values.shape
    assert np.isfinite(trace.t).all()
    assert (np.diff(trace.t) > 0).all()
    assert not np.isnan(trace.values).any()
    np.testing.assert_array_equal(
        trace.metadata["overrange"], np.flatnonzero(np.isinf(trace.values))
    )


@SETTINGS
@given(content=st.binary(max_size=3000))
def test_random_bytes(scratch, content):
    scratch.write_bytes(content)
    _check(scratch)


TOKENS = [*"0123456789.,-+eE \t\r\n;#[]()∞µxX\x00", "Infinity", "nan", "Volt"]


def _junk(min_size, max_size):
    return st.lists(st.sampled_from(TOKENS), min_size=min_size, max_size=max_size).map("".join)


MUTATION = st.tuples(
    st.sampled_from(["delete", "duplicate", "swap", "replace", "insert", "truncate"]),
    st.integers(min_value=0, max_value=10_000),
    st.integers(min_value=0, max_value=10_000),
    _junk(1, 8),
)


def _mutate(content, mutations):
    lines = content.split(b"\n")
    for kind, a, b, text in mutations:
        i, j = a % len(lines), b % len(lines)
        if kind == "delete" and len(lines) > 1:
            del lines[i]
        elif kind == "duplicate":
            lines.insert(i, lines[i])
        elif kind == "swap":
            lines[i], lines[j] = lines[j], lines[i]
        elif kind == "replace":
            line = lines[i]
            k = b % (len(line) + 1)
            lines[i] = line[:k] + text.encode() + line[k + 1 :]
        elif kind == "insert":
            lines.insert(i, text.encode())
        else:
            lines[i] = lines[i][: b % (len(lines[i]) + 1)]
            del lines[i + 1 :]
    return b"\n".join(lines)


@SETTINGS
@given(
    fmt=st.sampled_from(TEXT_LAYOUTS),
    mutations=st.lists(MUTATION, min_size=1, max_size=4),
    explicit=st.booleans(),
)
def test_mutated_valid_files(scratch, fmt, mutations, explicit):
    scratch.write_bytes(_mutate(VALID[fmt], mutations))
    _check(scratch, fmt if explicit else "auto")


CELL = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-5, 5).map(str),
    _junk(0, 6),
)


@SETTINGS
@given(
    fmt=st.sampled_from(TEXT_LAYOUTS),
    rows=st.lists(st.lists(CELL, min_size=0, max_size=5), max_size=30),
    channel=st.sampled_from([None, 0, 1, "CH1", "1"]),
)
def test_valid_header_with_random_rows(scratch, fmt, rows, channel):
    header = VALID[fmt].decode("utf-8").split("\n")
    keep = {"tektronix-tds": 0, "tektronix-mso": 21, "picoscope": 3, "lecroy": 5}.get(fmt, 2)
    if fmt == "generic":
        keep = 1
    body = "\n".join(",".join(cells) for cells in rows)
    scratch.write_bytes(("\n".join(header[:keep]) + "\n" + body).encode("utf-8"))
    _check(scratch, "auto", channel)


def _reference_traces():
    """What each valid file reads as: the reference a damaged copy may never contradict."""
    traces = {}
    with tempfile.TemporaryDirectory() as directory:
        for fmt, content in VALID.items():
            path = Path(directory) / fmt
            path.write_bytes(content)
            traces[fmt] = read_trace(path)
    return traces


REFERENCE = _reference_traces()


def _never_misread(path, fmt):
    """A TraceFormatError naming the file, or exactly the reference's first samples."""
    try:
        trace = read_trace(path, format=fmt)
    except TraceFormatError as exc:
        assert str(path) in str(exc)
        return False
    reference = REFERENCE[fmt]
    n = len(trace)
    np.testing.assert_array_equal(trace.t, reference.t[:n])
    np.testing.assert_array_equal(trace.values, reference.values[:n])
    return True


@SETTINGS
@given(fmt=st.sampled_from(TEXT_LAYOUTS), cut=st.integers(min_value=1))
def test_a_file_cut_anywhere_is_refused_or_read_exactly(scratch, fmt, cut):
    """A copy cut while written: no sample may change (4.8828125e-05 -> 4.8828125)."""
    content = VALID[fmt]
    scratch.write_bytes(content[: cut % len(content)])
    _never_misread(scratch, fmt)


@SETTINGS
@given(fmt=st.sampled_from(TEXT_LAYOUTS), rows=st.sets(st.integers(0, 60), min_size=1))
def test_decimal_commas_in_any_rows_are_refused_or_read_exactly(scratch, fmt, rows):
    lines = VALID[fmt].split(b"\n")
    for i in rows:
        if i < len(lines):
            lines[i] = re.sub(rb"(\d)\.(\d)", rb"\1,\2", lines[i])
    scratch.write_bytes(b"\n".join(lines))
    _never_misread(scratch, fmt)


def _binary_files():
    """Small valid HDF5 and TDMS files, as bytes."""
    t = np.arange(64) * 1e-6
    trace = Trace(t, np.sin(np.arange(64)) * 1e-2, "V", {"sample_interval": 1e-6})
    files = {}
    with tempfile.TemporaryDirectory() as directory:
        for fmt in ("hdf5", "tdms"):
            path = Path(directory) / fmt
            write_trace(path, trace, fmt)
            files[fmt] = path.read_bytes()
    return files


BINARY = _binary_files()


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    fmt=st.sampled_from(sorted(BINARY)),
    changes=st.lists(
        st.tuples(st.integers(min_value=0), st.integers(0, 255)), min_size=1, max_size=6
    ),
    cut=st.one_of(st.none(), st.integers(min_value=1)),
)
def test_mutated_binary_files(scratch, fmt, changes, cut):
    """Byte-mutated or cut HDF5 and TDMS files: a Trace or a TraceFormatError, nothing else
    (h5py's RuntimeError, KeyError, OSError, TypeError, UnicodeDecodeError were seen)."""
    content = bytearray(BINARY[fmt])
    for position, value in changes:
        content[position % len(content)] = value
    if cut is not None:
        content = content[: cut % len(content)]
    scratch.write_bytes(bytes(content))
    _check(scratch)
