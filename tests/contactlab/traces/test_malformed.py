"""Malformed trace files: each is reported with the file name and the 1-based line.

Nothing is repaired silently: every case below is a TraceFormatError (a ValueError), and
the one usable defect, overrange, is a flag in the metadata (tested with the readers).
"""

import re

import numpy as np
import pytest

from contactlab.errors import ParameterError, TraceFormatError
from contactlab.traces import Trace, read_trace, write_trace

GENERIC = "t [s],v [V]\n"
RIGOL = "X,CH1,Start,Increment,\nSequence,Volt,-1e-3,1e-6\n"
PICO = "Time,Channel A\n(ms),(mV)\n\n"
LECROY = (
    "LECROYWR6100A,1,Waveform\nSegments,1,SegmentSize,{n}\nSegment,TrigTime,TimeSinceSegment1\n"
)


def _tds(record_length="7", interval="1e-06", point_format="Y"):
    keys = [
        ("Record Length", record_length),
        ("Sample Interval", interval),
        ("Trigger Point", "0"),
        ("Source", "CH1"),
        ("Vertical Units", "V"),
        ("Horizontal Units", "s"),
        ("Pt Fmt", point_format),
    ]
    rows = [f"{k},{v},,{i * 1e-6!r},0.5," for i, (k, v) in enumerate(keys)]
    return "\n".join(rows) + "\n"


CASES = {
    "empty file": ("", 1, "empty"),
    "header without data": (GENERIC, 2, "no data rows"),
    "rigol header without data": (RIGOL, 3, "no data rows"),
    "picoscope header without data": (PICO, 4, "no data rows"),
    "time going back": (GENERIC + "0,1\n2e-6,1\n1e-6,1\n", 4, "going back"),
    "duplicated time": (GENERIC + "0,1\n1e-6,1\n1e-6,1\n", 4, "duplicated"),
    "missing cell": (GENERIC + "0,1\n1e-6,\n2e-6,1\n", 3, "missing cell"),
    "missing time cell": (GENERIC + "0,1\n,1\n", 3, "column 't': missing cell"),
    "short row": (GENERIC + "0,1\n1e-6\n", 3, "1 cells where the header has 2"),
    "extra cell": (GENERIC + "0,1\n1e-6,1,3\n", 3, "3 cells where the header has 2"),
    "blank line inside data": (GENERIC + "0,1\n\n2e-6,1\n", 3, "blank line"),
    "non-numeric cell": (GENERIC + "0,1\n1e-6,abc\n", 3, "'abc' is not a number"),
    "NaN cell": (GENERIC + "0,1\n1e-6,nan\n", 3, "'nan' is not a number"),
    # pandas' fast parser reads a column made only of these words as 1.0 and 0.0
    "boolean words": (GENERIC + "0,TRUE\n1e-6,FALSE\n", 2, "'TRUE' is not a number"),
    "rigol boolean sequence": (RIGOL + "False,1,\nTrue,2,\n", 3, "'False' is not a number"),
    "quoted number": (GENERIC + '0,1\n1e-6,"2"\n', 3, "is not a number"),
    "unit in a cell": (GENERIC + "0,1\n1e-6,1.2mV\n", 3, "carries a unit"),
    "two units in a header cell": ("t [s] (ms),v [V]\n0,1\n", 1, "mixed units"),
    "no unit in header": ("time,v [V]\n0,1\n", 1, "has no unit"),
    "unknown unit": ("t [s],v [furlong]\n0,1\n", 1, "'furlong' is not a known value unit"),
    "value unit for time": ("t [V],v [V]\n0,1\n", 1, "exactly one time column"),
    "infinite time": (GENERIC + "0,1\ninf,1\n", 3, "infinite time"),
    "stray carriage return": (GENERIC + "0,1\n1e-6,2\r3e-6,4\n", 3, "3 cells"),
    "rigol gap in sequence": (RIGOL + "0,1,\n1,2,\n3,3,\n", 5, "does not follow"),
    "rigol fractional sequence": (RIGOL + "0,1,\n1.5,2,\n", 4, "not an integer"),
    "rigol bad increment": (RIGOL.replace("1e-6", "x"), 2, "Increment 'x'"),
    "picoscope time unit in volts": ("Time,Channel A\n(mV),(mV)\n\n0,1\n", 2, "time unit"),
    "tds truncated record": (_tds(record_length="9"), 1, "declares 9 samples"),
    "tds interval in other units": (_tds(interval="1e-03"), 2, "mixed or wrong units"),
    "tds envelope": (_tds(point_format="ENV"), 7, "envelope"),
    "lecroy segmented": (
        LECROY.format(n=1).replace("Segments,1", "Segments,2") + "#1,x,0\n#2,x,0\nTime,Ampl\n",
        2,
        "segmented",
    ),
    "lecroy size mismatch": (LECROY.format(n=5) + "#1,x,0\nTime,Ampl\n0,1\n1e-6,2\n", 2, "holds 2"),
    "multichannel without channel": (
        "x-axis,1,2\nsecond,Volt,Volt\n0,1,2\n",
        1,
        r"2 channels \('1', '2'\); pass channel=",
    ),
}


@pytest.mark.parametrize("case", CASES)
def test_malformed_file_names_file_and_line(tmp_path, case):
    text, line, message = CASES[case]
    path = tmp_path / "bad_trace.csv"
    path.write_bytes(text.encode("utf-8"))
    with pytest.raises(TraceFormatError, match=message) as info:
        read_trace(path)
    assert f"bad_trace.csv, line {line}:" in str(info.value)
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize(
    ("channel", "message"),
    [
        ("CH9", r"no channel 'CH9'; available: 'CH1', 'CH2'"),
        (5, r"no channel 5; available"),
        (True, r"no channel True"),
    ],
)
def test_wrong_channel_lists_the_available_ones(tmp_path, channel, message):
    path = tmp_path / "two.csv"
    path.write_text(RIGOL.replace("CH1,", "CH1,CH2,").replace("Volt,", "Volt,Volt,") + "0,1,2,\n")
    with pytest.raises(TraceFormatError, match=message) as info:
        read_trace(path, channel=channel)
    assert "two.csv, line 1:" in str(info.value)


def test_index_that_is_another_channels_name_is_ambiguous(tmp_path):
    path = tmp_path / "keysight.csv"
    path.write_text("x-axis,1,2\nsecond,Volt,Volt\n0,1,2\n")
    with pytest.raises(TraceFormatError, match="ambiguous"):
        read_trace(path, channel=1)
    assert read_trace(path, channel="1").values.tolist() == [1.0]


def test_bad_line_deep_in_a_large_file_is_located(tmp_path):
    n = 200_000
    path = tmp_path / "large.csv"
    t = np.arange(n) * 1e-6
    write_trace(path, Trace(t, np.zeros(n), "V"), "generic")
    lines = path.read_text().splitlines()
    bad = 150_000  # 0-based data row; its line is bad + 2 (1-based, after the header)
    lines[bad + 1] = lines[bad + 1].replace(",0.0", ",0.0.1")
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(TraceFormatError, match=re.escape(f"line {bad + 2}: column 'value'")):
        read_trace(path)


def _h5(tmp_path, name, datasets):
    """An HDF5 file of ``{dataset: (values, attributes)}``, written in that order."""
    h5py = pytest.importorskip("h5py")
    path = tmp_path / name
    with h5py.File(path, "w") as f:
        for key, (values, attrs) in datasets.items():
            f[key] = values
            f[key].attrs.update(attrs)
    return path


def _tdms(tmp_path, name, properties):
    """A TDMS file of one channel ``g/c`` of four zeros with these properties."""
    nptdms = pytest.importorskip("nptdms")
    path = tmp_path / name
    with nptdms.TdmsWriter(path) as writer:
        writer.write_segment([nptdms.ChannelObject("g", "c", np.zeros(4), properties)])
    return path


def _refused(path, message):
    """Reading ``path`` is a TraceFormatError naming the file, then ``message``."""
    with pytest.raises(TraceFormatError, match=re.escape(f"{path.name}, {message}")):
        read_trace(path)


def test_hdf5_without_unit_names_the_dataset(tmp_path):
    datasets = {"trace/value": (np.zeros(3), {}), "trace/t": (np.arange(3.0), {"unit": "s"})}
    path = _h5(tmp_path, "nounit.h5", datasets)
    _refused(path, "dataset 'trace/value': needs a 'unit'")


def test_hdf5_time_going_back_names_the_sample(tmp_path):
    t = np.array([0.0, 2.0, 1.0])
    path = _h5(tmp_path, "back.h5", {"v": (np.zeros(3), {"unit": "V"}), "t": (t, {"unit": "ms"})})
    _refused(path, "sample 2: time 0.001 s is going back")


def test_tdms_without_time_axis(tmp_path):
    path = _tdms(tmp_path, "notime.tdms", {"unit_string": "Volts"})
    _refused(path, "channel 'g/c': no wf_increment")


@pytest.mark.parametrize("interval", [0.0, -1e-6, np.inf, "1 us"])
def test_tdms_bad_time_axis_property_is_named(tmp_path, interval):
    path = _tdms(tmp_path, "badtime.tdms", {"unit_string": "V", "wf_increment": interval})
    _refused(path, f"channel 'g/c': wf_increment {interval!r}")


@pytest.mark.parametrize(
    ("attrs", "message"),
    [
        ({"sample_interval": 0.0, "start_time": 0.0}, "sample_interval 0.0 is not a finite"),
        ({"sample_interval": 1e-6, "start_time": "soon"}, "start_time 'soon' is not a finite"),
        ({"sample_interval": 1e-6, "start_time": 0.0, "trigger_time": "x"}, "trigger_time 'x'"),
    ],
)
def test_hdf5_bad_time_attribute_is_named(tmp_path, attrs, message):
    path = _h5(tmp_path, "badtime.h5", {"v": (np.zeros(4), {"unit": "V", **attrs})})
    with pytest.raises(
        TraceFormatError, match=r"badtime\.h5, dataset '/?v': " + re.escape(message)
    ):
        read_trace(path)


@pytest.mark.parametrize(
    "content",
    [
        b"\x00\x01garbage" * 10,
        b"RG01" + bytes(200),
        b"\x89HDF\r\n\x1a\n" + bytes(100),
        b"TDSm" + bytes(40),
    ],
)
def test_corrupt_binaries(tmp_path, content):
    pytest.importorskip("RigolWFM")
    pytest.importorskip("h5py")
    pytest.importorskip("nptdms")
    path = tmp_path / "corrupt.bin"
    path.write_bytes(content)
    with pytest.raises(TraceFormatError, match=re.escape("corrupt.bin, binary")):
        read_trace(path)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"name": "force,left"}, "name = 'force,left' contains a comma"),
        ({"comments": {"note": "two\nlines"}}, "comments['note'] = 'two\\nlines' contains a line"),
        ({"format": "picoscope", "channel": "A\rB"}, "channel = 'A\\rB' contains a comma"),
    ],
)
def test_writer_text_that_would_not_read_back_is_refused(tmp_path, options, message):
    trace = Trace(np.arange(4) * 1e-6, np.arange(4.0), "V")
    with pytest.raises(ParameterError, match=re.escape(message)):
        write_trace(tmp_path / "out.csv", trace, **options)
    assert not (tmp_path / "out.csv").exists()  # refused before anything is written


def test_commas_in_comments_are_fine(tmp_path):
    trace = Trace(np.arange(4) * 1e-6, np.arange(4.0), "V")
    write_trace(tmp_path / "out.csv", trace, comments={"note": "grain 5 mm, 2 m/s"})
    comments = read_trace(tmp_path / "out.csv").metadata["header"]["comments"]
    assert comments["note"] == "grain 5 mm, 2 m/s"
