"""contactlab.testing: the helpers pass on right values, fail on wrong ones, and say why."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab import analytic
from contactlab.compare import QUANTITIES
from contactlab.config import load_preset
from contactlab.laws import LAWS, Branch, ContactLaw, Hertz, LinearViscoelastic, PlasticTrapezoid
from contactlab.testing import (
    CLOSED_FORMS,
    ClosedForm,
    GoldenMissingError,
    GoldenStore,
    GoldenTrace,
    NoClosedFormError,
    assert_contact_time,
    assert_matches_closed_form,
    assert_passive,
    assert_restitution,
    assert_trace_matches,
    closed_forms_for,
    compare_impacts,
    register_closed_form,
)
from contactlab.testing import closed_forms as closed_forms_module
from contactlab.testing.golden_trace import REGRESSION_RTOL, STORED_QUANTITIES
from contactlab.testing.strategies import grains, impact_velocities, laws, sensors
from contactlab.traces import Trace

M = 5.0e-5  # grain mass [kg]
GRAIN = cl.Grain.from_mass(M)
V = 2.0  # impact speed [m/s]
K_HERTZ = 1.5e6  # the paper's 5 mm grain on a rigid flat [N/m**1.5]


class StifferHertz(Hertz):
    """Hertz whose force is 1 % larger than its ``k_hertz`` says: a seeded bug."""

    def _force(self, overlap, rate, max_overlap):
        return 1.01 * super()._force(overlap, rate, max_overlap)

    def branch(self, name, max_overlap=0.0):
        return Branch("load", lambda d, r: self._force(d, r, None), loading=False)


class ActiveSpring(ContactLaw):
    """A spring with negative damping: it pushes harder while unloading, creating energy."""

    def __init__(self):
        self._params = {}

    def _force(self, overlap, rate, max_overlap):
        return 1e5 * overlap - 1.0 * rate

    def branch(self, name, max_overlap=0.0):
        return Branch("load", lambda d, r: self._force(d, r, None), loading=False)


def impact(damping=1.0, sensor=None, duration=300e-6):
    """The paper's hard grain (linear law) on its 40 kHz sensor."""
    sensor = sensor or cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    law = LinearViscoelastic(1e5, damping)
    return cl.simulate_impact(GRAIN, sensor, law, velocity=V, duration=duration)


# --- closed forms ---------------------------------------------------------------------
def test_every_law_has_closed_forms():
    # a subset, not equality: register_closed_form adds user classes to the global registry
    # (the public-API tests register one), which must not fail this test by run order
    assert set(LAWS.values()) <= set(CLOSED_FORMS)


def test_closed_forms_name_formula_and_reference():
    forms = {f.quantity: f for f in closed_forms_for(Hertz(K_HERTZ), M, V)}
    assert set(forms) == {"contact_time", "peak_contact_force", "restitution"}
    time = forms["contact_time"]
    assert time.value == analytic.hertz_contact_time(K_HERTZ, M, V)
    assert time.formula.startswith("contactlab.analytic.hertz_contact_time(k_hertz=1.5e+06")
    assert "DOI" in time.reference


def test_restitution_passes_and_fails():
    law = LinearViscoelastic(1e5, 1.0)
    e = analytic.linear_restitution(1e5, 1.0, M, convention="force")
    res = assert_restitution(law, GRAIN, V, e)
    assert res.restitution == pytest.approx(e, rel=1e-6)
    with pytest.raises(AssertionError) as info:
        assert_restitution(law, GRAIN, V, 1.001 * e, source="a wrong value")
    message = str(info.value)
    assert f"restitution [-]: expected {1.001 * e:.10g}, got {res.restitution:.10g}" in message
    assert "> tolerance" in message and "rtol 1e-06" in message
    assert "expected from: a wrong value" in message
    assert "LinearViscoelastic(stiffness=100000, damping=1)" in message


def test_contact_time_fails_with_absolute_tolerance_named():
    law = Hertz(K_HERTZ)
    t_c = analytic.hertz_contact_time(K_HERTZ, M, V)
    assert_contact_time(law, GRAIN, V, t_c + 1e-9, rtol=0.0, atol=2e-9)
    with pytest.raises(AssertionError, match=r"contact_time \[s\].*atol 5e-10"):
        assert_contact_time(law, GRAIN, V, t_c + 1e-9, rtol=0.0, atol=5e-10)


def test_bad_tolerance_is_named():
    with pytest.raises(cl.ParameterError, match="rtol"):
        assert_restitution(Hertz(K_HERTZ), GRAIN, V, 1.0, rtol=-1.0)


def test_matches_closed_form_catches_a_seeded_bug(monkeypatch):
    monkeypatch.setitem(CLOSED_FORMS, StifferHertz, CLOSED_FORMS[Hertz])
    with pytest.raises(AssertionError) as info:
        assert_matches_closed_form(StifferHertz(K_HERTZ), GRAIN, V)
    message = str(info.value)
    assert "contact_time [s]: expected" in message
    assert "peak_contact_force [N]: expected" in message
    assert "restitution" not in message  # still elastic: that closed form holds
    assert "closed form: contactlab.analytic.hertz_contact_time(" in message
    assert "reference:   Johnson, Contact Mechanics" in message


def test_law_without_closed_form_lists_those_with_one():
    with pytest.raises(NoClosedFormError) as info:
        assert_matches_closed_form(StifferHertz(K_HERTZ), GRAIN, V)
    message = str(info.value)
    assert "StifferHertz" in message and "not inherited" in message
    assert "LinearViscoelastic" in message and "Thornton" in message
    assert "register_closed_form" in message


def test_registered_closed_form_is_used(monkeypatch):
    monkeypatch.setattr(closed_forms_module, "CLOSED_FORMS", dict(CLOSED_FORMS))

    def stiffer_hertz(law, mass, velocity):
        time = analytic.hertz_contact_time(1.01 * law.k_hertz, mass, velocity)
        return (ClosedForm("contact_time", time, "Hertz at 1.01 kH", "Johnson (1985)"),)

    assert register_closed_form(StifferHertz, stiffer_hertz) is stiffer_hertz
    assert_matches_closed_form(StifferHertz(K_HERTZ), GRAIN, V)


def test_closed_form_allowance_needs_a_reason():
    with pytest.raises(cl.ParameterError, match="atol_reason"):
        ClosedForm("restitution", 0.5, "series", "ref", atol=1e-3)
    with pytest.raises(cl.ParameterError, match="Did you mean 'restitution'"):
        ClosedForm("restitutoin", 0.5, "series", "ref")


def test_series_allowance_is_stated():
    law = cl.laws.KuwabaraKono(K_HERTZ, 1e-7)
    (form,) = closed_forms_for(law, M, V)
    x = analytic.kuwabara_kono_parameter(K_HERTZ, 1e-7, M, V)
    assert form.atol == pytest.approx(0.5 * x**2.5, rel=1e-12)
    assert "x**2.5" in form.atol_reason


# --- passivity ---------------------------------------------------------------------------
def test_passive_law_returns_the_work_it_absorbed():
    # linear law at 1 m/s: the dashpot absorbs c v d_max per ramp (trapezoid rule exact
    # on straight lines; where unloading clips at zero force it absorbs a little less)
    work = assert_passive(LinearViscoelastic(1e5, 0.1), 1e-4, rate=1.0)
    assert 0.0 < work <= 2 * 0.1 * 1.0 * 1e-4 * (1 + 1e-12)


def test_active_law_fails_passivity():
    assert_passive(ActiveSpring(), 1e-4)  # quasi-statically it is a plain spring
    with pytest.raises(AssertionError) as info:
        assert_passive(ActiveSpring(), 1e-4, rate=1.0)
    message = str(info.value)
    assert "creates energy over a loading-unloading cycle" in message
    assert "work absorbed -" in message and "sign of the damping" in message


def test_passive_rejects_bad_input():
    with pytest.raises(cl.ParameterError, match="force of overlap"):
        assert_passive(PlasticTrapezoid(1e-4), 1e-4)
    with pytest.raises(cl.ParameterError, match="max_overlap"):
        assert_passive(Hertz(K_HERTZ), -1e-4)
    with pytest.raises(cl.ParameterError, match="samples"):
        assert_passive(Hertz(K_HERTZ), 1e-4, samples=1)


# --- trace comparison (contactlab.compare at regression tolerances) ------------------------
def test_result_matches_itself_on_every_quantity():
    res = impact()
    comparison = assert_trace_matches(res, res)
    assert list(comparison.table["quantity"]) == list(QUANTITIES)
    assert list(comparison.table["abs_error"]) == [0.0] * len(QUANTITIES)
    assert list(comparison.table["tolerance"]) == [REGRESSION_RTOL] * len(QUANTITIES)


def test_changed_law_fails_the_comparison():
    with pytest.raises(AssertionError) as info:
        assert_trace_matches(impact(damping=1.01), impact())
    message = str(info.value)
    assert message.startswith("impact differs from its reference in contact_time, ")
    assert "restitution" in message and "waveform_rms_error" in message
    # 1 % more damping moves every number by at most ~6e-3: 1e-2 everywhere lets it pass
    assert_trace_matches(impact(damping=1.01), impact(), dict.fromkeys(QUANTITIES, 1e-2))


def test_measured_trace_compares_on_its_sensor_channel():
    res = impact()
    trace = Trace(res.t, res.sensor_force, "N", {"source": "synthetic"})
    # the trace's lobe is read by linear interpolation on the 15 ns grid, the result's on
    # the exact solution: 1e-4 covers that; the samples themselves are identical
    tolerances = {"sensor_response_time": 1e-4, "peak_sensor_force": 1e-4}
    comparison = assert_trace_matches(trace, res, tolerances)
    verdicts = dict(zip(comparison.table["quantity"], comparison.table["passed"], strict=True))
    assert verdicts["restitution"] is None  # not available on a trace, not failed
    assert comparison.table.set_index("quantity").loc["waveform_max_error", "abs_error"] == 0.0


def test_comparison_refuses_what_it_cannot_compare():
    res = impact()
    volts = Trace(res.t, res.sensor_force, "V", {})
    with pytest.raises(cl.ParameterError, match="cannot compare signals in 'V'"):
        compare_impacts(volts, res)
    with pytest.raises(cl.ParameterError, match="did you mean 'contact_time'"):
        compare_impacts(res, res, {"contact_tme": 1e-6})
    with pytest.raises(cl.ParameterError, match="tolerances must be a dict"):
        compare_impacts(res, res, 1e-6)


# --- golden traces ------------------------------------------------------------------------
def test_golden_round_trip(tmp_path):
    res = impact()
    written = GoldenTrace.of("hard_grain", res, max_samples=500)
    json_path, npz_path = written.write(tmp_path)
    assert (json_path.name, npz_path.name) == ("hard_grain.json", "hard_grain.npz")
    read = GoldenTrace.read(tmp_path, "hard_grain")
    assert read.t.size <= 500
    np.testing.assert_array_equal(read.t, res.t[:: written.metadata["arrays"]["stride"]])
    assert read.quantities == {q: getattr(res, q) for q in STORED_QUANTITIES}  # JSON is exact
    meta = json.loads(json_path.read_text())
    assert meta["contactlab_version"] == cl.__version__ and meta["created"].endswith("+00:00")
    assert meta["setup"]["law_parameters"] == {"stiffness": 1e5, "damping": 1.0}
    assert meta["quantities"]["peak_sensor_force [N]"] == res.peak_sensor_force
    assert_trace_matches(res, read)


def test_missing_golden_says_how_to_create_it(tmp_path):
    with pytest.raises(GoldenMissingError) as info:
        GoldenStore(tmp_path).check("absent", impact())
    assert "--contactlab-update-golden" in str(info.value)
    assert str(tmp_path / "absent.json") in str(info.value)
    assert not list(tmp_path.iterdir())


def test_update_writes_only_what_changed(tmp_path):
    log = []
    store = GoldenStore(tmp_path, update=True, log=log)
    store.check("hard", impact())
    assert len(log) == 1 and log[0].startswith(f"created {tmp_path / 'hard.json'}")
    before = (tmp_path / "hard.json").read_text()
    store.check("hard", impact())  # still matches: left untouched, nothing recorded
    assert len(log) == 1 and (tmp_path / "hard.json").read_text() == before
    store.check("hard", impact(damping=1.01))
    assert log[1].startswith("rewrote") and "outside tolerance: contact_time" in log[1]
    assert "law_parameters.damping: 1.0 -> 1.01" in log[1]
    GoldenStore(tmp_path).check("hard", impact(damping=1.01))


def test_changed_impact_fails_against_golden(tmp_path):
    GoldenStore(tmp_path, update=True).check("hard", impact())
    with pytest.raises(AssertionError) as info:
        GoldenStore(tmp_path).check("hard", impact(damping=1.01))
    message = str(info.value)
    assert "impact differs from golden reference 'hard'" in message
    assert "FAILED contact_time, " in message and "restitution" in message
    assert "set-up changes since the reference: law_parameters.damping: 1.0 -> 1.01" in message
    assert "--contactlab-update-golden" in message


def test_golden_of_a_measured_trace(tmp_path):
    res = impact()
    trace = Trace(res.t, res.sensor_force, "N", {"source": "scope.csv", "format": "generic"})
    store = GoldenStore(tmp_path, update=True)
    store.check("measured", trace)
    read = GoldenTrace.read(tmp_path, "measured")
    assert list(read.channels) == ["sensor_force"]
    assert read.metadata["source"] == "measured trace"
    assert read.setup["source"] == "scope.csv"
    GoldenStore(tmp_path).check("measured", trace)


def test_unreadable_golden_names_the_file(tmp_path):
    GoldenStore(tmp_path, update=True).check("hard", impact())
    (tmp_path / "hard.json").write_text('{"format": "contactlab golden trace",\n oops}')
    with pytest.raises(cl.TraceFormatError, match=r"hard\.json: line 2: not valid JSON"):
        GoldenStore(tmp_path).check("hard", impact())
    log = []
    GoldenStore(tmp_path, update=True, log=log).check("hard", impact())
    assert "unreadable" in log[0]
    GoldenStore(tmp_path).check("hard", impact())


@pytest.mark.parametrize("name", ["../escape", "a/b", "", ".hidden", 3])
def test_golden_name_is_a_file_stem(tmp_path, name):
    with pytest.raises(cl.ParameterError, match="golden name"):
        GoldenStore(tmp_path).check(name, impact())


def test_paper_fig6_golden(golden):
    """The paper's Figure 6 set-up (preset fig6: hard grain on a 20 kHz sensor)."""
    golden.check("paper_fig6", load_preset("fig6").simulate())


# --- strategies ---------------------------------------------------------------------------
@settings(max_examples=30, deadline=None)
@given(grain=grains(), sensor=sensors(rigid=True), velocity=impact_velocities())
def test_strategies_draw_sensible_objects(grain, sensor, velocity):
    assert 0.5e-3 <= grain.diameter <= 20e-3 and 300.0 <= grain.density <= 3000.0
    modulus, poisson, _ = grain.material()
    assert 1e6 <= modulus <= 1e10 and 0.1 <= poisson <= 0.45
    # resonance comes back through k1 = m1 (2 pi f)**2: rounding only
    assert sensor.is_rigid or 10e3 * (1 - 1e-12) <= sensor.resonance <= 300e3 * (1 + 1e-12)
    assert 0.1 <= velocity <= 10.0


@settings(max_examples=10, deadline=None)
@given(data=st.data())
def test_law_strategies_cover_every_law(data):
    for name, cls in LAWS.items():
        assert type(data.draw(laws(name))) is cls


def test_strategy_arguments_are_checked():
    with pytest.raises(cl.ParameterError, match="Did you mean 'hertz'"):
        laws("herz")
    with pytest.raises(cl.ParameterError, match=r"diameter\[1\]"):
        grains(diameter=(2e-3, 1e-3))
    # bounds outside the quantity's own range fail when the strategy is built
    with pytest.raises(cl.ParameterError, match=r"poisson_ratio\[1\] .* <= 0.5"):
        grains(poisson_ratio=(0.1, 0.6))
