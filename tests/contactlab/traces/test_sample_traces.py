"""The synthetic sample traces in data/traces: each reads as labelled, and its truth is measurable.

Every sample file must be recognised as the layout its sidecar names and give back the
record the sidecar describes; read as a laboratory would (baseline from the pre-trigger
record, a low-pass well above the sensor resonance, threshold crossings), the measured
pulse must agree with the sidecar's truth within what the stated noise and quantisation
allow. The generator must reproduce the files byte for byte.
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from contactlab.config import load_config
from contactlab.errors import TraceFormatError
from contactlab.metrics import impulse
from contactlab.traces import (
    FORMATS,
    detect_onset,
    lowpass,
    noise_level,
    read_trace,
    remove_baseline,
)

DATA = Path(__file__).resolve().parents[3] / "data" / "traces"
SIDECARS = sorted(DATA.glob("*.json"))

CUTOFF_PER_RESONANCE = 10.0
"""Low-pass cutoff in sensor resonances: passes the 40 kHz sensor signal unchanged
(the zero-phase filter's gain there is 1 - 1e-16) and removes most of the noise."""

READING_K = 5.0
"""Onset threshold in noise standard deviations, as the sidecar's reading threshold."""

INPUTS = {
    "generate.py",
    "acquisitions.toml",
    "README.md",
    "model_hard.toml",
    "model_soft.toml",
    "model_hertz.toml",
}
"""Files in data/traces that the generator reads or documents but does not write."""


@pytest.fixture(params=SIDECARS, ids=lambda p: p.name.removesuffix(".json"))
def sample(request):
    """(path of a sample file, its sidecar)."""
    side = request.param
    return side.with_suffix(""), json.loads(side.read_text(encoding="utf-8"))


def test_every_readable_layout_has_a_labelled_sample():
    sidecars = [json.loads(p.read_text(encoding="utf-8")) for p in SIDECARS]
    assert all(s["synthetic"] is True for s in sidecars)
    # RigolWFM's binaries ("scope-binary") have no writer: tests/contactlab/traces/test_binary.py
    assert {s["format"] for s in sidecars} == set(FORMATS) - {"scope-binary"}
    assert all((DATA / s["file"]).is_file() for s in sidecars)
    assert all((DATA / s["model"]).is_file() for s in sidecars)
    total = sum(p.stat().st_size for p in DATA.iterdir() if p.is_file())
    assert total < 3e6  # [B] the sample data stay small


def test_sample_reads_as_labelled(sample):
    path, side = sample
    trace = read_trace(path)
    assert trace.metadata["format"] == side["format"]  # detected from the content
    assert trace.unit == "V"
    assert len(trace) == side["samples"]
    # The sidecar's numbers have 10 significant digits (generate.SIDECAR_DIGITS).
    for value, key in [
        (trace.t[0], "first_time [s]"),
        (trace.t[-1], "last_time [s]"),
        (trace.sample_interval, "sample_interval [s]"),
    ]:
        assert value == pytest.approx(side[key], rel=1e-10, abs=0), key
    codes = trace.values / side["lsb [V]"]
    # Quantised: whole ADC codes, up to the sidecar's 10-digit lsb (5e-10 relative) and
    # the rounding of code * lsb (and of mV for PicoScope).
    np.testing.assert_allclose(codes, np.round(codes), rtol=1e-9, atol=1e-9)
    low, high = side["vertical_range [V]"]
    assert low <= trace.values.min() and trace.values.max() <= high


def test_sensitivity_gives_newtons(sample):
    path, side = sample
    volts = read_trace(path)
    newtons = read_trace(path, sensitivity=side["sensitivity [V/N]"])
    assert newtons.unit == "N"
    np.testing.assert_array_equal(newtons.values, volts.values / side["sensitivity [V/N]"])


def test_measured_pulse_agrees_with_truth(sample):
    path, side = sample
    truth, free = side["truth"], side["noise_free_reading"]
    trace = read_trace(path, sensitivity=side["sensitivity [V/N]"])
    dt = side["sample_interval [s]"]
    window = (trace.t[0], trace.t[0] / 2)  # first half of the pre-trigger record [s]
    n_base = np.count_nonzero((trace.t >= window[0]) & (trace.t < window[1]))
    sigma = free["noise [N]"]  # white noise and quantisation (lsb**2 / 12) [N]

    measured_noise = noise_level(trace, window)
    # A standard deviation of n samples scatters by 1/sqrt(2 (n - 1)) relative: 5 of those.
    assert measured_noise == pytest.approx(sigma, rel=5 / math.sqrt(2 * (n_base - 1)))

    onset = detect_onset(trace, k=READING_K, pre_trigger=window)
    # The onset threshold k * measured noise differs from the reading threshold by
    # k * |noise error|, and the earliest crossing of a noisy edge by up to 5 sigma
    # (probability 3e-7 per sample); both become time through the edge's slope.
    level = READING_K * abs(measured_noise - sigma) + 5 * sigma
    assert onset == pytest.approx(free["start [s]"], abs=level / free["start_slope [N/s]"])
    assert onset > truth["onset_time [s]"]  # nothing is seen before the first touch

    zeroed = remove_baseline(trace, window)
    resonance = side["sensor"]["resonance [Hz]"]
    smooth = lowpass(zeroed, CUTOFF_PER_RESONANCE * resonance)
    sigma_smooth = noise_level(smooth, window)
    pulse = smooth.metrics(threshold=free["threshold [N]"])
    # Each crossing moves by the (filtered) noise over the edge's slope: 4 sigma each;
    # the filter itself moves them by < 10 ns (checked on the noise-free signal).
    slopes = 1 / free["start_slope [N/s]"] + 1 / abs(free["end_slope [N/s]"])
    assert pulse.duration == pytest.approx(free["duration [s]"], abs=4 * sigma_smooth * slopes)
    # Noise near the top (4 sigma), plus the top of a resonance-frequency oscillation of
    # the peak's size missed by half a sample.
    peak = truth["peak_sensor_force [N]"]
    miss = 0.5 * peak * (math.pi * resonance * dt) ** 2
    assert pulse.peak == pytest.approx(peak, abs=4 * sigma_smooth + miss)

    # Restitution from the impulse, e = J / (m v) - 1 (notes: "Metrics labs report").
    total = impulse(zeroed.t, zeroed.values, start=window[1])
    span = zeroed.t[-1] - window[1]
    # White noise integrates to sigma * dt * sqrt(n); the baseline mean's error
    # sigma / sqrt(n_base) integrates over the span; plus the ringing past the record.
    spread = sigma * math.sqrt(span * dt + span**2 / n_base)
    tail = abs(truth["impulse [N*s]"] - free["record_impulse [N*s]"])
    momentum = side["grain"]["mass [kg]"] * side["velocity [m/s]"]
    restitution = total / momentum - 1
    assert restitution == pytest.approx(
        truth["restitution [-]"], abs=(4 * spread + tail) / momentum
    )


@pytest.mark.parametrize("model", sorted({json.loads(p.read_text())["model"] for p in SIDECARS}))
def test_model_file_reproduces_the_truth(model):
    """The model TOML beside the traces (``dem-check compare --model``) is their model."""
    result = load_config(DATA / model).simulate()
    side = next(
        s
        for s in (json.loads(p.read_text(encoding="utf-8")) for p in SIDECARS)
        if s["model"] == model
    )
    truth = side["truth"]
    # The sidecar has 10 significant digits; events and integrals do not depend on the
    # output grid, and peaks are refined from the grid's maximum to machine precision.
    for key, value in [
        ("contact_time [s]", result.contact_time),
        ("peak_contact_force [N]", result.peak_contact_force),
        ("peak_sensor_force [N]", result.peak_sensor_force),
        ("sensor_response_time [s]", result.sensor_response_time),
        ("restitution [-]", result.restitution),
        ("impulse [N*s]", result.impulse),
    ]:
        assert value == pytest.approx(truth[key], rel=1e-9), key
    assert result.velocity == side["velocity [m/s]"]
    assert result.law.parameters() == pytest.approx(side["law"]["parameters"], rel=1e-9)


def _same_up_to(a, b, rel):
    """Equal nested JSON values, floats within ``rel`` of each other."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same_up_to(a[k], b[k], rel) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(_same_up_to(x, y, rel) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float):
        return a == pytest.approx(b, rel=rel)
    return a == b


def test_generator_is_deterministic(tmp_path):
    script = DATA / "generate.py"
    subprocess.run([sys.executable, str(script), "--out", str(tmp_path)], check=True)
    written = sorted(p.name for p in tmp_path.iterdir())
    generated = (p.name for p in DATA.iterdir() if p.is_file() and p.name not in INPUTS)
    assert written == sorted(generated)  # real/ holds measured records, not generated
    for name in written:
        if name.endswith(".json"):
            # the truth is the solver's: it may move in its last digits when the solver
            # improves (adaptive Hertz pieces: ~1e-9), never beyond 1e-8
            fresh = json.loads((tmp_path / name).read_text())
            assert _same_up_to(fresh, json.loads((DATA / name).read_text()), 1e-8), name
        else:  # quantised samples: identical bytes
            assert (tmp_path / name).read_bytes() == (DATA / name).read_bytes(), name


TEXT_SAMPLES = [p.with_suffix("") for p in SIDECARS if p.with_suffix("").suffix == ".csv"]


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-be", "utf-32"])
@pytest.mark.parametrize("path", TEXT_SAMPLES, ids=lambda p: p.name)
def test_wide_unicode_export_reads_like_utf8(tmp_path, path, encoding):
    """Windows software that saves text as UTF-16 (or UTF-32) with a byte-order mark."""
    text = path.read_text(encoding="utf-8")
    wide = tmp_path / path.name
    bom = "\ufeff" if encoding == "utf-16-be" else ""  # the plain codecs write their own
    wide.write_bytes((bom + text).encode(encoding))
    expected, trace = read_trace(path), read_trace(wide)
    assert trace.metadata["format"] == expected.metadata["format"]
    assert trace.metadata["encoding"] == encoding[:6]
    np.testing.assert_array_equal(trace.t, expected.t)
    np.testing.assert_array_equal(trace.values, expected.values)


def test_broken_utf16_names_the_encoding(tmp_path):
    path = tmp_path / "broken.csv"
    path.write_bytes("t [s],v [V]\n0,1\n".encode("utf-16") + b"\x00")  # odd byte count
    with pytest.raises(TraceFormatError, match=r"broken\.csv, byte \d+: .*not valid UTF-16"):
        read_trace(path)
