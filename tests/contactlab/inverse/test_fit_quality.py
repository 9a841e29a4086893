"""Does a fit judge itself honestly? Noise window, chi-squared, whiteness, over many seeds.

References: the sample files of ``data/traces`` (written by their own generator, with
their truth in the sidecars), the closed-form chi-squared and F distributions
(``scipy.stats``), and the Ljung-Box statistic of statsmodels.
"""

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy import signal as sps
from scipy import stats

import contactlab as cl
from contactlab.config import load_config
from contactlab.errors import ParameterError
from contactlab.inverse import (
    FitQualityWarning,
    IdentifiabilityWarning,
    fit_contact,
    synthetic_trace,
)
from contactlab.inverse.fit_quality import ALPHA, ljung_box
from contactlab.inverse.noise_window import clean_noise_window
from contactlab.traces import read_trace

TRACES = Path(__file__).resolve().parents[3] / "data" / "traces"
SENSITIVITY = 0.01124  # [V/N], every sample file (data/traces/README.md)
GRAIN = cl.Grain(diameter=5e-3, density=765.0)
SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
HARD = cl.laws.LinearViscoelastic(stiffness=1e5, damping=1.0)


def _sample(name):
    """A sample file in newtons, its sidecar and its model config."""
    sidecar = json.loads((TRACES / f"{name}.json").read_text())
    trace = read_trace(TRACES / name, sensitivity=SENSITIVITY)
    return trace, sidecar, load_config(TRACES / sidecar["model"])


def test_ljung_box_matches_statsmodels():
    x = [0.3, -1.2, 0.8, 1.5, -0.4, 0.0, 2.1, -0.9, -1.7, 0.6, 1.1, -0.2]
    x += [0.4, -1.0, 0.9, 1.3, -0.5, -0.8, 0.2, 1.6, -1.1, 0.7, -0.3, 0.5]
    # statsmodels 0.15.0 acorr_ljungbox(x, lags=[1, 5]); both are the same closed
    # formula, so they agree to rounding
    assert ljung_box(x, 1) == pytest.approx((1.5032685632639304, 0.22016912421963783), rel=1e-12)
    assert ljung_box(x, 5) == pytest.approx((11.93623081560658, 0.03567209072767236), rel=1e-12)
    with pytest.raises(ParameterError, match="22 samples"):
        ljung_box(x[:21], 20)
    with pytest.raises(ParameterError, match="lags must be"):
        ljung_box(x, 0)


def test_ljung_box_is_uniform_on_white_noise_and_rejects_coloured_noise():
    rng = np.random.default_rng(7)
    white = [ljung_box(rng.normal(size=2000))[1] for _ in range(200)]
    # KS against uniform p-values: the chi2(20) approximation is excellent at n = 2000;
    # a 1e-3 level fails a correct test once in a thousand seeds
    assert stats.kstest(white, "uniform").pvalue > 1e-3
    coloured = sps.lfilter([1.0], [1.0, -0.3], rng.normal(size=2000))
    # AR(1) with rho = 0.3: Q ~ n rho^2 = 180 against chi2(20), p ~ 1e-27
    assert ljung_box(coloured)[1] < 1e-10


@pytest.mark.parametrize("name", ["keysight.csv", "picoscope.csv", "daq.tdms", "tek_tds.csv"])
def test_noise_window_ends_before_the_touch_and_reads_the_true_noise(name):
    trace, sidecar, _ = _sample(name)
    start, end = clean_noise_window(trace.t, trace.values)
    touch = sidecar["truth"]["onset_time [s]"]
    assert start == trace.t[0] and end < touch < 0.0  # the scope triggered after the touch
    window = (trace.t >= start) & (trace.t < end)
    noise = np.std(trace.values[window], ddof=1)
    true = sidecar["noise_free_reading"]["noise [N]"]
    # sample standard deviation of m Gaussian samples: relative spread 1/sqrt(2(m - 1));
    # 4 of them is a 1-in-16000 miss
    assert abs(noise / true - 1.0) < 4.0 / math.sqrt(2.0 * (window.sum() - 1))
    before_trigger = np.std(trace.values[trace.t < 0.0], ddof=1)
    # the old default (t < 0) holds the pulse's start: 2.1x too noisy on keysight.csv
    assert before_trigger > noise


def test_noise_window_needs_samples_before_the_pulse():
    t, y, _ = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, pre_trigger=5e-6, seed=0)
    with pytest.raises(ParameterError, match="0 samples lie before the pulse"):
        clean_noise_window(t, y)


@pytest.fixture(scope="module")
def keysight():
    """The issue's trace (damped Hertz, 8-bit): its sidecar, the arguments of a fit and
    the fits of the true law and of the linear law."""
    trace, sidecar, model = _sample("keysight.csv")
    args = (trace.t, trace.values, model.grain, model.sensor)
    with pytest.warns(FitQualityWarning, match="the linear law is not consistent"):
        wrong = fit_contact(*args, "linear")
    return sidecar, args, {"hertz_damped": fit_contact(*args, "hertz_damped"), "linear": wrong}


def test_the_issue_example_linear_law_on_a_damped_hertz_trace_is_rejected(keysight):
    """issue 23: 'converged', reduced chi2 0.72 and a velocity of 1.818 +- 0.004 m/s for
    a true 2.0, because the noise window t < 0 held the pulse's start."""
    sidecar, args, fits = keysight
    wrong, true = fits["linear"], fits["hertz_damped"]
    assert wrong.quality.noise_window[1] < sidecar["truth"]["onset_time [s]"]
    # measured 3.38 with the clean window (the issue: 3.33 with a hand-picked one)
    assert wrong.quality.reduced_chi_squared > 3.0
    assert not wrong.quality.consistent
    assert wrong.quality.p_value < 1e-30 and wrong.quality.whiteness_p_value < 1e-30
    assert "NOT consistent" in wrong.summary() and "too large" in wrong.summary()
    # the true law: measured 1.128, p = 0.04 under F(4436, 680)
    assert true.quality.consistent
    low, high = true.parameters["velocity"].ci95
    assert low < sidecar["velocity [m/s]"] < high
    assert true.to_dict()["quality"]["consistent"] is True
    # the old default window, given by hand, is now caught by the two-sided test:
    # measured reduced chi2 0.25 (true law) and 0.72 (linear) against F(~4400, 999)
    for law in ("hertz_damped", "linear"):
        with pytest.warns(FitQualityWarning, match="too small"):
            old = fit_contact(*args, law, baseline_window=(args[0][0], 0.0))
        assert old.quality.reduced_chi_squared < 0.8
        assert "noise window holds signal" in " ".join(old.quality.reasons)


@pytest.mark.parametrize(
    ("name", "true_law", "wrong_law"),
    [
        ("picoscope.csv", "hertz_damped", "linear"),
        ("daq.tdms", "hertz_damped", "walton_braun"),
        ("tek_mso.csv", "linear", "hertz_damped"),
    ],
)
def test_sample_files_true_law_consistent_wrong_law_rejected(name, true_law, wrong_law):
    """Quantised 8-16 bit records with offsets: measured reduced chi2 0.95-1.08 for the
    true law on every sample file, 1.6-2.8 for the nearest wrong law."""
    trace, _, model = _sample(name)
    args = (trace.t, trace.values, model.grain, model.sensor)
    fits = {true_law: fit_contact(*args, true_law)}
    with warnings.catch_warnings():
        # a wrong law can also leave a parameter undetermined; not what is tested here
        warnings.simplefilter("ignore", IdentifiabilityWarning)
        with pytest.warns(FitQualityWarning, match="systematic misfit"):
            fits[wrong_law] = fit_contact(*args, wrong_law)
    assert fits[true_law].quality.consistent, fits[true_law].quality.reasons
    assert not fits[wrong_law].quality.consistent
    assert "systematic misfit" in " ".join(fits[wrong_law].quality.reasons)


@pytest.fixture(scope="module")
def seeds():
    """The true law fitted to 30 noise seeds (1 MHz, 1 % white noise)."""
    out = []
    for seed in range(30):
        t, y, truth = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, sample_rate=1e6, seed=seed)
        with warnings.catch_warnings():
            # a correct law is called inconsistent in ~2 % of seeds: counted in the test
            warnings.simplefilter("ignore", FitQualityWarning)
            fit = fit_contact(t, y, GRAIN, SENSOR, "linear")
        out.append((fit, 0.01 * truth.peak_sensor_force))
    return out


def test_chi_squared_follows_its_closed_form_over_noise_seeds(seeds):
    """Each seed has its own sample counts (the onset moves with the noise), so each value
    is mapped through its own closed-form CDF: the results must be uniform."""
    true_chi2, reduced, means = [], [], []
    for fit, sigma in seeds:
        q = fit.quality
        dof, noise_dof = q.degrees_of_freedom, q.noise_samples - 1
        # with the true noise level the sum of squared residuals is chi2(n - p)
        chi2 = q.reduced_chi_squared * dof * (fit.goodness["noise [N]"] / sigma) ** 2
        true_chi2.append(stats.chi2(dof).cdf(chi2))
        # with the noise read from the noise window the reduced chi2 is F(n - p, m - 1)
        reduced.append(stats.f(dof, noise_dof).cdf(q.reduced_chi_squared))
        means.append((q.reduced_chi_squared, stats.f(dof, noise_dof).mean()))
    # KS at 1e-3: a correct distribution fails once in a thousand seed sets
    assert stats.kstest(true_chi2, "uniform").pvalue > 1e-3
    assert stats.kstest(reduced, "uniform").pvalue > 1e-3
    # about 1: the mean over the seeds within 4 standard errors of the F means' mean
    observed, expected = np.mean(means, axis=0)
    spread = np.std([m[0] for m in means], ddof=1) / math.sqrt(len(means))
    assert abs(observed - expected) < 4.0 * spread
    assert abs(observed - 1.0) < 0.1


def test_p_values_are_uniform_and_the_true_law_is_consistent(seeds):
    q = [fit.quality for fit, _ in seeds]
    for p in ([x.p_value for x in q], [x.whiteness_p_value for x in q]):
        # uniform under the true model: KS at 1e-3 (fails once in a thousand seed sets)
        assert stats.kstest(p, "uniform").pvalue > 1e-3
    # each seed is called inconsistent with probability ~2 % (two tests at 1 %): 30 seeds
    # give more than 4 such calls with probability 0.2 %
    assert sum(not x.consistent for x in q) <= 4
    assert ALPHA == q[0].alpha


def test_coloured_noise_is_caught_by_whiteness_where_chi_squared_passes():
    """AR(1) noise (rho = 0.9, a low-pass in the acquisition): its variance is what the
    noise window reads, so the chi-squared test passes, but the samples are not
    independent and the intervals are about sqrt((1 + rho)/(1 - rho)) = 4.4x too narrow."""
    t, clean, truth = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, noise=0.0, pre_trigger=200e-6)
    rho = 0.9
    rng = np.random.default_rng(3)
    white = rng.normal(0.0, 0.01 * truth.peak_sensor_force * math.sqrt(1 - rho**2), t.size)
    with pytest.warns(FitQualityWarning, match="coloured"):
        fit = fit_contact(
            t, clean + sps.lfilter([1.0], [1.0, -rho], white), GRAIN, SENSOR, "linear"
        )
    q = fit.quality
    assert q.p_value > ALPHA  # the chi-squared alone calls it fine
    assert q.whiteness_p_value < 1e-10 and q.noise_whiteness_p_value < 1e-10
    assert not q.consistent
    assert "coloured" in " ".join(q.reasons)


def test_a_wrong_law_hidden_by_noise_is_caught_by_whiteness():
    """10 % white noise on the damped-Hertz model: the linear law's chi-squared is
    within the noise (measured 1.03, p = 0.6) and its velocity interval [1.78, 1.83] m/s
    misses the true 2.0, but its residuals keep the misfit's shape (Ljung-Box p = 2e-4)."""
    law = cl.laws.HertzDamped.from_material(
        cl.analytic.Material(21.6e6, 0.2, 2.5e-3), restitution=0.5, mass=GRAIN.mass
    )
    t, y, _ = synthetic_trace(
        GRAIN, SENSOR, law, 2.0, noise=0.1, duration=800e-6, pre_trigger=200e-6, seed=11
    )
    with pytest.warns(FitQualityWarning, match="systematic misfit"):
        wrong = fit_contact(t, y, GRAIN, SENSOR, "linear")
    assert wrong.quality.p_value > ALPHA  # the chi-squared alone calls it fine
    assert wrong.quality.whiteness_p_value < ALPHA
    assert wrong.quality.noise_whiteness_p_value > ALPHA  # the noise itself is white
    assert not wrong.parameters["velocity"].ci95[0] < 2.0 < wrong.parameters["velocity"].ci95[1]
    right = fit_contact(t, y, GRAIN, SENSOR, "hertz_damped")
    assert right.quality.consistent


def test_a_given_noise_window_is_used_as_given():
    t, y, _ = synthetic_trace(GRAIN, SENSOR, HARD, 2.0, sample_rate=1e6, seed=4)
    fit = fit_contact(t, y, GRAIN, SENSOR, "linear", baseline_window=(-1e-4, -5e-5))
    assert fit.quality.noise_window == (-1e-4, -5e-5)
    assert fit.quality.noise_samples == 50
    data = json.loads(fit.to_json())
    # strict JSON: every number finite
    json.loads(fit.to_json(), parse_constant=lambda c: pytest.fail(f"non-standard {c}"))
    assert set(data["quality"]) == {
        "consistent",
        "reasons",
        "reduced_chi_squared [-]",
        "degrees_of_freedom",
        "noise_samples",
        "p_value [-]",
        "whiteness",
        "noise_window [s]",
        "alpha [-]",
    }
    assert data["quality"]["noise_window [s]"] == [-1e-4, -5e-5]


def test_rebound_in_both_conventions_against_closed_forms(keysight):
    _, _, fits = keysight
    fit = fits["hertz_damped"]
    e = fit.parameters["restitution"].value
    alpha = cl.analytic.tsuji_damping_factor(e)
    rebound = fit.rebound
    # the Tsuji mapping realises e exactly at zero overlap, and the linear-oscillator
    # closed form at zero force (analytic.tsuji_restitution); the wall solver's rtol 1e-6
    assert rebound["overlap_end [-]"] == pytest.approx(e, rel=1e-12)
    assert rebound["fitted_law [-]"] == pytest.approx(
        cl.analytic.tsuji_restitution(alpha, "force"), rel=1e-5
    )
    text = fit.summary()
    # measured 0.5508 and 0.5007, both printed
    assert f"{rebound['fitted_law [-]']:.4f}" in text and f"{e:.4f}" in text
    linear = fits["linear"]
    k, c, mass = linear.law.stiffness, linear.law.damping, linear.grain.mass
    for convention, key in (("force", "fitted_law [-]"), ("overlap", "overlap_end [-]")):
        expected = cl.analytic.linear_restitution(k, c, mass, convention=convention)
        # exact solver against the closed form: rounding
        assert linear.rebound[key] == pytest.approx(expected, rel=1e-9)
    assert json.loads(fit.to_json())["rebound_on_wall"] == rebound
