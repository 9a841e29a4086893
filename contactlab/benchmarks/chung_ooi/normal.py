"""Normal impacts: tests 1 and 2 against Hertz, tests 3 and 9 against the requested restitution.

Two identical spheres (tests 1 and 9) are the equivalent sphere of
:mod:`contactlab.analytic.pair` on a rigid plane: mass ``m/2``, radius ``R/2``, the pair's
``E*``, at the relative speed (twice each sphere's).
"""

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi.grading import grain, row

__all__ = ["hertz_test", "restitution_test"]


def _identical_pair(material, radius):
    """``(m*, kH)`` of two identical spheres of ``material`` and ``radius`` [m]."""
    mass = analytic.effective_mass(grain(material, radius).mass, grain(material, radius).mass)
    e, nu = material.youngs_modulus, material.poisson_ratio
    modulus = analytic.effective_modulus(e, nu, e, nu)
    return mass, analytic.hertz_stiffness(modulus, analytic.effective_radius(radius, radius))


def _normal_law(k_hertz, mass, restitution):
    """Elastic Hertz for e = 1, else Tsuji's damped Hertz realising ``e`` (force-zero end)."""
    if restitution == 1.0:
        return cl.laws.Hertz(k_hertz)
    damping = analytic.tsuji_damping_coefficient(k_hertz, mass, restitution, "force")
    return cl.laws.HertzDamped(k_hertz, damping)


def hertz_test(case, material, pair):
    """Tests 1 (``pair``) and 2: contact time and peak force against Hertz."""
    radius = case.inputs["radius [m]"]
    if pair:
        mass, k_hertz = _identical_pair(material, radius)
        speed = 2 * case.inputs["speed of each sphere [m/s]"]
    else:
        mass = grain(material, radius).mass
        k_hertz = cl.laws.Hertz.from_material(*grain(material, radius).material()).k_hertz
        speed = case.inputs["speed [m/s]"]
    res = cl.simulate_impact(
        cl.Grain.from_mass(mass), cl.Sensor.rigid(), cl.laws.Hertz(k_hertz), speed
    )
    rows = [
        row(
            case,
            material,
            "contact time [s]",
            res.contact_time,
            analytic.hertz_contact_time(k_hertz, mass, speed),
        ),
        row(
            case,
            material,
            "peak force [N]",
            res.peak_contact_force,
            analytic.hertz_max_force(k_hertz, mass, speed),
        ),
    ]
    inside = res.t <= res.contact_time
    return rows, (res.t[inside], res.contact_force[inside])


def restitution_test(case, material, pair):
    """Tests 3 (sphere on a plane) and 9 (``pair``): realised against requested restitution."""
    radius = case.inputs["radius [m]"]
    if pair:
        mass, k_hertz = _identical_pair(material, radius)
        speeds = [2 * v for v in case.inputs["speed of each sphere [m/s]"]]
    else:
        body = grain(material, radius)
        mass = body.mass
        k_hertz = cl.laws.Hertz.from_material(*body.material()).k_hertz
        speeds = [case.inputs["speed [m/s]"]]
    rows, realised = [], []
    for e in case.inputs["restitution [-]"]:
        law = _normal_law(k_hertz, mass, e)
        for speed in speeds:
            got = cl.simulate_impact(cl.Grain.from_mass(mass), cl.Sensor.rigid(), law, speed)
            label = f" at {speed / 2:g} m/s each" if pair else ""
            rows.append(
                row(case, material, f"restitution for e = {e:g}{label} [-]", got.restitution, e)
            )
        realised.append(got.restitution)
    return rows, (case.inputs["restitution [-]"], realised)
