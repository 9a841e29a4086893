"""Hostile and broken trace files (issue 24): refused naming the file and line, never misread."""

import os
import re
from pathlib import Path

import pytest

from contactlab.errors import TraceFormatError
from contactlab.traces import read_trace

DATA = Path(__file__).parents[3] / "data" / "traces"

TEXT_RECORDS = ["tek_tds.csv", "rigol_sequence.csv", "rigol_seconds.csv", "generic.csv",
                "keysight.csv", "picoscope.csv", "lecroy.csv", "tek_mso.csv"]  # fmt: skip


def _decimal_commas(text):
    """The file as a comma-decimal locale writes it: every decimal point a comma."""
    return re.sub(r"(\d)\.(\d)", r"\1,\2", text)


@pytest.mark.parametrize("name", TEXT_RECORDS)
def test_decimal_commas_are_refused_not_misread(tmp_path, name):
    path = tmp_path / name
    path.write_text(_decimal_commas((DATA / name).read_text(encoding="utf-8")), encoding="utf-8")
    with pytest.raises(TraceFormatError, match=re.escape(str(path))):
        read_trace(path)


@pytest.mark.parametrize("name", TEXT_RECORDS)
def test_a_last_line_without_line_end_is_refused(tmp_path, name):
    """A value cut mid-number while the file is written (4.8828125e-05 -> 4.8828125)."""
    data = (DATA / name).read_bytes()
    assert data.endswith(b"\n")
    path = tmp_path / name
    path.write_bytes(data[:-1])
    last_line = data.count(b"\n")  # 1-based number of the unterminated last line
    with pytest.raises(TraceFormatError, match=rf"line {last_line}\b.*no line end"):
        read_trace(path)
    path.write_bytes(data)  # the same file, complete, reads
    assert len(read_trace(path)) > 0


def test_a_fifo_is_refused_at_once(tmp_path):
    fifo = tmp_path / "trace.csv"
    os.mkfifo(fifo)
    # nobody writes to the FIFO: opening it would block forever
    with pytest.raises(TraceFormatError, match="not a regular file"):
        read_trace(fifo)


def _h5_with(path, make):
    import h5py

    with h5py.File(path, "w") as h5file:
        dataset = make(h5file)
        dataset.attrs["unit"] = "V"
        dataset.attrs["sample_interval"] = 1e-6
        dataset.attrs["start_time"] = 0.0
    return path


def test_hdf5_external_storage_is_refused(tmp_path):
    secret = tmp_path / "secret.bin"
    secret.write_bytes(b"private bytes of another file" * 8)
    path = _h5_with(
        tmp_path / "external.h5",
        lambda f: f.create_dataset(
            "trace/value", shape=(16,), dtype="f8", external=[(str(secret), 0, 128)]
        ),
    )
    with pytest.raises(TraceFormatError, match=r"'/trace/value'.*external files"):
        read_trace(path)


def test_hdf5_virtual_dataset_is_refused(tmp_path):
    import h5py

    source = tmp_path / "other.h5"
    with h5py.File(source, "w") as f:
        f.create_dataset("data", data=list(range(16)), dtype="f8")
    layout = h5py.VirtualLayout(shape=(16,), dtype="f8")
    layout[:] = h5py.VirtualSource(str(source), "data", shape=(16,))
    path = _h5_with(tmp_path / "virtual.h5", lambda f: f.create_virtual_dataset("value", layout))
    with pytest.raises(TraceFormatError, match="virtual dataset"):
        read_trace(path)


def test_hdf5_declaring_1e12_samples_is_refused_before_allocating(tmp_path):
    path = _h5_with(
        tmp_path / "huge.h5",
        lambda f: f.create_dataset("value", shape=(10**12,), dtype="f8", chunks=(4096,)),
    )
    assert path.stat().st_size < 100_000  # nothing stored: every chunk unallocated
    with pytest.raises(TraceFormatError, match="declares 1000000000000 samples"):
        read_trace(path)


def test_hdf5_gzip_bomb_is_refused(tmp_path):
    import numpy as np

    path = _h5_with(
        tmp_path / "bomb.h5",
        lambda f: f.create_dataset(
            "value",
            data=np.zeros(4_000_000),
            chunks=(1 << 20,),
            compression="gzip",
            compression_opts=9,
        ),
    )
    # 32 MB of zeros in a file of ~40 kB: a ratio of ~800, over the limit of 200
    with pytest.raises(TraceFormatError, match="decompression bomb"):
        read_trace(path)


def test_every_byte_mutated_hdf5_reads_or_is_refused(tmp_path):
    """Damaged copies of data/traces/daq.h5: h5py's own errors come out as TraceFormatError."""
    import numpy as np

    data = bytearray((DATA / "daq.h5").read_bytes())
    rng = np.random.default_rng(24)
    path = tmp_path / "daq.h5"
    refused = 0
    for _ in range(60):  # fixed budget (~1 s); benchmarks/fuzz_traces.py runs thousands
        copy = bytearray(data)
        for position in rng.integers(0, len(copy), size=4):
            copy[position] = int(rng.integers(0, 256))
        path.write_bytes(bytes(copy))
        try:
            trace = read_trace(path)
        except TraceFormatError as exc:
            assert str(path) in str(exc)
            refused += 1
            continue
        assert np.isfinite(trace.t).all() and (np.diff(trace.t) > 0).all()
    assert refused < 60  # most mutations hit samples: some copies must still read


def test_a_tdms_file_cut_short_is_refused(tmp_path):
    data = (DATA / "daq.tdms").read_bytes()
    path = tmp_path / "daq.tdms"
    path.write_bytes(data[: len(data) * 3 // 10])
    with pytest.raises(TraceFormatError, match=re.escape(str(path))):
        read_trace(path)


def test_a_tdms_file_declaring_more_samples_than_it_holds_is_refused(tmp_path):
    import numpy as np

    from contactlab.traces import Trace, write_trace

    path = tmp_path / "short.tdms"
    trace = Trace(np.arange(100) * 1e-6, np.zeros(100), "V", {"sample_interval": 1e-6})
    write_trace(path, trace, "tdms")
    import nptdms

    with nptdms.TdmsWriter(path, mode="a") as writer:  # a later segment restates wf_samples
        writer.write_segment([nptdms.ChannelObject("trace", "value", [], {"wf_samples": 4000})])
    with pytest.raises(TraceFormatError, match="wf_samples declares 4000 samples"):
        read_trace(path)


def test_a_cut_tdms_file_without_wf_samples_is_refused(tmp_path):
    """npTDMS only logs "less data than expected": the log is read, not the short trace."""
    import nptdms
    import numpy as np

    path = tmp_path / "nodeclared.tdms"
    properties = {"wf_increment": 1e-6, "unit_string": "V"}
    with nptdms.TdmsWriter(path) as writer:
        writer.write_segment([nptdms.ChannelObject("g", "c", np.zeros(4000), properties)])
    whole = path.read_bytes()
    path.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(TraceFormatError, match="less data than expected"):
        read_trace(path)


def test_a_crash_in_the_reading_library_is_a_refusal(tmp_path):
    """A segmentation fault in the child (here forced) is a TraceFormatError, not our end."""
    import ctypes

    from contactlab.traces.isolate import run_isolated

    path = str(tmp_path / "x.h5")
    with pytest.raises(TraceFormatError, match="library crashed"):
        run_isolated(path, ctypes.string_at, 0)  # reads address 0: SIGSEGV in the child


def test_the_hdf5_file_that_crashed_h5py_is_refused():
    """A byte-mutated daq-like file found by benchmarks/fuzz_traces.py (h5py 3, HDF5 1.14
    segfault in an attribute read); whatever the library does with it, we refuse it."""
    path = Path(__file__).parent / "hostile" / "segfault.h5"
    with pytest.raises(TraceFormatError, match=re.escape(str(path))):
        read_trace(path)


def test_a_zero_filled_tail_is_refused_in_bounded_memory(tmp_path):
    """A valid CSV followed by 64 MiB of NUL bytes (a preallocated file never filled):
    refused from a streaming scan, naming the line, without parsing the tail."""
    import resource

    data = (DATA / "generic.csv").read_bytes()
    path = tmp_path / "tail.csv"
    with open(path, "wb") as fh:
        fh.write(data)
        fh.write(bytes(64 << 20))
    first_tail_line = data.count(b"\n") + 1
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # [KiB] on Linux
    with pytest.raises(TraceFormatError, match=rf"line {first_tail_line}\b.*NUL byte"):
        read_trace(path)
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown < 32 << 10  # < 32 MiB: streamed in 1 MiB chunks, never the 64 MiB whole


@pytest.mark.parametrize("name", ["generic.csv", "tek_tds.csv", "rigol_seconds.csv"])
def test_more_rows_than_the_sample_limit_are_refused_before_parsing(monkeypatch, name):
    from contactlab.traces import checks

    monkeypatch.setattr(checks, "MAX_SAMPLES", 1000)  # the files hold 2 500-6 000 rows
    with pytest.raises(TraceFormatError, match=r"line \d+: more than 1000 rows") as info:
        read_trace(DATA / name)
    assert name in str(info.value)
    monkeypatch.undo()
    assert len(read_trace(DATA / name).t) > 1000  # under the real limit: read whole
