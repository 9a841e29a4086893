"""The rule-by-rule attribution's plumbing (``contactlab.benchmarks.chung_ooi.attribution``)
without an engine: which variants it runs, that the preset's own rebound is found exactly,
and that a combination this toolkit refuses is reported, not dropped. Against the engines
themselves: ``tests/dem_check/engines/kratos/test_benchmark.py``."""

import math

import numpy as np

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi.attribution import BASE, RULES, attribute, markdown, variants
from contactlab.solver.conventions import DEM_CONVENTIONS, Conventions

GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
MU, SPEED, ANGLES = 0.092, 3.9, (5, 20, 45)
ELASTIC = cl.laws.Hertz.from_material(GRAIN.material())
MINDLIN = cl.laws.Mindlin.from_material(GRAIN.material(), MU)
KRATOS = DEM_CONVENTIONS["kratos"]


def test_variants_switch_each_differing_rule_alone_both_ways():
    found = variants(KRATOS, engine="kratos")
    assert RULES == ("lever_arm", "history", "damping", "coulomb_cap")
    # the default, 4 rules alone, all but each of 4, the preset
    assert len(found) == 10 and next(iter(found)) == BASE and list(found)[-1] == "kratos rules"
    assert found["only lever_arm = contact"] == Conventions("contact", "total", "none")
    assert (
        found["all but history"].history == "total" and found["all but history"].damping == "tied"
    )
    # one differing rule: no "all but" (it would be the default); none: the preset alone
    assert list(variants(DEM_CONVENTIONS["lammps_mindlin_force"], engine="x")) == [
        BASE,
        "only history = incremental",
        "x rules",
    ]
    assert list(variants(DEM_CONVENTIONS["lammps_mindlin"], engine="x")) == ["x rules"]


def _rebounds(normal, rules):
    law = rules.mindlin(MINDLIN)
    out = []
    for degrees in ANGLES:
        res = cl.simulate_oblique(
            GRAIN,
            cl.Sensor.rigid(),
            normal,
            law,
            SPEED,
            math.radians(degrees),
            lever_arm=rules.lever_arm,
        )
        out.append((res.rebound_normal_velocity, res.tangential_velocity, res.angular_velocity))
    return out


def test_an_engine_running_a_preset_is_found_exactly_and_the_default_is_not():
    found = attribute(
        GRAIN,
        "alumina",
        ELASTIC,
        MINDLIN,
        SPEED,
        ANGLES,
        "fake",
        _rebounds(ELASTIC, KRATOS),
        KRATOS,
    )
    # the same deterministic runs: equal to the last bit
    assert found.worst("fake rules") == (0.0, 0.0)
    # the rules' effect at 5 deg: 9.2e-2 of vt (docs/dem-conventions.md)
    assert found.worst(BASE)[0] > 5e-2
    # gross sliding (45 deg): vt' is the closed form under every rule
    assert np.allclose(
        found.differences("only history = incremental_rescaled")[2, 0], 0.0, atol=1e-9
    )
    assert not found.refused and "| fake | alumina | fake rules | 0.0e+00 |" in markdown([found])


def test_a_refused_combination_is_reported_with_its_reason():
    damped = cl.laws.HertzDamped(
        ELASTIC.k_hertz,
        analytic.tsuji_damping_coefficient(ELASTIC.k_hertz, GRAIN.mass, 0.98, "force"),
    )
    found = attribute(
        GRAIN,
        "alumina",
        damped,
        MINDLIN,
        SPEED,
        ANGLES[:1],
        "fake",
        _rebounds(damped, KRATOS)[:1],
        KRATOS,
    )
    # history total with the tied damping beside a damped normal law: refused (its reason)
    assert set(found.refused) == {"only damping = tied", "all but history"}
    assert all("not supported" in reason for reason in found.refused.values())
    assert np.isnan(found.values["all but history"]).all()
    assert "not run" in markdown([found])
    rows = found.table()
    assert len(rows) == len(found.values) and {"coulomb_cap", "angle [deg]"} <= set(rows[0])
