"""Straw: rigid clumps of spheres (LAMMPS ``fix rigid/small``) in the stream.

* A straw dropped flat is, for the sensor, one body of the clump's mass on ``n``
  parallel contacts: with a linear law (stiffness ``k``, damping ``c``, mapped for the
  clump's mass, which LAMMPS' wall uses as ``m*`` for a body's sphere) it equals
  contactlab's exact two-mass solver with one contact of ``n k`` and ``n c``.
* Its impulse (the summed plate forces on its spheres, from the contact dump) equals its
  momentum change (the clump's centre-of-mass velocities, the same dump) and the plate
  force's integral (the walls' reduction, the step series).
* A tilted straw touches with its lowest sphere at the drawn aim time.
* The insertion clearance's capsule distance against a brute-force search.
"""

import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from stream_readings import impact_readings

import contactlab as cl
from contactlab.laws import LinearViscoelastic
from dem_check.stream import Feed, Flow, ParticleKind, StreamCase, run_stream
from dem_check.stream.clearance import segment_distances

SENSOR = cl.Sensor.from_resonance(40e3, mass=1.2e-3, damping_ratio=0.02)
SPHERES = 4
STIFFNESS, DAMPING = 2e3, 0.05


def _straw(tilt_deg):
    return ParticleKind(
        name="straw",
        diameter=3e-3,
        density=300.0,
        spheres=SPHERES,
        tilt_deg=tilt_deg,
        contact={"law": "linear", "stiffness": STIFFNESS, "damping": DAMPING},
    )


def _one_straw(tilt_deg, steps_per_contact):
    case = StreamCase(
        particles=(_straw(tilt_deg),),
        sensor=SENSOR,
        flow=Flow(rate=1.0 / 4e-4, arrivals="regular"),
        feed=Feed(speed=2.0, spot=0.0, release=1e-3),
        duration=4e-4,
        gravity=0.0,
        steps_per_contact=steps_per_contact,
        slot=2e-4,
        seed=3,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return run_stream(case)


@pytest.fixture(scope="module")
def flat():
    return _one_straw(0.0, 200)


pytestmark = pytest.mark.lammps


def test_flat_straw_equals_one_body_on_n_contacts(flat):
    truth = flat.truth
    assert len(truth) == 1 and truth["recontacts"].iloc[0] == 0
    row = truth.iloc[0]
    grain = _straw(0.0).classes()[0][0]
    assert row["mass [kg]"] == pytest.approx(SPHERES * 300.0 * np.pi / 6 * 3e-3**3, rel=1e-12)
    law = LinearViscoelastic(SPHERES * STIFFNESS, SPHERES * DAMPING)
    ref = cl.simulate_impact(grain, SENSOR, law, 2.0)
    for name, value in impact_readings(flat).items():
        # the single-grain check's 1 %; measured <= 2.5e-3 at tc/200 (peak S1, read on
        # the step grid), 1.6e-3 restitution
        assert value == pytest.approx(getattr(ref, name), rel=1e-2), name
    # dropped flat, it does not turn: no tangential rebound
    assert row["tangential_speed [m/s]"] == pytest.approx(0.0, abs=1e-12)


def test_straw_impulse_is_its_momentum_change_and_the_plate_force(flat):
    row = flat.truth.iloc[0]
    change = row["mass [kg]"] * (row["normal_speed [m/s]"] + row["rebound_normal_speed [m/s]"])
    # the 1e-3; measured 9e-6 (the dump's velocities are the rigid body's centre
    # of mass, its forces the spheres': velocity Verlet on the body)
    assert row["impulse [N*s]"] == pytest.approx(change, rel=1e-3)
    plate = flat.steps["contact_force [N]"]
    # the same doubles summed in another order (the walls' reduction against the dump)
    assert plate.sum() * flat.time_step == pytest.approx(row["impulse [N*s]"], rel=1e-12)
    assert plate.max() == pytest.approx(row["peak_force [N]"], rel=1e-12)


def test_tilted_straw_touches_with_its_lowest_sphere_at_the_aim():
    result = _one_straw(60.0, 50)
    first = result.truth[result.truth["contact"] == 0].iloc[0]
    aim = result.particles.loc[int(first["pid"]), "aim_time [s]"]
    assert result.particles.loc[int(first["pid"]), "axis_z [-]"] > 0.1  # drawn tilted
    # the touch is interpolated within one step from the overlap and approach speed
    assert first["touch [s]"] == pytest.approx(aim, abs=0.05 * result.time_step)


unit = st.floats(-1.0, 1.0, allow_nan=False)


@given(
    d=st.tuples(unit, unit, unit),
    u=st.tuples(unit, unit, unit),
    w=st.tuples(unit, unit, unit),
    h=st.floats(0.0, 1.0),
    k=st.floats(0.0, 1.0),
)
def test_capsule_distance_against_a_search(d, u, w, h, k):
    d, u, w = (np.array(v) for v in (d, u, w))
    if np.linalg.norm(u) < 0.1 or np.linalg.norm(w) < 0.1:
        return
    u, w = u / np.linalg.norm(u), w / np.linalg.norm(w)
    s, t = np.meshgrid(np.linspace(-h, h, 201), np.linspace(-k, k, 201), indexing="ij")
    points = d + s[..., None] * u - t[..., None] * w
    brute = np.linalg.norm(points, axis=-1).min()
    got = float(segment_distances(d, u, h, w, np.array([k]))[0])
    assert got <= brute + 1e-12  # a search can only overestimate the minimum
    # the grid's steps are 2h/200 and 2k/200: its minimum is within half a step along each
    # segment of the true one, (h + k)/200 (unit directions); twice that for rounding
    assert got >= brute - 2.0 * (h + k) / 200.0 - 1e-12
