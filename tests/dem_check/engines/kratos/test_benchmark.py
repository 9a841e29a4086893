"""`contactlab benchmark chung-ooi --engines lammps,kratos`: both engines graded on the normal
tests beside theory and contactlab, Kratos' test 4 reported."""

import math

import pytest

from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.cli import main
from contactlab.errors import ParameterError
from dem_check.engines.kratos import kratos_oblique

pytestmark = [pytest.mark.kratos, pytest.mark.lammps]

NORMAL_TESTS = {1, 2, 3, 9}


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The tests with engine columns; LAMMPS' tests 4-6 (``lammps=``) are test_oblique.py's,
    the contactlab-only tests 5-8 test_chung_ooi.py's."""
    from contactlab.cli import _benchmark_engines

    out = tmp_path_factory.mktemp("chung_ooi_engines")
    engines = _benchmark_engines(["lammps", "kratos"])
    return run_chung_ooi(out, engines=engines, tests=(1, 2, 3, 4, 9))


def test_every_row_passes_and_both_engines_grade_the_normal_tests(report):
    rows = report["rows"]
    assert all(r["passed"] for r in rows), [r for r in rows if not r["passed"]]
    normal = [r for r in rows if r["test"] in NORMAL_TESTS]
    assert len(normal) == 28  # 4 + 4 + 10 + 10 (test_chung_ooi.test_graded_numbers_per_test)
    for r in normal:
        for engine in ("lammps", "kratos"):
            # 1000 steps per contact, first order with damping: worst measured 8.6e-4 at
            # e = 0.2 (both engines), 5.1e-7 / 1.4e-6 for Hertz; the engines' 1e-3
            assert r[f"{engine}_error"] <= 1e-3, (engine, r)
        assert r["not_graded"] == ""


def test_kratos_test4_is_reported_not_graded(report):
    rows = [r for r in report["rows"] if r["test"] == 4]
    assert rows and all(r["kratos"] is not None and r["not_graded"] == "kratos" for r in rows)
    # gross sliding: vt' is the impulse closed form whatever the tangential rules
    # (measured 4e-12 for Kratos)
    assert max(r["kratos_error"] for r in rows) < 1e-9
    assert "(reported)" in report["markdown"]


def test_kratos_spin_in_gross_sliding_is_lower_by_its_lever_arm(report):
    """Kratos' torque arm R - d (not R): its final spin is lower by about the mean d/R."""
    import contactlab as cl
    from contactlab.benchmarks.chung_ooi.cases import CASES
    from contactlab.benchmarks.chung_ooi.grading import grain

    case = next(c for c in CASES if c.number == 4)
    body = grain(case.materials[0], case.inputs["radius [m]"])
    normal = cl.laws.Hertz.from_material(*body.material())
    law = cl.laws.Mindlin.from_material(*body.material(), case.inputs["friction [-]"])
    angle = math.radians(45.0)
    speed = case.inputs["speed [m/s]"]
    theirs = kratos_oblique(body, normal, law, speed, angle)
    ours = cl.simulate_oblique(body, cl.Sensor.rigid(), normal, law, speed, angle)
    ratio = theirs.angular_velocity / ours.angular_velocity
    # the issue measured 2.4e-3 to 3.9e-3 lower; here 2.0e-3 (45 deg): the force-weighted
    # mean of d/R over the contact, a few 1e-3 for aluminium oxide at 3.9 m/s
    assert 1e-3 < 1.0 - ratio < 5e-3
    assert theirs.tangential_velocity == pytest.approx(ours.tangential_velocity, rel=1e-9)


def test_only_the_tests_asked_for_run(report):
    assert {r["test"] for r in report["rows"]} == {1, 2, 3, 4, 9}
    with pytest.raises(ParameterError, match="tests"):
        run_chung_ooi(tests=[10])


def test_an_unknown_engine_is_refused(capsys):
    from contactlab.cli import _benchmark_engines

    assert main(["benchmark", "chung-ooi", "--engines", "kratoss", "--out", "."]) == 2
    assert "--engines" in capsys.readouterr().err
    with pytest.raises(ParameterError, match="--engines"):  # an engine, not a DEM code
        _benchmark_engines(["bullet"])
