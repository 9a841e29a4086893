"""contactlab.compare: passes on identical input, fails where physics says it must."""

import json
import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import contactlab as cl
from contactlab.compare import DEFAULT_TOLERANCES, QUANTITIES, compare_trace
from contactlab.config import load_preset
from contactlab.errors import ParameterError
from dem_check import Comparison, Trace, compare

MASS = 5.0e-5  # grain mass [kg]
V0 = 2.0  # impact speed [m/s]


def _wall(stiffness=1e5, damping=0.0, **kwargs):
    """A grain of MASS on an immovable wall (closed forms known)."""
    law = cl.laws.LinearViscoelastic(stiffness, damping)
    return cl.simulate_impact(cl.Grain.from_mass(MASS), cl.Sensor.rigid(), law, V0, **kwargs)


@pytest.fixture(scope="module")
def base():
    """The preset fig6 impact (linear law on a 20 kHz sensor)."""
    return load_preset("fig6").simulate()


def _trace(result, shift=0.0, noise=0.0, unit="N", seed=0):
    """The result's sensor signal as a trace, delayed by ``shift`` [s], with noise [N]."""
    rng = np.random.default_rng(seed)
    values = result.sensor_force + noise * rng.standard_normal(result.t.size)
    return Trace(result.t + shift, values, unit)


def _row(comparison, name):
    return comparison.table.set_index("quantity").loc[name]


def test_identical_results_pass_with_zero_error(base):
    comparison = compare(base, base)
    assert isinstance(comparison, Comparison)
    assert comparison.passed
    assert comparison.failed == []
    assert list(comparison.table["quantity"]) == list(QUANTITIES)
    # the same numbers on both sides: every error is exactly zero
    assert (comparison.table["abs_error"] == 0.0).all()
    assert comparison.shift == 0.0


def test_stiffer_contact_fails_contact_time_and_peak_by_the_closed_form():
    ratio = 1.05  # 5 % stiffer contact
    reference, stiffer = _wall(), _wall(stiffness=1e5 * ratio)
    comparison = compare(stiffer, reference)
    assert not comparison.passed
    # t_c ~ k**-1/2 (-2.4 %) and the peak ~ k**1/2 (+2.5 %) leave their tolerances; an
    # elastic impact keeps e = 1 whatever the stiffness
    assert set(comparison.failed) >= {"contact_time", "peak_contact_force"}
    assert _row(comparison, "restitution")["passed"]
    # both solutions are exact (events to ~1e-12, peaks refined to ~1e-9)
    assert _row(comparison, "contact_time")["rel_error"] == pytest.approx(ratio**-0.5 - 1, abs=1e-8)
    assert _row(comparison, "peak_contact_force")["rel_error"] == pytest.approx(
        ratio**0.5 - 1, abs=1e-8
    )


def test_restitution_is_compared_in_absolute_terms():
    stiffness = 1e5
    lossy = cl.laws.LinearViscoelastic.from_restitution(stiffness, 0.97, MASS, "force")
    comparison = compare(_wall(damping=lossy.damping), _wall())
    row = _row(comparison, "restitution")
    # e = 0.97 against 1: an absolute error of 0.03 (to the solver's 1e-9) > 0.01
    assert row["abs_error"] == pytest.approx(0.03, abs=1e-9)
    assert row["basis"] == "absolute"
    assert not row["passed"]
    # loosened by name, it passes
    assert _row(
        compare(_wall(damping=lossy.damping), _wall(), {"restitution": 0.05}), "restitution"
    )["passed"]


def test_a_time_shift_fails_the_waveform_unless_aligned(base):
    shift = 7.3e-6  # [s], a few sample intervals and not a multiple of one
    delayed = _trace(base, shift)
    unaligned = compare(delayed, base, align=None)
    assert set(unaligned.failed) == {"waveform_rms_error", "waveform_max_error"}
    onset = compare(delayed, base, align="onset")
    xcorr = compare(delayed, base, align="xcorr")
    # onset: crossings interpolated linearly on a 2.5e-8 s grid, at the same level on
    # both sides of an identical signal: exact to rounding
    assert onset.shift == pytest.approx(-shift, abs=1e-12)
    # xcorr: best lag refined by a parabola; a fraction of the 2.5e-8 s sample interval
    assert xcorr.shift == pytest.approx(-shift, abs=0.25 * 2.5e-8)
    assert onset.passed and xcorr.passed
    # durations and peaks do not depend on the alignment
    for name in ("peak_sensor_force", "sensor_response_time"):
        assert _row(unaligned, name)["a"] == _row(onset, name)["a"]


def test_trace_lacks_contact_quantities_which_are_not_failed(base):
    comparison = compare(_trace(base), base)
    for name in ("contact_time", "peak_contact_force", "restitution"):
        row = _row(comparison, name)
        assert row["passed"] is None
        assert math.isnan(row["a"])  # the trace has none
        assert row["b"] == getattr(base, name)  # the model's value is still shown
        assert row["note"].startswith("not available: trace")
    assert comparison.passed
    # the trace's lobe is read on the model's own grid: grid-limited against exact
    # crossings, within a sample interval (2.5e-8 s of 48 us)
    assert _row(comparison, "sensor_response_time")["rel_error"] == pytest.approx(0.0, abs=1e-3)


def test_noisy_trace_read_at_a_threshold(base):
    sigma = 0.001 * base.peak_sensor_force  # white noise [N], 0.1 % of the peak
    clean = _trace(base)
    trace = Trace(clean.t[::8], _trace(base, noise=sigma, seed=4).values[::8], "N")  # 2e-7 s
    # read on the steep rise (slope x interval = 6.6 sigma there): noise cannot re-cross
    comparison = compare(trace, base, align=None, threshold=0.1 * base.peak_sensor_force)
    # linear interpolation of white noise between samples has variance 2/3 sigma**2; the
    # 2500 samples scatter the RMS by 1/sqrt(2 n) = 1.4 %, and the signal's own
    # interpolation error (~2e-4 N) adds in quadrature: 5 % holds
    rms = _row(comparison, "waveform_rms_error")["abs_error"]
    assert rms == pytest.approx(sigma * math.sqrt(2 / 3), rel=0.05)
    assert comparison.passed


def test_trace_in_volts_is_refused(base):
    with pytest.raises(ParameterError, match="newtons"):
        compare(_trace(base, unit="V"), base)


def test_unknown_tolerance_names_are_listed(base):
    with pytest.raises(ParameterError, match="did you mean 'contact_time'") as info:
        compare(base, base, tolerances={"contact_tme": 0.01})
    for name in DEFAULT_TOLERANCES:
        assert name in str(info.value)
    with pytest.raises(ParameterError, match="tolerance restitution"):
        compare(base, base, tolerances={"restitution": -1.0})


def test_bad_arguments(base):
    with pytest.raises(ParameterError, match="align"):
        compare(base, base, align="peak")
    with pytest.raises(ParameterError, match="expected a simulated result or a Trace"):
        compare(base, [1.0, 2.0])
    with pytest.raises(ParameterError, match="labels"):
        compare(base, base, labels=("only one",))
    with pytest.raises(ParameterError, match="hysteresis"):  # checked even when unused
        compare(base, base, hysteresis=-1.0)
    with pytest.raises(ParameterError, match="tolerances must be a dict"):
        compare(base, base, tolerances=0.01)
    with pytest.raises(ParameterError, match=r"config must be a contactlab\.config\.ImpactConfig"):
        compare_trace(_trace(base), "fig6.toml")


def test_outputs_text_json_and_plot(base):
    comparison = compare(_wall(stiffness=1.05e5), _wall(), labels=("stiff", "reference"))
    text = str(comparison)
    assert text.splitlines()[0].startswith("stiff vs reference: FAILED")
    for name in QUANTITIES:
        assert name in text
    data = json.loads(json.dumps(comparison.to_dict(), allow_nan=False))
    assert data["passed"] is False
    assert [q["quantity"] for q in data["quantities"]] == list(QUANTITIES)
    assert "Comparison('stiff' vs 'reference'" in repr(comparison)
    fig, ax = comparison.plot()
    assert ax.get_xlabel() == "time [µs]"
    assert len(ax.lines) >= 4  # S1 and S2 of both
    plt.close(fig)


def test_compare_trace_removes_the_baseline(base):
    config = load_preset("fig6")
    offset, sigma = 0.05, 0.002  # DC offset and white noise [N]
    interval = 8 * (base.t[1] - base.t[0])  # 2e-7 s, as a scope would sample
    pre = np.arange(-400, 0) * interval
    rng = np.random.default_rng(7)
    t = np.concatenate((pre, base.t[::8]))
    values = np.concatenate((np.zeros(pre.size), base.sensor_force[::8]))
    trace = Trace(t, values + offset + sigma * rng.standard_normal(t.size), "N")
    comparison = compare_trace(trace, config)
    assert comparison.notes["baseline"].startswith("removed")
    # the threshold is 5 sample standard deviations of 400 baseline samples (+-3.5 %)
    assert comparison.notes["lobe threshold [N]"] == pytest.approx(5 * sigma, rel=0.15)
    assert comparison.passed
