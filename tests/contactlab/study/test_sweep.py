"""Sweeps: grid handling, seeds, statistics, backends (serial, processes, Dask), trends."""

import math
import sys
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

import contactlab as cl
from contactlab import metrics
from contactlab.laws import Hertz, LinearViscoelastic, PlasticTrapezoid
from contactlab.solver.wall import wall_contact_time
from contactlab.study import (
    Scatter,
    StudySetup,
    diameter_sweep,
    frequency_sweep,
    point_statistics,
    run_grid,
)
from contactlab.study.execution import run_tasks

GRID = {"grain.diameter": [2.5e-3, 5.0e-3], "sensor.resonance": [20e3, 200e3]}


@pytest.fixture(scope="module")
def setup():
    """The paper's set-up with 3 repetitions per point (quick)."""
    return StudySetup.paper(scatter=Scatter(repetitions=3))


@pytest.fixture(scope="module")
def serial(setup):
    return run_grid(setup, GRID, seed=7)


def test_grid_order_columns_and_units(serial):
    points, impacts = serial.points, serial.impacts
    assert len(points) == 4 and len(impacts) == 12
    # the first grid name varies slowest
    assert points["diameter [m]"].tolist() == [2.5e-3, 2.5e-3, 5e-3, 5e-3]
    assert points["resonance [Hz]"].tolist() == [20e3, 200e3, 20e3, 200e3]
    for column in (
        "time_error [%]",
        "force_error [%]",
        "time_error_mean [%]",
        "time_error_rms [%]",
        "force_error_mean [%]",
        "force_error_rms [%]",
        "repetitions [-]",
    ):
        assert column in points.columns
    for column in (
        "stiffness [N/m]",
        "contact_time [s]",
        "sensor_response_time [s]",
        "peak_contact_force [N]",
        "peak_sensor_force [N]",
        "repetition [-]",
    ):
        assert column in impacts.columns
    assert (points["repetitions [-]"] == 3).all()


def test_stiffness_drawn_within_half_of_the_mean(serial):
    k = serial.impacts["stiffness [N/m]"]
    assert k.between(0.5e5, 1.5e5).all()
    assert k.nunique() == len(k)  # every impact has its own draw


def test_statistics_equal_a_direct_recomputation(serial):
    for (d, f), group in serial.impacts.groupby(["diameter [m]", "resonance [Hz]"]):
        row = serial.points[
            (serial.points["diameter [m]"] == d) & (serial.points["resonance [Hz]"] == f)
        ].iloc[0]
        for q in ("time", "force"):
            e = group[f"{q}_error [%]"].to_numpy()
            # the same arithmetic in another order: agreement to a few ulps
            assert row[f"{q}_error [%]"] == pytest.approx(np.std(e), rel=1e-12)
            assert row[f"{q}_error_mean [%]"] == pytest.approx(np.mean(e), rel=1e-12)
            assert row[f"{q}_error_rms [%]"] == pytest.approx(np.sqrt(np.mean(e**2)), rel=1e-12)
            # population std: rms**2 = mean**2 + std**2 up to rounding
            assert row[f"{q}_error_rms [%]"] ** 2 == pytest.approx(
                row[f"{q}_error_mean [%]"] ** 2 + row[f"{q}_error [%]"] ** 2, rel=1e-10
            )


def test_per_impact_errors_are_those_of_a_direct_simulation(setup, serial):
    row = serial.impacts.iloc[4]
    grain = cl.Grain(diameter=row["diameter [m]"], density=765.0)
    sensor = cl.Sensor.from_resonance(
        row["resonance [Hz]"], mass=setup.sensor.mass, damping_ratio=0.02
    )
    law = LinearViscoelastic(row["stiffness [N/m]"], 1.0)
    res = cl.simulate_impact(grain, sensor, law, 2.0)
    # the study's window and grid are its own; the events and lobe are exact, so the numbers
    # agree to the solver's accuracy
    assert row["contact_time [s]"] == pytest.approx(res.contact_time, rel=1e-9)
    assert row["time_error [%]"] == pytest.approx(
        100 * (res.sensor_response_time / res.contact_time - 1), abs=1e-6
    )
    assert row["force_error [%]"] == pytest.approx(
        100 * (res.peak_sensor_force / res.peak_contact_force - 1), abs=1e-6
    )


def test_seed_reproducible_and_independent_of_the_grid_around(setup, serial):
    again = run_grid(setup, GRID, seed=7)
    pd.testing.assert_frame_equal(again.impacts, serial.impacts, check_exact=True)
    other = run_grid(setup, GRID, seed=8)
    assert not np.allclose(other.impacts["stiffness [N/m]"], serial.impacts["stiffness [N/m]"])
    # point 0 draws from its own seed sequence, whatever follows it in the grid
    alone = run_grid(setup, {"grain.diameter": [2.5e-3], "sensor.resonance": [20e3]}, seed=7)
    first = serial.impacts[serial.impacts["point [-]"] == 0]
    np.testing.assert_array_equal(alone.impacts["stiffness [N/m]"], first["stiffness [N/m]"])


def test_processes_give_the_serial_result_bit_for_bit(setup, serial):
    # one point per chunk: chunks finish out of order on two processes
    parallel = run_grid(setup, GRID, seed=7, workers=2, chunksize=1)
    pd.testing.assert_frame_equal(parallel.impacts, serial.impacts, check_exact=True)
    pd.testing.assert_frame_equal(parallel.points, serial.points, check_exact=True)


@pytest.fixture(scope="module")
def dask_cluster():
    distributed = pytest.importorskip("dask.distributed")
    # threads in this process: quick to start; the dashboard on a free port (``None``
    # binds distributed's default 8787, where two test workers' clusters collided)
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=False, dashboard_address=":0"
    ) as cluster:
        yield cluster


def test_dask_gives_the_serial_result_bit_for_bit(setup, serial, dask_cluster):
    from dask.distributed import Client

    with Client(dask_cluster) as client:
        on_client = run_grid(setup, GRID, seed=7, client=client, chunksize=1)
    on_address = run_grid(setup, GRID, seed=7, client=dask_cluster.scheduler_address)
    for result in (on_client, on_address):
        pd.testing.assert_frame_equal(result.impacts, serial.impacts, check_exact=True)


def test_dask_missing_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    with pytest.raises(ImportError, match=r"contactlab\[dask\]"):
        run_tasks(abs, [1, -2], client="tcp://127.0.0.1:1")


def test_bad_client_and_workers_named():
    with pytest.raises(cl.ParameterError, match="client"):
        run_tasks(abs, [1], client=42)
    with pytest.raises(cl.ParameterError, match="workers"):
        run_tasks(abs, [1], workers=1.5)


def test_progress_bar_on_request(setup, capsys):
    run_grid(setup, {"sensor.resonance": [100e3]}, progress=True)
    assert "impacts" in capsys.readouterr().err


def test_unknown_grid_name_suggests_the_near_match(setup):
    with pytest.raises(cl.ParameterError, match=r"Did you mean 'sensor\.resonance'"):
        run_grid(setup, {"sensor.resonanse": [40e3]})
    with pytest.raises(cl.ParameterError, match=r"law\.stiffness"):
        run_grid(setup, {"law.stifness": [1e5]})
    with pytest.raises(cl.ParameterError, match="non-empty"):
        run_grid(setup, {"sensor.resonance": []})
    with pytest.raises(cl.ParameterError, match=r"grid\['sensor\.resonance'\].*'40 kHz'"):
        run_grid(setup, {"sensor.resonance": ["40 kHz"]})


def test_law_and_velocity_are_grid_parameters(setup):
    res = run_grid(setup, {"law.damping": [0.0, 1.0], "velocity": [1.0]})
    assert "damping [N*s/m]" in res.points.columns and "velocity [m/s]" in res.points.columns
    swept = run_grid(setup, {"law.stiffness": [5e4]})
    assert "stiffness_mean [N/m]" in swept.points.columns  # the scatter's mean
    assert swept.impacts["stiffness [N/m]"].between(2.5e4, 7.5e4).all()


def test_errors_fall_as_the_resonance_rises():
    # elastic contact: no force step at first touch (see docs/study.md)
    setup = StudySetup.paper(law=LinearViscoelastic(1e5, 0.0), scatter=Scatter(repetitions=3))
    res = frequency_sweep(setup, [10e3, 300e3], diameters=[5e-3], seed=1)
    low, high = res.points.iloc[0], res.points.iloc[1]
    # a factor 10 at least: 68 % -> 0.6 % (force) and 27 % -> 0.05 % (time) in the study
    assert high["force_error_rms [%]"] < 0.1 * low["force_error_rms [%]"]
    assert high["time_error_rms [%]"] < 0.1 * low["time_error_rms [%]"]


def test_errors_fall_as_the_grain_grows():
    setup = StudySetup.paper(law=LinearViscoelastic(1e5, 0.0), scatter=Scatter(repetitions=3))
    res = diameter_sweep(setup, [1.5e-3, 8e-3], resonances=[40e3], seed=1)
    small, large = res.points.iloc[0], res.points.iloc[1]
    assert large["force_error_rms [%]"] < 0.5 * small["force_error_rms [%]"]
    assert large["time_error_rms [%]"] < 0.5 * small["time_error_rms [%]"]


def test_the_grid_resolves_the_lobe_and_the_peaks(setup):
    """Reading the metrics off the study's output grid changes them far less than the errors
    the study reports (0.5-200 %): the grid is fine enough for either reading."""
    for d, f in ((2.5e-3, 300e3), (5e-3, 10e3), (1e-3, 40e3)):
        config = setup.config({"grain.diameter": d, "sensor.resonance": f})
        grain, sensor, law, v = config.grain, config.sensor, config.law, config.velocity
        period = min(sensor.period, wall_contact_time(law, grain.mass, v))
        res = cl.simulate_impact(
            grain, sensor, law, v, sample_rate=setup.samples_per_period / period
        )
        grid = metrics.pulse_metrics(res.t, res.sensor_force)
        # 0.1 %: linear interpolation of the crossings and the sample nearest the peak
        assert grid.duration == pytest.approx(res.sensor_response_time, rel=1e-3)
        assert grid.peak == pytest.approx(res.peak_sensor_force, rel=1e-3)


def test_scatter_distributions_and_validation():
    seq = np.random.SeedSequence(3)
    uniform = Scatter(repetitions=2000, spread=0.5).factors(seq)
    assert uniform.min() >= 0.5 and uniform.max() <= 1.5
    # mean of 2000 uniform draws: standard error 0.5/sqrt(3*2000) = 0.0065; 4 of them
    assert uniform.mean() == pytest.approx(1.0, abs=0.026)
    normal = Scatter(repetitions=2000, spread=0.1, distribution="normal").factors(seq)
    assert normal.min() >= 0.7 and normal.max() <= 1.3  # truncated at 3 sigma
    assert normal.std() == pytest.approx(0.1, rel=0.1)  # sampling error ~2 %, truncation ~1 %
    for bad in (
        dict(spread=1.0),
        dict(spread=-0.1),
        dict(spread=0.4, distribution="normal"),
        dict(repetitions=0),
        dict(repetitions=True),
        dict(repetitions=2.0),
        dict(distribution="unifrom"),
    ):
        with pytest.raises(cl.ParameterError):
            Scatter(**bad)
    with pytest.raises(cl.ParameterError, match="Did you mean 'uniform'"):
        Scatter(distribution="unifrom")


def test_material_size_dependence(setup):
    material = replace(setup, size_dependence="material")
    small = material.config({"grain.diameter": 2e-3}).law
    large = material.config({"grain.diameter": 4e-3}).law
    # equivalent linear stiffness of a Hertz contact grows in proportion to the diameter
    assert large.stiffness / small.stiffness == pytest.approx(2.0, rel=1e-12)
    # and keeps the base law's damping ratio
    zeta = [
        law.damping / (2 * math.sqrt(law.stiffness * 765 * math.pi * d**3 / 6))
        for law, d in ((small, 2e-3), (large, 4e-3))
    ]
    assert zeta[0] == pytest.approx(zeta[1], rel=1e-12)
    hertz = replace(setup, law=Hertz(1e6), size_dependence="material")
    h2 = hertz.config({"grain.diameter": 2e-3}).law
    h8 = hertz.config({"grain.diameter": 8e-3}).law
    assert h8.k_hertz / h2.k_hertz == pytest.approx(2.0, rel=1e-12)  # kH ~ sqrt(R)
    with pytest.raises(cl.ParameterError, match="cannot be swept"):
        run_grid(material, {"law.stiffness": [1e5]})
    with pytest.raises(cl.ParameterError, match="material data"):
        replace(setup, grain=cl.Grain(diameter=5e-3, density=765.0), size_dependence="material")


def test_vary_is_checked_and_normalised(setup):
    assert replace(setup, vary=["stiffness", "damping"]).vary == ("stiffness", "damping")
    with pytest.raises(cl.ParameterError, match="vary must be a law parameter name"):
        replace(setup, vary=3)
    # an empty vary would leave the scatter's spread without effect
    with pytest.raises(cl.ParameterError, match=r"vary=\(\) names nothing"):
        replace(setup, vary=())
    assert replace(setup, vary=(), scatter=Scatter(repetitions=2, spread=0.0)).varied == ()


def test_output_grid_follows_the_shortest_draw(setup, monkeypatch):
    """Scattering a pulse length, the shortest contact is the smallest factor's draw."""
    from contactlab.study import points

    rates = []
    simulate = cl.config.ImpactConfig.simulate

    def recording(config, *, sample_rate, **kwargs):
        rates.append(sample_rate)
        return simulate(config, sample_rate=sample_rate, **kwargs)

    monkeypatch.setattr(cl.config.ImpactConfig, "simulate", recording)
    varied = replace(setup, law=PlasticTrapezoid(70e-6, 7e-6), vary="contact_time")
    # 20 kHz: a 50 us period, between the draws' contact times of 35 and 105 us
    points.simulate_point(varied, {"sensor.resonance": 20e3}, [0.5, 1.5])
    assert rates == [varied.samples_per_period / 35e-6] * 2


def test_the_plastic_pulse_needs_a_named_parameter(setup):
    pulse = PlasticTrapezoid(70e-6, 7e-6)
    with pytest.raises(cl.ParameterError, match="vary"):
        replace(setup, law=pulse)
    varied = replace(setup, law=pulse, vary="contact_time")
    res = run_grid(varied, {"sensor.resonance": [200e3]})
    assert res.impacts["contact_time [s]"].between(35e-6, 105e-6).all()


def test_point_statistics_of_a_hand_made_frame():
    frame = pd.DataFrame(
        {
            "p": [0, 0, 1, 1],
            "contact_time [s]": [1.0, 3.0, 2.0, 2.0],
            "time_error [%]": [3.0, -3.0, 1.0, 1.0],
            "force_error [%]": [4.0, 4.0, 0.0, 2.0],
        }
    )
    out = point_statistics(frame, ["p"])
    assert out["time_error [%]"].tolist() == [3.0, 0.0]
    assert out["time_error_mean [%]"].tolist() == [0.0, 1.0]
    assert out["force_error_rms [%]"].tolist() == [4.0, math.sqrt(2.0)]
    assert out["contact_time_mean [s]"].tolist() == [2.0, 2.0]
    with pytest.raises(cl.ParameterError, match=r"no column\(s\) \['point'\]"):
        point_statistics(frame, ["point"])
