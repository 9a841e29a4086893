"""Oscilloscope binaries through RigolWFM: LeCroy .trc, Rigol DS1000E .wfm, Tektronix .isf.

RigolWFM ships no sample files, and no instrument file with a known licence is at hand,
so each test writes a small file from the vendor's layout: the ``WAVEDESC`` block of
Teledyne LeCroy's template ``LECROY_2_3`` (what the scope's ``TEMPLATE?`` query prints),
and the header of Rigol's "DS1000E/D WFM structure instruction". The field offsets are
those documents' as RigolWFM's Kaitai descriptions (``RigolWFM/lecroy_2_3_le_trc.py``,
``RigolWFM/rigol_1000e_wfm.py``) restate them, so these tests check the reading path
(detection, RigolWFM, calibration, time axis, errors), not RigolWFM's reading of the
documents. Only the fields a reader needs are filled; the rest are zero."""

import struct

import numpy as np
import pytest

from contactlab.errors import TraceFormatError
from contactlab.traces import detect_format, read_trace

pytest.importorskip("RigolWFM")

N = 8192  # samples: a DS1000E record with both channels on (8k long memory)
PRE = 1638  # samples before the trigger (20 %)


def _pulse_codes(amplitude, noise, seed):
    """ADC codes of a half-sine pulse of 50 us at 5 MS/s after PRE samples, with noise."""
    n = np.arange(N) - PRE
    pulse = np.where((n >= 0) & (n < 250), np.sin(np.pi * n / 250), 0.0)
    rng = np.random.default_rng(seed)
    return np.round(amplitude * pulse + rng.normal(0.0, noise, N)).astype(int)


# --- LeCroy .trc ------------------------------------------------------------------------

WAVEDESC_BYTES = 346
"""Length of the LECROY_2_3 WAVEDESC block [B]."""


def _lecroy_trc(codes, *, gain, offset, interval, horiz_offset, word=True, prefix=True):
    """A LeCroy .trc file: WAVEDESC (LECROY_2_3, little-endian), then WAVE_ARRAY_1.

    Volts are ``VERTICAL_GAIN * code - VERTICAL_OFFSET``, times
    ``HORIZ_OFFSET + i * HORIZ_INTERVAL``. Files saved by the scope start with the IEEE
    488.2 block header ``#9<nine digits>`` of the remote transfer (``prefix``).
    """
    data = codes.astype("<i2" if word else "i1").tobytes()
    desc = bytearray(WAVEDESC_BYTES)
    fields = [  # (offset [B], struct format, value), as the template numbers them
        (0, "16s", b"WAVEDESC"),
        (16, "16s", b"LECROY_2_3"),
        (32, "H", 1 if word else 0),  # COMM_TYPE: word (16-bit) or byte samples
        (34, "H", 1),  # COMM_ORDER: LOFIRST (little-endian)
        (36, "l", WAVEDESC_BYTES),  # WAVE_DESCRIPTOR
        (60, "l", len(data)),  # WAVE_ARRAY_1 [B]
        (76, "16s", b"LECROYWR6100A"),  # INSTRUMENT_NAME
        (116, "l", codes.size),  # WAVE_ARRAY_COUNT
        (120, "l", codes.size),  # PNTS_PER_SCREEN
        (128, "l", codes.size - 1),  # LAST_VALID_PNT
        (136, "l", 1),  # SPARSING_FACTOR
        (144, "l", 1),  # SUBARRAY_COUNT
        (148, "l", 1),  # SWEEPS_PER_ACQ
        (156, "f", gain),  # VERTICAL_GAIN [V/count]
        (160, "f", offset),  # VERTICAL_OFFSET [V]
        (164, "f", 32512.0 if word else 127.0),  # MAX_VALUE [count]
        (168, "f", -32768.0 if word else -128.0),  # MIN_VALUE [count]
        (172, "h", 8),  # NOMINAL_BITS
        (174, "h", 1),  # NOM_SUBARRAY_COUNT
        (176, "f", interval),  # HORIZ_INTERVAL [s]
        (180, "d", horiz_offset),  # HORIZ_OFFSET [s]
        (196, "48s", b"V"),  # VERTUNIT
        (244, "48s", b"S"),  # HORUNIT
        (326, "H", 2),  # VERT_COUPLING: DC, 1 MOhm
        (328, "f", 1.0),  # PROBE_ATT
        (344, "H", 0),  # WAVE_SOURCE: channel 1
    ]
    for at, fmt, value in fields:
        struct.pack_into("<" + fmt, desc, at, value)
    body = bytes(desc) + data
    return (f"#9{len(body):09d}".encode() if prefix else b"") + body


@pytest.mark.parametrize(("word", "prefix"), [(True, True), (False, True), (True, False)])
def test_lecroy_trc(tmp_path, word, prefix):
    codes = _pulse_codes(100.0 if word else 60.0, 1.5, seed=1)
    gain, offset, interval, horiz_offset = 2.5e-4, -1.25e-3, 2e-7, -PRE * 2e-7
    path = tmp_path / "C1impact00000.trc"
    path.write_bytes(
        _lecroy_trc(
            codes,
            gain=gain,
            offset=offset,
            interval=interval,
            horiz_offset=horiz_offset,
            word=word,
            prefix=prefix,
        )
    )
    assert detect_format(path) == "scope-binary"
    trace = read_trace(path, channel="CH1")
    assert trace.metadata["instrument"] == "LECROYWR6100A"
    assert len(trace) == N
    # Gain, offset and interval are float32 fields; RigolWFM returns float32 volts.
    f32 = np.float32
    volts = (float(f32(gain)) * codes - float(f32(offset))).astype(f32)
    np.testing.assert_array_equal(trace.values, volts)
    assert trace.sample_interval == float(f32(interval))
    np.testing.assert_array_equal(trace.t, horiz_offset + np.arange(N) * float(f32(interval)))


def test_truncated_lecroy_trc_is_a_format_error(tmp_path):
    codes = _pulse_codes(100.0, 1.5, seed=2)
    content = _lecroy_trc(
        codes, gain=2.5e-4, offset=0.0, interval=2e-7, horiz_offset=0.0, prefix=False
    )
    path = tmp_path / "cut.trc"
    path.write_bytes(content[: WAVEDESC_BYTES - 40])  # the descriptor itself is cut
    with pytest.raises(TraceFormatError, match=r"cut\.trc, binary: not a readable"):
        read_trace(path)


# --- Rigol DS1000E .wfm -----------------------------------------------------------------

RIGOL_HEADER_BYTES = 276
"""Length of the DS1000E/D header [B]; channel 1's bytes follow it."""


def _rigol_ds1000e_wfm(raw, *, scale_uv, shift, sample_rate, offset_ps):
    """A Rigol DS1000E .wfm file with channel 1 only.

    Volts are ``scale * (125 - raw) - shift * scale`` with ``scale = scale_uv * 1e-6 /
    25`` (25 counts per division); time is sample-aligned around the trigger:
    ``offset - N / (2 rate) + n / rate`` with ``offset = offset_ps * 1e-12``.
    """
    header = bytearray(RIGOL_HEADER_BYTES)
    fields = [  # (offset [B], struct format, value)
        (0, "4s", b"\xa5\xa5\x00\x00"),  # file mark
        (28, "I", raw.size),  # channel 1 points
        (34 + 10, "f", 1.0),  # channel 1: probe attenuation
        (34 + 15, "B", 1),  # channel 1: enabled
        (34 + 18, "i", scale_uv),  # channel 1: vertical scale [uV/div]
        (34 + 22, "h", shift),  # channel 1: vertical position [counts]
        (84 + 16, "f", sample_rate),  # time base: sample rate [Hz]
        (84 + 20, "q", 50_000_000),  # time base: scale [ps/div]
        (84 + 28, "q", offset_ps),  # time base: delay [ps]
    ]
    for at, fmt, value in fields:
        struct.pack_into("<" + fmt, header, at, value)
    return bytes(header) + raw.astype(np.uint8).tobytes()


def test_rigol_ds1000e_wfm(tmp_path):
    codes = _pulse_codes(90.0, 1.0, seed=3)
    shift = -60  # the baseline sits 60 counts below the screen's middle
    raw = 125 - (codes + shift)
    assert raw.min() >= 0 and raw.max() <= 255  # the pulse fits the 8-bit range
    rate, scale_uv = 5e6, 20_000  # 5 MS/s, 20 mV/div
    offset_ps = round((N / 2 - PRE) / rate * 1e12)  # trigger 20 % into the record
    path = tmp_path / "DS1102E.wfm"
    path.write_bytes(
        _rigol_ds1000e_wfm(
            raw, scale_uv=scale_uv, shift=shift, sample_rate=rate, offset_ps=offset_ps
        )
    )
    assert detect_format(path) == "scope-binary"
    trace = read_trace(path, channel="CH1")
    assert trace.metadata["instrument"] == "DS1000E"
    assert len(trace) == N
    scale = scale_uv * 1e-6 / 25
    # Rounding of the scale and of the products: a few ulp of the largest value.
    np.testing.assert_allclose(trace.values, codes * scale, rtol=0, atol=4e-16 * 255 * scale)
    interval = 1 / rate
    # 5e6 Hz is exact in float32: the interval is 1 / 5e6 up to one rounding.
    assert trace.sample_interval == pytest.approx(interval, rel=1e-15)
    # start + n * interval, each term rounded once: a few ulp of the record's span.
    expected = offset_ps * 1e-12 - N * interval / 2 + np.arange(N) * interval
    np.testing.assert_allclose(trace.t, expected, rtol=0, atol=1e-18)
    assert trace.t[PRE] == pytest.approx(0.0, abs=1e-18)  # the trigger is at t = 0


# --- Tektronix .isf ---------------------------------------------------------------------


def _tektronix_isf(codes, *, ymult, xincr, xzero):
    """A Tektronix ISF file: the ``:WFMPRE`` preamble (semicolon-separated ``KEY VALUE``
    pairs, long field names of the programmer manual) and ``:CURVE #<n><count>`` with
    big-endian 16-bit signed samples."""
    data = np.asarray(codes, dtype=">i2").tobytes()
    header = (
        ":WFMPRE:BYT_NR 2;BIT_NR 16;ENCDG BIN;BN_FMT RI;BYT_OR MSB;"
        f'WFID "Ch1, DC coupling";NR_PT {len(codes)};PT_FMT Y;XUNIT "s";XINCR {xincr!r};'
        f'XZERO {xzero!r};PT_OFF 0;YUNIT "V";YMULT {ymult!r};YOFF 0.0E0;YZERO 0.0E0;:CURVE '
    )
    count = str(len(data))
    return header.encode() + f"#{len(count)}{count}".encode() + data + b"\n"


def test_tektronix_isf(tmp_path):
    codes = _pulse_codes(3000.0, 20.0, seed=3)
    path = tmp_path / "scope.isf"
    path.write_bytes(_tektronix_isf(codes, ymult=3.125e-6, xincr=2e-7, xzero=-PRE * 2e-7))
    assert detect_format(path) == "scope-binary"
    trace = read_trace(path)
    assert len(trace) == N and trace.unit == "V"
    # volts = YZERO + YMULT (code - YOFF); RigolWFM computes in float32: 6e-8 relative
    np.testing.assert_allclose(trace.values, 3.125e-6 * codes, rtol=1e-7, atol=1e-12)
    # t = XZERO + XINCR (i - PT_OFF): the trigger at sample PRE is t = 0
    assert trace.t[PRE] == pytest.approx(0.0, abs=1e-18)
    assert np.diff(trace.t) == pytest.approx(2e-7, rel=1e-12)


@pytest.mark.parametrize(
    ("cut", "message"),
    [
        # 150 whole samples (and the final newline) missing: RigolWFM reads the rest without
        # a word, and the preamble's NR_PT catches it
        (301, "the header declares 8192 points"),
        # half a sample missing: RigolWFM itself fails
        (300, "not a readable oscilloscope binary"),
    ],
)
def test_truncated_tektronix_isf_is_a_format_error(tmp_path, cut, message):
    raw = _tektronix_isf(_pulse_codes(3000.0, 20.0, seed=3), ymult=3e-6, xincr=2e-7, xzero=0.0)
    path = tmp_path / "cut.isf"
    path.write_bytes(raw[:-cut])
    with pytest.raises(TraceFormatError, match=rf"cut\.isf, binary: {message}"):
        read_trace(path)
