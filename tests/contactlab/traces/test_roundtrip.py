"""Reading traces: round trips of every layout, literal instrument files, detection.

Each writer writes a trace of known content; reading it back must give the same sample
count, first and last time, sample interval and values. Literal files in the instruments'
own spellings check the readers independently of the writers.
"""

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from contactlab.errors import ParameterError, TraceFormatError
from contactlab.metrics import pulse_metrics
from contactlab.traces import FORMATS, Trace, detect_format, read_trace, write_trace

EPS = np.finfo(float).eps

START = -2.5e-4  # [s] time of sample number 0 (non-zero, as scopes write it)
INCREMENT = 4e-7  # [s]
FIRST = -600  # first sample number of the Rigol sequence layout
N = 1500


def _uniform_trace(unit="V", first=0):
    """A trace on t = START + n * INCREMENT, computed as the readers compute it."""
    n = np.arange(first, first + N)
    t = n * INCREMENT
    t += START
    rng = np.random.default_rng(6)
    values = rng.normal(0.0, 0.02, N)
    values[:4] = [0.0, -9.99e-07, 1.25e-3, -3.0]  # zero, engineering-notation cases
    return Trace(t, values, unit, {"sample_interval": INCREMENT})


# (format, writer options, values exact?, times exact?)
LAYOUTS = [
    ("generic", {}, True, True),
    ("generic", {"time_unit": "ms", "value_unit": "mV", "brackets": "()"}, False, False),
    ("generic", {"time_unit": "us", "value_unit": "uV"}, False, False),
    ("tektronix-tds", {}, True, True),
    ("tektronix-mso", {}, True, True),
    ("rigol-sequence", {"first_index": FIRST, "start": START, "increment": INCREMENT}, True, True),
    ("rigol-seconds", {}, True, True),
    ("keysight", {}, True, True),
    ("picoscope", {}, False, False),
    ("picoscope", {"time_unit": "s", "value_unit": "V"}, True, True),
    ("lecroy", {}, True, True),
]

# One correctly rounded scaling on writing (x 1000) and one on reading (/ 1000): at most
# one ulp each, so 2 ulp relative.
SCALED_RTOL = 2 * EPS
# The mean spacing (t[-1] - t[0]) / (N - 1) of times rounded to ~1e-16 relative to
# |t| ~ 1e-4 s, over a span of 6e-4 s: ~1e-15 relative to the interval.
SPACING_RTOL = 1e-13


@pytest.mark.parametrize(("fmt", "options", "exact_values", "exact_times"), LAYOUTS)
def test_text_round_trip(tmp_path, fmt, options, exact_values, exact_times):
    first = FIRST if fmt == "rigol-sequence" else 0
    trace = _uniform_trace(first=first)
    path = tmp_path / f"{fmt}.csv"
    write_trace(path, trace, fmt, **options)
    back = read_trace(path)
    assert back.metadata["format"] == fmt
    assert len(back) == N
    assert back.unit == "V"
    if exact_times:
        assert back.t[0] == trace.t[0]
        assert back.t[-1] == trace.t[-1]
        np.testing.assert_array_equal(back.t, trace.t)
    else:
        np.testing.assert_allclose(back.t, trace.t, rtol=SCALED_RTOL, atol=0)
    if exact_values:
        np.testing.assert_array_equal(back.values, trace.values)
    else:
        np.testing.assert_allclose(back.values, trace.values, rtol=SCALED_RTOL, atol=0)
    if back.metadata["sample_interval_source"] == "header":
        assert back.sample_interval == INCREMENT
    else:
        assert back.sample_interval == pytest.approx(INCREMENT, rel=SPACING_RTOL)
    assert back.metadata["overrange"].size == 0
    assert back.metadata["source"] == str(path)


def test_rigol_sequence_time_is_built_from_start_and_increment(tmp_path):
    path = tmp_path / "rigol.csv"
    path.write_text(
        "X,CH1,Start,Increment,\n"
        "Sequence,Volt,-6.000000e-03,2.000000e-06\n"
        "-3,1.20e-02,\n-2,1.16e-02,\n-1,-4.00e-03,\n0,0.00e+00,\n"
    )
    trace = read_trace(path)
    n = np.arange(-3, 1)
    np.testing.assert_array_equal(trace.t, -6e-3 + n * 2e-6)  # exactly start + n * increment
    np.testing.assert_array_equal(trace.values, [1.2e-2, 1.16e-2, -4e-3, 0.0])
    assert trace.sample_interval == 2e-6
    assert trace.metadata["sample_interval_source"] == "header"
    assert trace.metadata["header"]["lines"][1] == "Sequence,Volt,-6.000000e-03,2.000000e-06"


def test_rigol_multichannel_selects_by_name_and_index(tmp_path):
    path = tmp_path / "rigol2.csv"
    path.write_text(
        "X,CH1,CH2,Start,Increment,\nSequence,Volt,Volt,-1e-3,1e-6,\n0,0.1,0.2,\n1,0.3,0.4,\n"
    )
    assert read_trace(path, channel="CH2").values.tolist() == [0.2, 0.4]
    assert read_trace(path, channel=0).values.tolist() == [0.1, 0.3]
    assert read_trace(path, channel="ch 2").metadata["channels"] == ["CH1", "CH2"]


def test_keysight_engineering_notation_literal(tmp_path):
    path = tmp_path / "keysight.csv"
    path.write_text(
        "x-axis,1,2\nsecond,Volt,Volt\n"
        "-999.00E-09,1.2500E-03,-3.1250E-03\n-998.00E-09,2.5000E-03,-6.2500E-03\n"
    )
    trace = read_trace(path, channel="2")
    assert trace.t.tolist() == [-999e-9, -998e-9]
    assert trace.values.tolist() == [-3.125e-3, -6.25e-3]
    assert trace.metadata["vertical_unit"] == "Volt"


def test_tds_literal_header_fields(tmp_path):
    rows = [
        "Record Length,2.000000e+01,",
        "Sample Interval,4.000000e-07,",
        "Trigger Point,1.000000000000e+01,",
        ",,",
        ",,",
        "Source,CH2,",
        "Vertical Units,V,",
        "Vertical Scale,1.000000e-01,",
        "Vertical Offset,0.000000e+00,",
        ",,",
        "Horizontal Units,s,",
        "Horizontal Scale,5.000000e-07,",
        "Pt Fmt,Y,",
        "Yzero,0.000000e+00,",
        "Probe Atten,1.000000e+00,",
        "Model Number,TDS2012B,",
        "Serial Number,C012345,",
        "Firmware Version,FV:v22.11,",
    ] + [",,"] * 2
    times = [f"{-4e-6 + i * 4e-7:.12f}" for i in range(20)]
    lines = [
        f"{row},{t},{0.004 * i:.5f}," for i, (row, t) in enumerate(zip(rows, times, strict=True))
    ]
    path = tmp_path / "tds.csv"
    path.write_text("\n".join(lines) + "\n")
    trace = read_trace(path)
    assert trace.metadata["format"] == "tektronix-tds"
    assert trace.metadata["instrument"] == "TDS2012B"
    assert trace.metadata["channel"] == "CH2"
    assert trace.metadata["trigger_index"] == 10
    assert trace.metadata["header"]["Firmware Version"] == "FV:v22.11"
    assert trace.sample_interval == 4e-7
    assert trace.t.tolist() == [float(t) for t in times]  # the file's own time column
    assert trace.values[-1] == 0.076


def test_mso_literal_two_channels(tmp_path):
    path = tmp_path / "mso.csv"
    path.write_text(
        "Model,MDO3024\nFirmware Version,1.03\n,\nWaveform Type,ANALOG,\nPoint Format,Y,\n"
        "Horizontal Units,s,\nSample Interval,4e-08,\nRecord Length,3,\n"
        "Vertical Units,V,A\n,\nLabel,,\nTIME,CH1,CH2\n"
        "-4e-08,0.01,0.5\n0,0.02,0.6\n4e-08,0.03,0.7\n"
    )
    ch2 = read_trace(path, channel="CH2")
    assert ch2.unit == "A"
    assert ch2.values.tolist() == [0.5, 0.6, 0.7]
    assert ch2.metadata["instrument"] == "MDO3024"
    assert ch2.metadata["header"]["Record Length"] == "3,"


def test_picoscope_overrange_is_flagged_not_dropped(tmp_path):
    path = tmp_path / "pico.csv"
    path.write_text(
        "Time,Channel A\n(us),(mV)\n\n"
        "-1.0,0.5\n0.0,∞\n1.0,-∞\n2.0,Infinity\n3.0,-Infinity\n4.0,12.5\n",
        encoding="utf-8",
    )
    trace = read_trace(path)
    assert len(trace) == 6
    assert trace.metadata["overrange"].tolist() == [1, 2, 3, 4]
    assert trace.values[[1, 3]].tolist() == [np.inf, np.inf]
    assert trace.values[[2, 4]].tolist() == [-np.inf, -np.inf]
    assert trace.values[-1] == 12.5 / 1000
    assert trace.t[0] == -1.0 / 1e6
    with pytest.raises(ParameterError, match="overrange"):
        trace.metrics()


@pytest.mark.parametrize("infinity", ["∞", "Infinity"])
def test_picoscope_writer_round_trips_overrange(tmp_path, infinity):
    trace = _uniform_trace()
    values = trace.values.copy()
    values[[5, 9]] = [np.inf, -np.inf]
    trace = dataclasses.replace(trace, values=values, metadata={})
    path = tmp_path / "pico.csv"
    write_trace(path, trace, "picoscope", time_unit="s", value_unit="V", infinity=infinity)
    back = read_trace(path)
    assert back.metadata["overrange"].tolist() == [5, 9]
    np.testing.assert_array_equal(back.values, values)


def test_lecroy_literal(tmp_path):
    path = tmp_path / "lecroy.csv"
    path.write_text(
        "LECROYWR6100A,40123,Waveform\nSegments,1,SegmentSize,3\n"
        "Segment,TrigTime,TimeSinceSegment1\n#1,16-Nov-2012 12:35:47,0\nTime,Ampl\n"
        "-5e-06,0.001\n-4.9e-06,0.002\n-4.8e-06,0.003\n"
    )
    trace = read_trace(path)
    assert trace.metadata["instrument"] == "LECROYWR6100A"
    assert trace.metadata["trigger_timestamp"] == "16-Nov-2012 12:35:47"
    assert trace.metadata["units_stated"] is False
    assert trace.t.tolist() == [-5e-06, -4.9e-06, -4.8e-06]


@pytest.mark.parametrize(
    ("header", "rows", "t_scale", "v_scale", "unit"),
    [
        ("t [s],Voltage [V]", "1,2\n3,4\n", 1.0, 1.0, "V"),
        ("Time (ms),signal (mV)", "1,2\n3,4\n", 1e-3, 1e-3, "V"),
        ("time [us]\tforce [N]", "1\t2\n3\t4\n", 1e-6, 1.0, "N"),
        ("t [s];U [V]", "1;2\n3;4\n", 1.0, 1.0, "V"),
        ("value [kN],t [ns]", "2,1\n4,3\n", 1e-9, 1e3, "N"),
    ],
)
def test_generic_header_units(tmp_path, header, rows, t_scale, v_scale, unit):
    path = tmp_path / "generic.csv"
    path.write_text(f"# instrument: bench rig\n{header}\n{rows}")
    trace = read_trace(path)
    assert trace.unit == unit
    # One correctly rounded scaling of exact integers: within an ulp.
    np.testing.assert_allclose(trace.t, np.array([1.0, 3.0]) * t_scale, rtol=EPS, atol=0)
    np.testing.assert_allclose(trace.values, np.array([2.0, 4.0]) * v_scale, rtol=EPS, atol=0)
    assert trace.metadata["instrument"] == "bench rig"


def test_crlf_latin1_and_trailing_blank_lines(tmp_path):
    path = tmp_path / "windows.csv"
    path.write_bytes("t [s],v [µV]\r\n0,1\r\n1e-6,2\r\n\r\n\r\n".encode("latin-1"))
    trace = read_trace(path)
    assert trace.values.tolist() == [1e-6, 2e-6]
    assert trace.metadata["encoding"] == "latin-1"


def test_detection_by_content_not_extension(tmp_path):
    trace = _uniform_trace()
    names = {"rigol-sequence": "scope.txt", "keysight": "data.dat", "picoscope": "x.rigol"}
    for fmt, name in names.items():
        write_trace(tmp_path / name, trace, fmt)
        assert detect_format(tmp_path / name) == fmt
        assert read_trace(tmp_path / name).metadata["format"] == fmt


def test_every_layout_has_a_writer_and_is_detected(tmp_path):
    text_layouts = {fmt for fmt, *_ in LAYOUTS}
    for fmt in text_layouts:
        path = tmp_path / f"{fmt}.bin"
        write_trace(path, _uniform_trace(), fmt)
        assert detect_format(path) == fmt
    assert text_layouts | {"hdf5", "tdms", "scope-binary"} == set(FORMATS)


def test_explicit_format_and_unknown_name(tmp_path):
    path = tmp_path / "x.csv"
    write_trace(path, _uniform_trace(), "generic")
    assert read_trace(path, format="generic").metadata["format"] == "generic"
    with pytest.raises(ParameterError, match="did you mean 'rigol-sequence'"):
        read_trace(path, format="rigol-sequnce")
    with pytest.raises(TraceFormatError, match=r"x\.csv, line 1"):
        read_trace(path, format="keysight")


def test_writer_rejects_unknown_options_and_non_uniform_time(tmp_path):
    trace = _uniform_trace()
    with pytest.raises(TypeError):
        write_trace(tmp_path / "a.csv", trace, "generic", colour="red")
    t = trace.t.copy()
    t[5] += 0.5 * INCREMENT
    uneven = Trace(t, trace.values, "V")
    with pytest.raises(ParameterError, match="non-uniform"):
        write_trace(tmp_path / "b.csv", uneven, "rigol-sequence")
    with pytest.raises(ParameterError, match="volts"):
        write_trace(tmp_path / "c.csv", Trace(t, trace.values, "N"), "keysight")
    # a misspelt layout option would write a file the reader cannot read (or silently
    # another layout): refused by name
    for fmt, option in [
        ("generic", {"brackets": "<>"}),
        ("picoscope", {"infinity": "inf!"}),
        ("hdf5", {"time": "attr"}),
    ]:
        with pytest.raises(ParameterError, match=f"{next(iter(option))} must be one of"):
            write_trace(tmp_path / f"d.{fmt}", trace, fmt, **option)
        assert not (tmp_path / f"d.{fmt}").exists()


def test_sensitivity_converts_volts_to_newtons(tmp_path):
    path = tmp_path / "v.csv"
    write_trace(path, _uniform_trace(), "generic")
    trace = read_trace(path, sensitivity=0.0225)
    assert trace.unit == "N"
    # One correctly rounded division.
    np.testing.assert_allclose(trace.values, _uniform_trace().values / 0.0225, rtol=EPS)
    assert trace.metadata["sensitivity [V/N]"] == 0.0225
    assert trace.metadata["history"][-1] == {"step": "to_force", "sensitivity [V/N]": 0.0225}
    assert list(trace.to_frame().columns) == ["t [s]", "force [N]"]
    newtons = tmp_path / "n.csv"
    write_trace(newtons, trace, "generic")
    with pytest.raises(ParameterError, match=r"not 'V'"):
        read_trace(newtons, sensitivity=0.0225)
    with pytest.raises(ParameterError, match="sensitivity"):
        read_trace(path, sensitivity=-1.0)


def test_trace_is_read_only_and_metrics_match_contactlab(tmp_path):
    t = np.linspace(-1e-4, 4e-4, 501)
    pulse = np.where((t > 0) & (t < 2e-4), np.sin(np.pi * t / 2e-4), 0.0)
    trace = Trace(t, pulse, "N")
    with pytest.raises(ValueError, match="read-only"):
        trace.values[0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        trace.unit = "V"
    assert trace.metrics(0.1) == pulse_metrics(t, pulse, 0.1)
    assert list(trace.to_frame().columns) == ["t [s]", "force [N]"]
    for unit in ("mV", "", None):  # values are in SI base units, nothing else
        with pytest.raises(ParameterError, match="unit must be one of V, N, A"):
            Trace(t, pulse, unit)


# --- binary formats ------------------------------------------------------------------


@pytest.mark.parametrize("time", ["dataset", "attrs"])
def test_hdf5_round_trip(tmp_path, time):
    pytest.importorskip("h5py")
    trace = _uniform_trace()
    path = tmp_path / "trace.h5"
    write_trace(path, trace, "hdf5", time=time, value_unit="mV")
    back = read_trace(path)
    assert back.metadata["format"] == "hdf5"
    assert back.metadata["channel"] == "trace/value"
    np.testing.assert_array_equal(back.t, trace.t)  # start + n * increment, as written
    # One correctly rounded scaling each way (V -> mV -> V): 2 ulp.
    np.testing.assert_allclose(back.values, trace.values, rtol=SCALED_RTOL, atol=0)
    assert back.sample_interval == pytest.approx(INCREMENT, rel=SPACING_RTOL)


def test_tdms_round_trip(tmp_path):
    pytest.importorskip("nptdms")
    trace = _uniform_trace()
    path = tmp_path / "trace.tdms"
    write_trace(path, trace, "tdms", group="impact", channel="sensor")
    back = read_trace(path, channel="impact/sensor")
    assert back.metadata["format"] == "tdms"
    np.testing.assert_array_equal(back.t, trace.t)
    np.testing.assert_array_equal(back.values, trace.values)
    assert back.sample_interval == INCREMENT


@pytest.mark.parametrize(
    ("fmt", "options", "module"),
    [("tdms", {}, "nptdms"), ("hdf5", {"time": "attrs"}, "h5py"), ("rigol-sequence", {}, None)],
)
def test_start_and_interval_layouts_keep_every_sample_time(tmp_path, fmt, options, module):
    """A declared interval 5e-5 off the time column passes a step-by-step check, but
    ``start + n * declared`` drifts a whole sample over 20 000 samples: the writers must
    store an interval that gives back every time."""
    if module is not None:
        pytest.importorskip(module)
    n = 20_000
    t = np.arange(n) * 1.00005e-6
    trace = Trace(t, np.zeros(n), "V", {"sample_interval": 1e-6})
    path = tmp_path / f"drift.{fmt}"
    write_trace(path, trace, fmt, **options)
    back = read_trace(path)
    assert back.sample_interval == pytest.approx(1.00005e-6, rel=1e-12)  # the spacing, to rounding
    # the writers' promise: every time within UNIFORM_RTOL (1e-4) of an interval
    np.testing.assert_allclose(back.t, t, rtol=0, atol=1e-4 * 1.00005e-6)


def _write_isf(path, codes, ymult, xincr, xzero):
    """A Tektronix ISF file as the TDS programmer manuals define it: the WFMPRE header,
    then ``:CURVE`` and an IEEE 488.2 definite-length block of big-endian int16 codes."""
    header = (
        ':WFMPRE:BYT_NR 2;BIT_NR 16;ENCDG BIN;BN_FMT RI;BYT_OR MSB;WFID "Ch1, DC coupling";'
        f'NR_PT {codes.size};PT_FMT Y;XUNIT "s";XINCR {xincr:.6E};XZERO {xzero:.6E};PT_OFF 0;'
        f'YUNIT "V";YMULT {ymult:.6E};YOFF 0.0E0;YZERO 0.0E0;:CURVE '
    )
    data = codes.astype(">i2").tobytes()
    count = str(len(data))
    path.write_bytes(header.encode() + f"#{len(count)}{count}".encode() + data + b"\n")


def test_isf_through_rigolwfm(tmp_path):
    pytest.importorskip("RigolWFM")
    codes = np.round(20000 * np.sin(np.linspace(0, 6, 500))).astype(np.int16)
    path = tmp_path / "scope.csv"  # extension deliberately misleading
    _write_isf(path, codes, ymult=8e-6, xincr=2e-7, xzero=-5e-5)
    trace = read_trace(path, channel="CH1")
    assert trace.metadata["format"] == "scope-binary"
    assert len(trace) == 500
    np.testing.assert_array_equal(trace.t, -5e-5 + np.arange(500) * 2e-7)
    # RigolWFM computes ISF volts in float32: equal to the float32 of code * YMULT.
    np.testing.assert_array_equal(trace.values, (codes * 8e-6).astype(np.float32))
    assert trace.sample_interval == 2e-7


@pytest.mark.parametrize(
    ("module", "fmt", "suffix"),
    [("h5py", "hdf5", "h5"), ("nptdms", "tdms", "tdms"), ("RigolWFM.wfm", "scope-binary", "isf")],
)
def test_missing_extra_names_it(tmp_path, monkeypatch, module, fmt, suffix):
    path = tmp_path / f"x.{suffix}"
    if fmt == "scope-binary":
        _write_isf(path, np.zeros(20, dtype=np.int16), 1e-3, 1e-6, 0.0)
    else:
        pytest.importorskip(module)
        write_trace(path, _uniform_trace(), fmt)
    monkeypatch.setitem(sys.modules, module, None)  # makes `import module` fail
    with pytest.raises(ImportError, match=r"pip install contactlab\[traces\]"):
        read_trace(path)


def test_tds_without_source_does_not_guess_the_channel(tmp_path):
    """A TDS export whose header lost its Source row keeps every sample, and the channel is
    called "unknown" rather than guessed."""
    sample = Path(__file__).resolve().parents[3] / "data" / "traces" / "tek_tds.csv"
    lines = sample.read_text().splitlines(keepends=True)
    assert lines[5].startswith("Source,CH1,")
    lines[5] = ",," + lines[5].split(",", 2)[2]
    path = tmp_path / "no_source.csv"
    path.write_text("".join(lines))
    trace, reference = read_trace(path), read_trace(sample)
    assert trace.metadata["channel"] == "unknown"
    np.testing.assert_array_equal(trace.values, reference.values)
