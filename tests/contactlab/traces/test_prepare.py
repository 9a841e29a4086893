"""Preparing traces: the windows, checks and history a Trace adds to contactlab.signals
(whose arithmetic is tested against closed forms in tests/contactlab/test_signals.py),
and the results on the shipped sample traces."""

from pathlib import Path

import numpy as np
import pytest
from scipy import signal

from contactlab import signals
from contactlab.errors import ParameterError
from contactlab.traces import (
    Trace,
    align,
    detect_onset,
    lowpass,
    noise_level,
    read_trace,
    remove_baseline,
    to_force,
)

DT = 1e-6  # [s] sample interval
FS = 1.0 / DT  # [Hz]


def _trace(values, t0=-1e-3, trigger=0.0):
    n = np.arange(len(values))
    t = n * DT
    t += t0
    return Trace(t, values, "V", {"sample_interval": DT, "trigger_time": trigger})


def _pulse_on_offset(offset=0.37, amplitude=2.0, n=3000):
    """An offset baseline, then a half-sine pulse of 200 us starting at t = 100 us."""
    t = np.arange(n) * DT - 1e-3
    pulse = np.where((t >= 1e-4) & (t <= 3e-4), amplitude * np.sin(np.pi * (t - 1e-4) / 2e-4), 0)
    return _trace(offset + pulse)


def test_remove_baseline_subtracts_the_pre_trigger_mean():
    trace = remove_baseline(_pulse_on_offset())
    before = trace.t < 0
    # The baseline is the constant 0.37; subtracting its mean leaves rounding only.
    np.testing.assert_allclose(trace.values[before], 0.0, atol=1e-15)
    # The pulse is untouched up to rounding of adding and removing the offset (~1e-16).
    assert trace.values.max() == pytest.approx(2.0, rel=1e-12)
    step = trace.metadata["history"][-1]
    assert step["step"] == "remove_baseline"
    assert step["window [s]"] == (-1e-3, 0.0)
    # Mean of 1000 equal samples: summation rounding only (~1e-16 per sample).
    assert step["baseline"] == pytest.approx(0.37, rel=1e-14)


def test_default_window_is_before_the_trigger_or_before_zero():
    trace = _pulse_on_offset()
    values = trace.values.copy()
    values[trace.t < -5e-4] = 10.0  # only the last 500 pre-trigger samples are at 0.37
    late = Trace(trace.t, values, "V", {**trace.metadata, "trigger_time": None})
    explicit = remove_baseline(late, pre_trigger=(-5e-4, 0.0))
    # Mean of 500 equal samples: summation rounding only.
    assert explicit.metadata["history"][-1]["baseline"] == pytest.approx(0.37, rel=1e-14)
    shifted = Trace(trace.t, trace.values, "V", {"trigger_time": -5e-4})
    step = remove_baseline(shifted).metadata["history"][-1]
    assert step["window [s]"] == (-1e-3, -5e-4)
    assert step["samples"] == 500


def test_detect_onset_on_a_ramp_is_exact():
    a, slope, t_start = 1e-3, 50.0, 2e-5  # [V], [V/s], [s]
    n_base = 1000
    t = np.arange(3000) * DT - n_base * DT
    baseline = np.where(np.arange(t.size) % 2 == 0, a, -a)  # mean 0 over the window
    values = np.where(t < t_start, np.where(t < 0, baseline, 0.0), slope * (t - t_start))
    trace = _trace(values)
    sigma = np.std(baseline[:n_base], ddof=1)
    expected = t_start + 5 * sigma / slope
    # A linear ramp is interpolated exactly; only rounding of t and values remains.
    assert detect_onset(trace, k=5) == pytest.approx(expected, abs=1e-15)
    aligned = align(trace, detect_onset(trace, k=5))
    np.testing.assert_array_equal(aligned.t, trace.t - detect_onset(trace, k=5))
    # The trigger moved with the time axis, so the default baseline is the same samples.
    assert aligned.metadata["trigger_time"] == -detect_onset(trace, k=5)
    assert detect_onset(aligned, k=5) == pytest.approx(0.0, abs=1e-15)  # rounding of t - onset
    assert [s["step"] for s in aligned.metadata["history"]] == ["align"]


def test_detect_onset_without_a_pulse_raises():
    rng = np.random.default_rng(4)
    with pytest.raises(ParameterError, match="no sample deviates"):
        detect_onset(_trace(rng.normal(0, 1e-3, 2000) * 0.1), k=50)


def test_lowpass_filters_the_values_and_records_itself():
    """The filter is contactlab.signals.lowpass (its response is tested there) on the
    trace's values at its sample interval; the trace keeps a record of it."""
    pulse = _pulse_on_offset(offset=0.0)
    out = lowpass(pulse, 50e3, order=3)
    np.testing.assert_array_equal(out.values, signals.lowpass(pulse.values, DT, 50e3, 3))
    np.testing.assert_array_equal(out.t, pulse.t)
    assert out.metadata["history"][-1] == {
        "step": "lowpass",
        "cutoff [Hz]": 50e3,
        "order": 3,
        "filter": "Butterworth, zero-phase (sosfiltfilt)",
    }


@pytest.mark.parametrize("cutoff", [FS / 2, FS, -1.0, np.nan])
def test_lowpass_rejects_cutoff_outside_zero_nyquist(cutoff):
    with pytest.raises(ParameterError, match=r"cutoff .*< 500000 \[Hz\]"):
        lowpass(_pulse_on_offset(), cutoff)


def test_lowpass_rejects_overrange_and_non_uniform():
    trace = _pulse_on_offset()
    values = trace.values.copy()
    values[1500] = np.inf
    with pytest.raises(ParameterError, match="overrange"):
        lowpass(Trace(trace.t, values, "V", trace.metadata), 1e4)
    t = trace.t.copy()
    t[10] += 0.3 * DT
    with pytest.raises(ParameterError, match="non-uniform"):
        lowpass(Trace(t, trace.values, "V"), 1e4)


def test_metrics_after_preparation_match_the_pulse():
    sensitivity = 0.0225  # [V/N]
    trace = to_force(remove_baseline(_pulse_on_offset(amplitude=2.0)), sensitivity)
    m = trace.metrics(threshold=5 * noise_level(trace) + 1e-9)
    assert m.peak == pytest.approx(2.0 / sensitivity, rel=1e-12)  # sampled exactly at the crest
    # The lobe spans the 200 us half-sine to within a sample at each end.
    assert m.duration == pytest.approx(2e-4, abs=2 * DT)
    # Trapezoidal impulse of a half-sine with 200 samples: relative error ~ (pi/200)^2 / 12.
    assert m.impulse == pytest.approx(2 * 2.0 / sensitivity * 2e-4 / np.pi, rel=1e-4)
    steps = [s["step"] for s in trace.metadata["history"]]
    assert steps == ["remove_baseline", "to_force"]
    with pytest.raises(ParameterError, match="not 'V'"):
        to_force(trace, sensitivity)


def test_baseline_window_needs_samples():
    trace = _trace(np.zeros(100), t0=0.0)  # no sample before t = 0
    with pytest.raises(ParameterError, match="holds 0 samples"):
        remove_baseline(trace)
    with pytest.raises(ParameterError, match="pre_trigger end"):
        noise_level(trace, pre_trigger=(5e-5, 1e-5))
    for window in (1e-5, (0.0, 1e-5, 2e-5)):  # not a (start, end) pair
        with pytest.raises(ParameterError, match=r"pre_trigger must be \(start, end\)"):
            remove_baseline(trace, pre_trigger=window)


def test_metrics_keys_carry_the_trace_unit():
    """A volt trace reports its peak in V and impulse in V*s; converted, in N and N*s."""
    volts = _trace(0.01 * _pulse_on_offset(offset=0.0).values)
    keys = volts.metrics().to_dict()
    assert "peak [V]" in keys and "impulse [V*s]" in keys and "peak [N]" not in keys
    newtons = to_force(volts, 0.01).metrics().to_dict()
    assert newtons["peak [N]"] == pytest.approx(keys["peak [V]"] / 0.01, rel=1e-12)
    assert "impulse [N*s]" in newtons


SAMPLES = sorted((Path(__file__).resolve().parents[3] / "data" / "traces").glob("*.json"))


@pytest.mark.parametrize("sidecar", SAMPLES, ids=lambda p: p.name.removesuffix(".json"))
def test_sample_traces_prepare_as_written_out(sidecar):
    """On the shipped traces, the results of the arithmetic prepare.py held before it moved
    to contactlab.signals, written out here with numpy and scipy: identical to the bit."""
    trace = read_trace(sidecar.with_suffix(""))
    assert trace.metadata["trigger_time"] in (0.0, None)  # default baseline: before t = 0
    t, v = trace.t, trace.values
    before = v[t < 0.0]
    assert noise_level(trace) == float(before.std(ddof=1))
    zeroed = remove_baseline(trace)
    np.testing.assert_array_equal(zeroed.values, v - float(before.mean()))
    interval = trace.sample_interval
    cutoff = 0.1 / interval  # [Hz] a fifth of the Nyquist frequency
    sos = signal.butter(4, cutoff, btype="low", output="sos", fs=1.0 / interval)
    np.testing.assert_array_equal(
        lowpass(zeroed, cutoff).values, signal.sosfiltfilt(sos, zeroed.values)
    )
    onset = detect_onset(trace)
    deviation = np.abs(v - float(before.mean()))
    level = 5.0 * float(before.std(ddof=1))
    i = int(np.argmax(deviation > level))
    # the onset is the linear crossing of the level between the first sample above it and
    # the one before: on that line, the level is met to rounding (observed <= 2.2e-16
    # relative; 1e-14 leaves room for a jump far above the level)
    assert t[i - 1] < onset <= t[i]
    crossing = deviation[i - 1] + (onset - t[i - 1]) / (t[i] - t[i - 1]) * (
        deviation[i] - deviation[i - 1]
    )
    assert crossing == pytest.approx(level, rel=1e-14)
