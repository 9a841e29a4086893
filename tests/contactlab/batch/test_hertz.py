"""hertz_impacts against simulate_impact row by row, closed forms on a wall, accuracy
against a converged solution, re-contacts, handed-back rows, bad rows, threads, Dask."""

import functools
import math
import warnings

import numpy as np
import pandas as pd
import pytest
import rowcheck
from rowcheck import relative

import contactlab as cl
from contactlab import analytic
from contactlab.batch import RESULT_COLUMNS, dask_hertz_impacts, hertz_impacts
from contactlab.batch.rows import result_row
from contactlab.errors import ParameterError, PlausibilityWarning

# The random frames reach over-damped sensors (damping ratio up to 3.2) on purpose, to cover
# the kernels' real-mode branches: beyond real sensors, so the PlausibilityWarning is expected.
pytestmark = pytest.mark.filterwarnings("ignore::contactlab.errors.PlausibilityWarning")

COLUMNS = (*rowcheck.BODY_COLUMNS, "k_hertz [N/m**1.5]", "damping [N*s/m**1.25]", "v0 [m/s]")
EVENTS = [0, 1, 4, 5]
"""contact time, response time, restitution, contacts: event times and states."""
PEAKS = [2, 3]
EPS = np.finfo(float).eps


def random_frame(rng, n, **bodies):
    """Sensors 3 kHz - 300 kHz with damping ratios 1e-3 - 3 (under- and overdamped; the
    keywords of ``rowcheck.random_bodies``), grains 0.01 - 30 times the sensor mass, Hertz
    stiffness 1e5 - 1e9 N/m**1.5 with restitution 0.05 - 1 (15 % elastic), speeds 0.1 -
    10 m/s, 15 % immovable walls."""
    m1, k1, c1, m2 = rowcheck.random_bodies(rng, n, **bodies)
    k_hertz = 10 ** rng.uniform(5, 9, n)
    e = rng.uniform(0.05, 1.0, n)
    cases = zip(k_hertz, m2, e, strict=True)
    eta = np.array([analytic.tsuji_damping_coefficient(*case) for case in cases])
    eta[rng.random(n) < 0.15] = 0.0
    k1[rng.random(n) < 0.15] = np.inf
    values = (m1, k1, c1, m2, k_hertz, eta, 10 ** rng.uniform(-1, 1, n))
    return pd.DataFrame(dict(zip(COLUMNS, values, strict=True)))


def single(row, rtol):
    """The six numbers by simulate_impact (adaptive) at ``rtol``."""
    m1, k1, c1, m2, k_hertz, eta, v0 = row
    sensor = cl.Sensor.rigid() if math.isinf(k1) else cl.Sensor(m1, k1, c1)
    law = cl.laws.HertzDamped(k_hertz, eta)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # coarse default grids: the numbers are dense
        res = cl.simulate_impact(cl.Grain.from_mass(m2), sensor, law, v0, rtol=rtol)
    return np.array(result_row(res))


def test_random_rows_give_the_single_solvers_numbers_at_the_same_tolerance():
    frame = random_frame(np.random.default_rng(15), 600)
    got = hertz_impacts(frame, rtol=1e-10)[list(RESULT_COLUMNS)].to_numpy()
    ref = np.array([single(row, 1e-10) for row in frame.to_numpy()])
    rel = relative(got, ref)
    single_contact = ref[:, 5] == 1
    # the same compiled steps: events agree to round-off (measured worst 1e-15)
    assert rel[single_contact][:, EVENTS].max() <= 1e-12, rel[:, EVENTS].max(axis=0)
    # after a re-contact the two solvers start the next piece from a touch found by two
    # root finders (modal scan, roots.py) to round-off, and the adaptive step control
    # turns a round-off difference into one of order rtol: the single solver's own
    # numbers move as much when v0 is nudged by 1-4 ulp (2.3e-11 measured on one row),
    # so the batch must stay within twice that spread, measured here
    for i in np.flatnonzero(~single_contact):
        row = frame.to_numpy()[i]
        nudged = [single(np.r_[row[:6], row[6] * (1 + k * EPS)], 1e-10) for k in range(1, 5)]
        spread = relative(np.array(nudged), ref[i]).max(axis=0)
        assert np.all(rel[i, EVENTS] <= 2 * spread[EVENTS] + 1e-12), (i, rel[i], spread)
    # peaks: the batch roots the slope on the dense output, the single solver zooms in
    # from its grid to ~1e-5 of a sample interval (measured worst 8e-10 on 1000 rows)
    assert rel[:, PEAKS].max() <= 2e-9, rel[:, PEAKS].max(axis=0)


def test_default_tolerance_gives_every_number_to_one_part_in_a_million():
    frame = random_frame(np.random.default_rng(7), 300)
    got = hertz_impacts(frame)[list(RESULT_COLUMNS)].to_numpy()
    converged = np.array([single(row, 1e-12) for row in frame.to_numpy()])
    rel = relative(got, converged)
    # the requirement (measured worst 7e-8 at the default rtol 1e-9)
    assert rel.max() <= 1e-6, rel.max(axis=0)


@pytest.mark.parametrize("restitution", [1.0, 0.8, 0.5, 0.2])
def test_wall_rows_follow_the_closed_forms(restitution):
    m2 = np.array([5e-5, 2e-3, 0.1])
    k_hertz, v0 = np.array([1e7, 3e8, 2e6]), np.array([2.0, 0.3, 5.0])
    alpha = analytic.tsuji_damping_factor(restitution) if restitution < 1 else 0.0
    eta = alpha * np.sqrt(m2 * k_hertz)
    values = (np.inf, np.inf, 0.0, m2, k_hertz, eta, v0)
    got = hertz_impacts(pd.DataFrame(dict(zip(COLUMNS, values, strict=True))))
    e_force = analytic.tsuji_restitution(alpha, "force")
    # rtol 1e-8 integration; the closed forms are exact (restitution: velocity-free)
    np.testing.assert_allclose(got["restitution [-]"], e_force, rtol=1e-7)
    if restitution == 1.0:
        cases = list(zip(k_hertz, m2, v0, strict=True))
        t_c = [analytic.hertz_contact_time(*case) for case in cases]
        peak = [analytic.hertz_max_force(*case) for case in cases]
        np.testing.assert_allclose(got["contact_time [s]"], t_c, rtol=1e-7)
        np.testing.assert_allclose(got["peak_contact_force [N]"], peak, rtol=1e-7)
    # on a wall the signal is the contact force: its lobe is the contact
    np.testing.assert_array_equal(got["sensor_response_time [s]"], got["contact_time [s]"])
    np.testing.assert_array_equal(got["peak_sensor_force [N]"], got["peak_contact_force [N]"])
    assert (got["contacts [-]"] == 1).all()


def test_a_light_grain_on_a_ringing_plate_recontacts_as_in_the_single_solver():
    row = [2.5166e-4, 4.33978e5, 0.172437, 5.7397e-4, 8.69221e8, 0.0, 0.539066]
    got = hertz_impacts(pd.DataFrame([row], columns=COLUMNS), rtol=1e-10)
    got = got[list(RESULT_COLUMNS)].to_numpy()[0]
    ref = single(row, 1e-10)
    assert ref[5] == 3  # two re-contacts in the window
    assert np.all(relative(got, ref)[EVENTS] <= 1e-12)  # round-off, as above
    assert np.all(relative(got, ref)[PEAKS] <= 2e-9)  # the single solver's zoom, as above


def test_a_critically_damped_plate_is_handed_to_the_single_solver():
    """The modal free flight needs distinct modes; that row is simulate_impact's own."""
    m1, k1 = 1.233e-3, 7.79e7
    row = [m1, k1, 2.0 * math.sqrt(k1 * m1), 5e-5, 1e7, 0.02, 2.0]
    got = hertz_impacts(pd.DataFrame([row], columns=COLUMNS), rtol=1e-9)
    np.testing.assert_array_equal(got[list(RESULT_COLUMNS)].to_numpy()[0], single(row, 1e-9))


paper_frame = functools.partial(rowcheck.paper_frame, COLUMNS, 5.6e6, 0.05)


@pytest.mark.parametrize(
    ("column", "value", "message"),
    [
        *rowcheck.BAD_BODY_ROWS,
        ("damping [N*s/m**1.25]", -1.0, "'damping [N*s/m**1.25]' (Hertz damping eta of F"),
        ("k_hertz [N/m**1.5]", np.inf, "'k_hertz [N/m**1.5]' (Hertz stiffness kH of F"),
    ],
)
def test_a_bad_row_is_named_by_column_and_first_row(column, value, message):
    rowcheck.assert_bad_row_named(hertz_impacts, paper_frame(6), column, value, message)


def test_missing_columns_and_bad_options_are_named():
    with pytest.raises(ParameterError, match=r"no column\(s\) \['k_hertz \[N/m\*\*1.5\]'\]"):
        hertz_impacts(paper_frame(3).drop(columns="k_hertz [N/m**1.5]"))
    with pytest.raises(ParameterError, match="rtol"):
        hertz_impacts(paper_frame(3), rtol=0.1)
    with pytest.raises(ParameterError, match="threads"):
        hertz_impacts(paper_frame(3), threads=0)


def test_rows_keep_order_and_index_whatever_the_chunk_and_threads():
    frame = random_frame(np.random.default_rng(3), 120).sample(frac=1.0, random_state=3)
    frame["label"] = np.arange(120)
    whole = hertz_impacts(frame)
    # rows are independent: chunks and threads change nothing, bit for bit
    pd.testing.assert_frame_equal(hertz_impacts(frame, chunk=7), whole, check_exact=True)
    pd.testing.assert_frame_equal(hertz_impacts(frame, chunk=9, threads=2), whole, check_exact=True)
    pd.testing.assert_index_equal(whole.index, frame.index)
    pd.testing.assert_frame_equal(whole[frame.columns], frame)


def test_dask_partitions_give_the_same_frame(dask_client):
    # real sensors only (damping ratio <= 0.8): the workers' threads warn nothing, which
    # the local run shows
    frame = random_frame(np.random.default_rng(4), 60, most_damping=0.8)
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        local = hertz_impacts(frame, rtol=1e-9)
    for partitions in (None, 7):
        on_dask = dask_hertz_impacts(frame, dask_client, rtol=1e-9, partitions=partitions)
        pd.testing.assert_frame_equal(on_dask, local, check_exact=True)
    bad = frame.copy()
    bad.iloc[50, 3] = -1.0
    with pytest.raises(ParameterError, match=r"row 50 "):
        dask_hertz_impacts(bad, dask_client, partitions=3)
