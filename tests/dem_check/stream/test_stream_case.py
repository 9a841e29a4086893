"""Stream cases, the feed and the scoring rules, without LAMMPS.

The feed is checked against its definition (regular arrivals reach the cumulative flow's
half-integers; Poisson counts have the flow's mean; every particle arrives at its aim
with the drawn velocity under the case's gravity, in closed form); the matching rules
against hand-made truths and onsets.
"""

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import contactlab as cl
from contactlab.errors import ParameterError
from dem_check.campaign import Effects
from dem_check.stream import DEFAULT_CASE, Feed, Flow, Plate, calibration_curve, read_case, score
from dem_check.stream.feed import gravity_vector, schedule

CASE_TOML = """
[stream]
duration = 0.01
seed = 2

[sensor]
resonance = 40e3
mass = 1.2e-3
damping_ratio = 0.02

[plate]
inclination_deg = 30.0

[flow]
kind = "count"
rate = 500.0
profile = "ramp"
end_rate = 1500.0

[feed]
speed = 4.0
spot = 8e-3

[[particles]]
species = "wheat"
diameter_classes = 2
[particles.contact]
law = "hertz_damped"
from_material = true
restitution = 0.5
"""


def test_read_case_builds_the_species_laws(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(CASE_TOML, encoding="utf-8")
    case = read_case(path)
    (kind,) = case.particles
    assert kind.name == "wheat" and kind.diameter == (3.07e-3, 4.26e-3)
    classes = kind.classes()
    assert len(classes) == 2
    grain, law, tangential = classes[0]
    # the class law is the toolkit's own Hertz-Mindlin law of that grain
    expected = cl.laws.HertzDamped.from_material(grain.material(), 0.5, grain.mass)
    assert law.k_hertz == expected.k_hertz and law.damping == expected.damping
    assert tangential is None
    assert case.sensor.resonance == pytest.approx(40e3, rel=1e-12)  # rounding of k1/m1


WHEAT = "[[particles]]\nspecies = 'wheat'\ncontact = {law = 'linear', stiffness = 1e4}\n"


def test_read_case_reads_straw_and_record_effects(tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(
        CASE_TOML + "[[particles]]\nname = 'straw'\ndiameter = 3e-3\ndensity = 150.0\nspheres = 6\n"
        "spacing = 0.5\ntilt_deg = 20.0\ncontact = {law = 'linear', stiffness = 5e3}\n"
        "[effects]\nhum = 0.02\nharmonics = [0.3]\nplate_modes = [[730.0, 0.01]]\n"
        "full_scale = 20.0\n",
        encoding="utf-8",
    )
    case = read_case(path)
    straw = case.particles[1]
    assert (straw.spheres, straw.spacing, straw.tilt_deg) == (6, 0.5, 20.0)
    # centres 0.5 diameters apart about the centre of mass
    assert straw.offsets(3e-3) == pytest.approx(
        [-3.75e-3, -2.25e-3, -0.75e-3, 0.75e-3, 2.25e-3, 3.75e-3], abs=1e-18
    )
    grain = straw.classes()[0][0]
    # the law's grain: a sphere's diameter carrying the clump's mass (six spheres)
    assert grain.mass == pytest.approx(6 * 150.0 * math.pi / 6 * 3e-3**3, rel=1e-15)
    assert case.effects == Effects(
        hum=0.02, harmonics=(0.3,), plate_modes=((730.0, 0.01),), full_scale=20.0
    )


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("[flow]\nrate = 1.0\n[[particles]]\ndiameter = 1e-3\ndensity = 1e3\n", "contact"),
        ("[flow]\nrate = 1.0\nprofile = 'square'\n", "profile"),
        ("[flow]\nrate = 1.0\n[stream]\nduraton = 1.0\n", "duraton"),
        (
            "[[particles]]\nspecies = 'wheat'\ncontact = {law = 'linear', stiffness = 1e4}\n",
            "[flow]",
        ),
        (
            "[flow]\nrate = 1.0\n[[particles]]\nspecies = 'wheat'\nspheres = 0\n"
            "contact = {law = 'linear', stiffness = 1e4}\n",
            "spheres",
        ),
        (
            "[flow]\nrate = 1.0\n[[particles]]\nspecies = 'wheat'\nspacing = 1.5\n"
            "contact = {law = 'linear', stiffness = 1e4}\n",
            "spacing",
        ),
        (WHEAT + "[flow]\nrate = 1.0\n[effects]\nbounce = 0.4\n", "bounce"),
        (WHEAT + "[flow]\nrate = 1.0\n[effects]\nhum = -1.0\n", "hum"),
        (WHEAT + "[flow]\nrate = 1.0\n[effects]\nhumm = 1.0\n", "humm"),
    ],
)
def test_bad_cases_are_refused_naming_the_key(tmp_path, text, named):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ParameterError, match=str(path)) as info:
        read_case(path)
    assert named in str(info.value)


def test_regular_arrivals_follow_the_cumulative_flow():
    case = DEFAULT_CASE.with_(
        flow=Flow(rate=1000.0, end_rate=3000.0, profile="ramp", arrivals="regular"),
        duration=0.01,
        time_step=1e-6,
    )
    table = schedule(case).table
    # cumulative count of a linear ramp 1000 -> 3000 1/s over 10 ms: 20 particles
    assert len(table) == 20
    lead = schedule(case).lead
    t = np.sort(table["aim_time [s]"].to_numpy()) - lead
    # the k-th arrives where 1000 t + 1e5 t**2 = k + 1/2 (closed form of the ramp)
    expected = (-1000.0 + np.sqrt(1000.0**2 + 4e5 * (np.arange(20) + 0.5))) / 2e5
    # the cumulative flow is integrated on a 1e5-interval grid (trapezoids, exact for a ramp)
    assert t == pytest.approx(expected, abs=1e-9)


def test_poisson_counts_have_the_flows_mean():
    counts = [
        len(schedule(DEFAULT_CASE.with_(duration=0.05, seed=s, time_step=1e-6)).table)
        for s in range(20)
    ]
    # 400 1/s for 50 ms: mean 20 per run, 400 in all; Poisson sd of the total is 20, so 4 sd
    assert abs(sum(counts) - 400) < 80


def test_every_particle_reaches_its_aim_with_its_velocity():
    case = DEFAULT_CASE.with_(
        plate=Plate(inclination_deg=35.0),
        feed=Feed(speed=3.0, speed_sd=0.5, incidence_deg=20.0, incidence_sd_deg=5.0, spot=8e-3),
        duration=0.02,
        time_step=1e-6,
    )
    drawn = schedule(case)
    g = gravity_vector(case)
    assert g == pytest.approx(
        [9.81 * math.sin(math.radians(35.0)), 0.0, -9.81 * math.cos(math.radians(35.0))], rel=1e-15
    )
    slot = drawn.slot_steps * drawn.time_step
    for _, row in drawn.table.iterrows():
        back = row["aim_time [s]"] - row["slot"] * slot
        x = row[["x [m]", "y [m]", "z [m]"]].to_numpy(float)
        v = row[["vx [m/s]", "vy [m/s]", "vz [m/s]"]].to_numpy(float)
        at_aim, v_aim = x + v * back + 0.5 * g * back**2, v + g * back
        # ballistic closed form: the centre is one radius above the plate at the aim time
        # (a straw's centre of mass: its lowest sphere's, half its row of touching
        # spheres higher along its tilted axis)
        rise = 0.5 * (row["spheres"] - 1) * row["diameter [m]"] * row["axis_z [-]"]
        assert at_aim[2] == pytest.approx(row["diameter [m]"] / 2 + rise, abs=1e-12)
        assert np.hypot(*at_aim[:2]) <= case.feed.spot + 1e-12
        assert np.linalg.norm(v_aim) == pytest.approx(row["speed [m/s]"], rel=1e-12)
        incidence = math.degrees(math.acos(-v_aim[2] / np.linalg.norm(v_aim)))
        assert incidence == pytest.approx(row["incidence [deg]"], abs=1e-9)


def _fake_result(touches, kinds=None):
    truth = pd.DataFrame(
        {"pid": range(len(touches)), "kind": kinds or ["g"] * len(touches), "touch [s]": touches}
    )
    case = SimpleNamespace(sensor=cl.Sensor.from_resonance(40e3, mass=1e-3, damping_ratio=0.02))
    steps = pd.DataFrame({"t [s]": [0.0, 1.0], "sensor_force [N]": [0.0, 0.0]})
    return SimpleNamespace(truth=truth, case=case, steps=steps)


def test_matching_counts_hits_merges_misses_and_false_alarms():
    result = _fake_result([1e-3, 2e-3, 2.001e-3, 5e-3])
    onsets = [0.9e-3, 1.999e-3, 3.5e-3, 4.0e-3]

    def detector(trace, sensor):
        return onsets

    scored = score(result, detector, trace=object())
    # 1 ms: hit (onset 0.1 ms early); 2 and 2.001 ms: one detection, merged; the 3.5 and
    # 4 ms detections hold none (false alarms): 5 ms is 40 sensor periods after the 4 ms
    # onset, beyond the 20-period reach, so a miss
    assert scored.counts == {
        "impacts": 4,
        "hits": 1,
        "merged": 2,
        "misses": 1,
        "false_alarms": 2,
        "detections": 4,
    }
    hits = scored.matches[scored.matches["outcome"] == "hit"]
    assert hits["onset_error [s]"].to_numpy() == pytest.approx([-0.1e-3], abs=1e-15)


def test_an_impact_before_every_detection_is_a_miss():
    scored = score(_fake_result([1e-3, 2.2e-3]), lambda trace, sensor: [2e-3], trace=object())
    assert scored.counts["misses"] == 1 and scored.counts["hits"] == 1


def test_peaks_a_detector_gives_are_scored_against_the_clean_signal():
    result = _fake_result([1e-3])
    t = np.arange(0.0, 2e-3, 1e-6)
    # a clean S1 of one lobe peaking at 3 N, 10 us after the touch
    s1 = 3.0 * np.exp(-(((t - 1.01e-3) / 5e-6) ** 2))
    result.steps = pd.DataFrame({"t [s]": t, "sensor_force [N]": s1})
    scored = score(result, lambda trace, sensor: [(0.999e-3, 2.7)], trace=object())
    row = scored.matches.iloc[0]
    assert row["outcome"] == "hit"
    # the grid holds the lobe's top exactly (1.010 ms is a sample): 3 N, error -0.3 N
    assert row["signal_peak [N]"] == pytest.approx(3.0, rel=1e-12)
    assert row["peak_error [N]"] == pytest.approx(-0.3, rel=1e-12)


def test_oscillating_regular_flow_delivers_its_integral():
    flow = Flow(rate=2000.0, profile="oscillating", amplitude=0.5, frequency=30.0)
    case = DEFAULT_CASE.with_(flow=replace(flow, arrivals="regular"), duration=0.02, time_step=1e-6)
    # closed form of the integral: r (T + A (1 - cos 2 pi f T) / (2 pi f))
    total = 2000.0 * (0.02 + 0.5 * (1 - math.cos(2 * math.pi * 30.0 * 0.02)) / (2 * math.pi * 30.0))
    assert len(schedule(case).table) == math.floor(total + 0.5)


def test_calibration_recovers_a_linear_plate():
    """A plate whose mean signal is exactly 2 + 300 N*s/kg times the mass flow: the fit
    inverts it and the test errors vanish (the arithmetic, not the physics)."""

    def run(case):
        steps = pd.DataFrame({"t [s]": [0.0, 1.0], "sensor_force [N]": [0.0, 0.0]})
        steps["sensor_force [N]"] = 2.0 + 300.0 * case.flow.rate
        return SimpleNamespace(steps=steps, lead=0.0)

    calibration = calibration_curve(DEFAULT_CASE, capacity=0.1, run=run)
    assert calibration.slope == pytest.approx(1.0 / 300.0, rel=1e-12)
    assert calibration.intercept == pytest.approx(-2.0 / 300.0, rel=1e-12)
    assert np.abs(calibration.table["error [%]"]).max() < 1e-9
    assert list(calibration.table["flow [kg/s]"]) == pytest.approx([0.025, 0.05, 0.075, 0.1])


def test_discrimination_separates_three_kinds_and_counts_every_hit():
    from dem_check.stream import FEATURES, discrimination

    rng = np.random.default_rng(0)
    centres = {"wheat": 6.0, "chaff": 0.4, "straw": 0.05}  # peak [N]
    rows = []
    for kind, peak in centres.items():
        for _ in range(15):
            values = np.exp(rng.normal(0.0, 0.05, len(FEATURES)))  # 5 % scatter
            rows.append(
                {
                    "kind": kind,
                    **dict(zip(FEATURES, values * [peak, 2e-5, 1e-4, 3e-5], strict=True)),
                }
            )
    matrix = discrimination(pd.DataFrame(rows))
    # log peaks 2 to 5 apart against a scatter of 0.05: no centroid is nearer than its own
    assert list(matrix.index) == list(matrix.columns) == sorted(centres)
    assert np.array_equal(matrix.to_numpy(), 15 * np.eye(3, dtype=int))
