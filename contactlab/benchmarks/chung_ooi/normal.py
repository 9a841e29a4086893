"""Normal impacts: tests 1 and 2 against Hertz, tests 3 and 9 against the requested restitution.

Two identical spheres (tests 1 and 9) are the equivalent sphere of
:mod:`contactlab.analytic.pair` on a rigid plane: mass ``m/2``, radius ``R/2``, the pair's
``E*``, at the relative speed (twice each sphere's).

DEM engines (``engines``: name -> ``impact(grain, law, speed)``, e.g. a drop test on a
rigid sensor, returning an object with ``contact_time``, ``peak_contact_force`` and
``restitution``) run the same law on a rigid plane and are graded beside contactlab. For
the pair tests they run that equivalent sphere too: what they check is their integration
of the law, not their own two-sphere contact geometry.
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


def _engine_impacts(engines, mass, radius, law, speed):
    """Each engine's impact of the (equivalent) sphere of ``mass`` [kg] and ``radius`` [m]."""
    body = cl.Grain.from_mass(mass, diameter=2.0 * radius)
    return {name: impact(body, law, speed) for name, impact in (engines or {}).items()}


def _graded(impacts, quantity):
    return {name: (getattr(res, quantity), True) for name, res in impacts.items()}


def _force_curve(result):
    """(t [s], contact force [N]) of an impact from the touch to the contact's end."""
    inside = (result.t >= 0.0) & (result.t <= result.contact_time)
    return result.t[inside], result.contact_force[inside]


def hertz_test(case, material, pair, engines=None):
    """Tests 1 (``pair``) and 2: contact time and peak force against Hertz.

    The curves: ``{"contactlab" or engine: (t [s], force [N]), "theory": (contact time
    [s], peak force [N])}``.
    """
    radius = case.inputs["radius [m]"]
    if pair:
        mass, k_hertz = _identical_pair(material, radius)
        speed = 2 * case.inputs["speed of each sphere [m/s]"]
        radius = analytic.effective_radius(radius, radius)
    else:
        mass = grain(material, radius).mass
        k_hertz = cl.laws.Hertz.from_material(grain(material, radius).material()).k_hertz
        speed = case.inputs["speed [m/s]"]
    law = cl.laws.Hertz(k_hertz)
    res = cl.simulate_impact(cl.Grain.from_mass(mass), cl.Sensor.rigid(), law, speed)
    impacts = _engine_impacts(engines, mass, radius, law, speed)
    contact_time = analytic.hertz_contact_time(k_hertz, mass, speed)
    peak = analytic.hertz_max_force(k_hertz, mass, speed)
    rows = [
        row(
            case,
            material,
            "contact time [s]",
            res.contact_time,
            contact_time,
            engines=_graded(impacts, "contact_time"),
        ),
        row(
            case,
            material,
            "peak force [N]",
            res.peak_contact_force,
            peak,
            engines=_graded(impacts, "peak_contact_force"),
        ),
    ]
    curves = {"contactlab": _force_curve(res), "theory": (contact_time, peak)}
    curves.update({name: _force_curve(got) for name, got in impacts.items()})
    return rows, curves


def restitution_test(case, material, pair, engines=None):
    """Tests 3 (sphere on a plane) and 9 (``pair``): realised against requested restitution.

    The curves: ``(requested, {"contactlab" or engine: realised at the last speed})``.
    """
    radius = case.inputs["radius [m]"]
    if pair:
        mass, k_hertz = _identical_pair(material, radius)
        speeds = [2 * v for v in case.inputs["speed of each sphere [m/s]"]]
        radius = analytic.effective_radius(radius, radius)
    else:
        body = grain(material, radius)
        mass = body.mass
        k_hertz = cl.laws.Hertz.from_material(body.material()).k_hertz
        speeds = [case.inputs["speed [m/s]"]]
    rows, realised = [], {name: [] for name in ["contactlab", *(engines or {})]}
    for e in case.inputs["restitution [-]"]:
        law = _normal_law(k_hertz, mass, e)
        for speed in speeds:
            got = cl.simulate_impact(cl.Grain.from_mass(mass), cl.Sensor.rigid(), law, speed)
            label = f" at {speed / 2:g} m/s each" if pair else ""
            impacts = _engine_impacts(engines, mass, radius, law, speed)
            rows.append(
                row(
                    case,
                    material,
                    f"restitution for e = {e:g}{label} [-]",
                    got.restitution,
                    e,
                    engines=_graded(impacts, "restitution"),
                )
            )
        realised["contactlab"].append(got.restitution)
        for name, impact in impacts.items():
            realised[name].append(impact.restitution)
    return rows, (case.inputs["restitution [-]"], realised)
