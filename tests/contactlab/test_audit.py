"""The audit's pieces (ledger, checks, warning) and that an audit catches a broken solver."""

import json
import math
import warnings

import pytest

import contactlab as cl
from contactlab.audit import (
    Audit,
    Check,
    EnergyLedger,
    elastic_energy,
    energy_check,
    warn_if_broken,
)
from contactlab.errors import AuditWarning

GRAIN = cl.Grain(diameter=4e-3, density=1300.0, youngs_modulus=0.35e9, poisson_ratio=0.3)
"""Issue 21's grain."""

K_HERTZ = 4.0 / 3.0 * 0.35e9 / (1.0 - 0.3**2) * math.sqrt(GRAIN.radius)


def test_the_ledger_closes_on_its_residual():
    ledger = EnergyLedger(
        kinetic_in=10.0,
        translation_out=4.0,
        rotation_out=1.0,
        sensor_left=0.5,
        sensor_damper=0.5,
        normal_damper=2.0,
        normal_elastic_left=0.25,
        friction=1.5,
    )
    assert ledger.residual == pytest.approx(0.25)  # 10 - 9.75, exactly representable
    assert ledger.kinetic_out == pytest.approx(5.5)
    assert set(ledger.as_dict()) >= {"kinetic_in [J]", "friction [J]", "residual [J]"}


def test_a_check_fails_only_beyond_tolerance_and_unless_the_model_allows_it():
    assert Check("energy", 1e-9, 1e-8, "impact energy").passed
    broken = Check("energy", 1e-3, 1e-8, "impact energy", 2e-6)
    assert broken.failed and "2e-06 s" in broken.describe()
    allowed = Check("energy", 1e-3, 1e-8, "impact energy", math.nan, "the model's")
    assert not allowed.passed and not allowed.failed
    audit = Audit(None, (broken, allowed))
    assert audit.failures == [broken] and not audit.ok
    json.dumps(audit.as_dict())  # JSON-ready
    with pytest.raises(KeyError, match="no check 'coulomb'"):
        audit["coulomb"]


def test_warn_if_broken_names_every_failed_check():
    audit = Audit(None, (Check("coulomb", 0.5, 1e-9, "peak normal force", 1e-5),))
    with pytest.warns(AuditWarning, match=r"coulomb: 0\.5 of the peak normal force"):
        warn_if_broken(audit, "this result")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warn_if_broken(Audit(None, ()), "a clean result")  # nothing to say


def test_elastic_energy_is_the_closed_form():
    """``integral k x**1.5 dx = 0.4 k d**2.5`` and ``k d**2 / 2``, rate terms excluded."""
    d = 3e-5
    kk = cl.laws.KuwabaraKono(K_HERTZ, 2e-6)
    # 64-node Gauss-Legendre on graded panels: x**1.5 to ~1e-12
    assert elastic_energy(kk, d) == pytest.approx(0.4 * K_HERTZ * d**2.5, rel=1e-10)
    linear = cl.laws.LinearViscoelastic(1e5, 3.0)
    assert elastic_energy(linear, d) == pytest.approx(0.5e5 * d**2, rel=1e-13)
    assert elastic_energy(linear, -d) == 0.0
    assert elastic_energy(cl.laws.WaltonBraun(1e5, 3e5), d) == 0.0  # ends at zero force


def test_the_audit_catches_a_solver_that_breaks_coulomb(monkeypatch):
    """A solver whose events let the tangential force past ``mu N`` (issue 21's defect let a
    phase that started at zero never arm its Coulomb events; since issue 25 those events are
    compiled, so the defect is put back as a kernel that caps at ten times the law's
    friction): the default cheap audit warns about Coulomb, the full audit names it."""
    from contactlab.kernels.oblique_rhs import FRICTION
    from contactlab.solver.oblique import ObliqueModel

    packed = ObliqueModel.pack

    def broken(model):
        par = packed(model)
        par[FRICTION] *= 10.0
        return par

    monkeypatch.setattr(ObliqueModel, "pack", broken)
    normal, spring = cl.laws.KuwabaraKono(K_HERTZ, 2e-6), cl.laws.TangentialSpring(2e5, 0.3)
    with pytest.warns(AuditWarning, match="coulomb"):
        res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), normal, spring, 3.0, math.radians(85))
    check = res.audit()["coulomb"]
    assert check.failed and check.worst > 1.0  # |T| above mu N by more than max N


def test_a_coarse_euler_step_warns():
    """Issue 21: ``method="euler"`` at 1e-6 s created energy silently (restitution 1.11 on
    elastic Hertz); at the paper's step it is clean."""
    hertz = cl.laws.Hertz.from_material(GRAIN.material())
    with pytest.warns(AuditWarning, match=r"energy: 0\.2\d* of the impact energy"):
        res = cl.simulate_impact(
            GRAIN, cl.Sensor.rigid(), hertz, 3.0, method="euler", time_step=1e-6
        )
    assert res.restitution > 1.1
    damped = cl.laws.KuwabaraKono(K_HERTZ, 2e-6)  # loses energy, but the wrong amount
    with pytest.warns(AuditWarning, match="euler_step"):
        cl.simulate_impact(GRAIN, cl.Sensor.rigid(), damped, 3.0, method="euler", time_step=1e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("error", AuditWarning)
        res = cl.simulate_impact(
            GRAIN, cl.Sensor.rigid(), hertz, 3.0, method="euler", time_step=1e-9
        )
    assert res.audit()["energy"].worst < 1e-3


def test_impact_audit_ledger_against_closed_forms():
    """Linear damped contact on a wall: the ledger's damper work is the energy the
    restitution says is lost, and an elastic contact leaves nothing behind."""
    law = cl.laws.LinearViscoelastic(1e5, 0.5)
    res = cl.simulate_impact(GRAIN, cl.Sensor.rigid(), law, 2.0)
    audit = res.audit()
    assert audit.ok
    lost = (
        0.5
        * GRAIN.mass
        * 4.0
        * (1.0 - cl.analytic.linear_restitution(1e5, 0.5, GRAIN.mass, "force") ** 2)
    )
    # exact modal solution and Gauss-Legendre: 1e-9 covers both
    assert audit.ledger.normal_damper + audit.ledger.normal_elastic_left == pytest.approx(
        lost, rel=1e-9
    )
    elastic = cl.simulate_impact(GRAIN, cl.Sensor.rigid(), cl.laws.Hertz(K_HERTZ), 2.0).audit()
    assert elastic.ledger.normal_elastic_left == 0.0
    assert abs(elastic.ledger.normal_damper) < 1e-7 * elastic.ledger.kinetic_in  # quadrature


def test_a_pulse_with_a_vanishing_ramp_is_the_rectangle():
    """Found by the audit matrix: a prescribed trapezoid with a ramp of 1e-224 s overflowed in
    the sensor's particular solution (slope 1e224 N/s; signal 1e201 N), at 1e-20 s it lost
    digits (residual 8e-6). Such a ramp is now a step of the same impulse: the result is the
    rectangle's, and it audits clean (the energy check, which no model property excuses
    when it is not finite, would have said otherwise)."""
    grain = cl.Grain(diameter=2.243e-3, density=530.0)
    sensor = cl.Sensor.from_resonance(82.91e3, mass=1.089e-4, damping_ratio=0.0217)
    steep = cl.simulate_impact(
        grain, sensor, cl.laws.PlasticTrapezoid(2.58889e-4, 1.48354e-224), 5.45
    )
    rectangle = cl.simulate_impact(grain, sensor, cl.laws.PlasticTrapezoid(2.58889e-4, 0.0), 5.45)
    assert steep.audit().ok
    # the same exact pieces up to the ramp's 1e-224 s: rounding only
    assert steep.peak_sensor_force == pytest.approx(rectangle.peak_sensor_force, rel=1e-12)
    overflow = Audit(None, (energy_check(EnergyLedger(1.0, math.inf), 1e-9, "a model's"),))
    assert overflow["energy"].failed  # an infinite energy is never the model's
