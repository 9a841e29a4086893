"""Run the Chung & Ooi tests: this toolkit against theory, one figure per test, one table.

Pass/fail tolerances (relative, on the compared quantity):

* tests 1-2: contact time and peak force against Hertz's closed forms, 1e-6 (the solver
  runs at rtol 1e-10; Hertz is exact for an elastic sphere);
* test 3: realised restitution against the requested one, 1e-6 (the damping is mapped
  with the force-zero convention this toolkit's contact ends with, which is exact);
* tests 4 and 6: rebound in gross sliding against the impulse closed form, 1e-6 (exact
  for any Coulomb-capped tangential law); below the sliding limit no closed form exists
  (Maw et al. 1976 solved it numerically), and the curves are shown, not graded.

LAMMPS' column stays empty until the LAMMPS oblique runner is available (issue 13).
"""

import math
from pathlib import Path

import numpy as np

import contactlab as cl
from contactlab import analytic
from contactlab.benchmarks.chung_ooi.cases import CASES

__all__ = ["ANGLES", "run_chung_ooi"]

ANGLES = tuple(range(5, 90, 5))
"""Incidence angles of tests 4 and 6 [deg] (5-85, as Chung & Ooi)."""

_TOLERANCE = 1e-6


def _grain(material, radius):
    return cl.Grain(
        diameter=2 * radius,
        density=material.density,
        youngs_modulus=material.youngs_modulus,
        poisson_ratio=material.poisson_ratio,
    )


def _row(case, material, quantity, ours, theory, tolerance=_TOLERANCE):
    error = abs(ours - theory) / abs(theory)
    return {
        "test": case.number,
        "material": material.name,
        "quantity": quantity,
        "contactlab": ours,
        "theory": theory,
        "lammps": None,
        "relative_error": error,
        "tolerance": tolerance,
        "passed": bool(error <= tolerance),
    }


def _hertz_test(case, material, pair):
    """Tests 1 and 2: two identical spheres reduce to m/2, R/2 at twice the speed."""
    radius = case.inputs["radius [m]"]
    grain = _grain(material, radius)
    e, nu = material.youngs_modulus, material.poisson_ratio
    if pair:
        mass, r_eff = grain.mass / 2, radius / 2
        modulus = analytic.effective_modulus(e, nu, e, nu)
        speed = 2 * case.inputs["speed of each sphere [m/s]"]
    else:
        mass, r_eff = grain.mass, radius
        modulus = analytic.effective_modulus(e, nu)
        speed = case.inputs["speed [m/s]"]
    k_hertz = analytic.hertz_stiffness(modulus, r_eff)
    res = cl.simulate_impact(
        cl.Grain.from_mass(mass), cl.Sensor.rigid(), cl.laws.Hertz(k_hertz), speed
    )
    rows = [
        _row(
            case,
            material,
            "contact time [s]",
            res.contact_time,
            analytic.hertz_contact_time(k_hertz, mass, speed),
        ),
        _row(
            case,
            material,
            "peak force [N]",
            res.peak_contact_force,
            analytic.hertz_max_force(k_hertz, mass, speed),
        ),
    ]
    curve = (res.t[res.t <= res.contact_time], res.contact_force[res.t <= res.contact_time])
    return rows, curve


def _restitution_test(case, material):
    radius, speed = case.inputs["radius [m]"], case.inputs["speed [m/s]"]
    grain = _grain(material, radius)
    k_hertz = cl.laws.Hertz.from_material(*grain.material()).k_hertz
    rows, realised = [], []
    for e in case.inputs["restitution [-]"]:
        if e == 1.0:
            law = cl.laws.Hertz(k_hertz)
        else:
            damping = analytic.tsuji_damping_coefficient(k_hertz, grain.mass, e, "force")
            law = cl.laws.HertzDamped(k_hertz, damping)
        got = cl.simulate_impact(grain, cl.Sensor.rigid(), law, speed).restitution
        realised.append(got)
        rows.append(_row(case, material, f"restitution for e = {e:g} [-]", got, e))
    return rows, (case.inputs["restitution [-]"], realised)


def _oblique_test(case, material):
    """Test 4: both Mindlin history forms over the incidence angles."""
    radius, speed, mu = (case.inputs[k] for k in ("radius [m]", "speed [m/s]", "friction [-]"))
    grain = _grain(material, radius)
    normal = cl.laws.Hertz.from_material(*grain.material())
    rows, curves = [], {}
    for history in ("total", "incremental"):
        law = cl.laws.Mindlin.from_material(*grain.material(), mu, history=history)
        out = []
        for degrees in ANGLES:
            res = cl.simulate_oblique(
                grain, cl.Sensor.rigid(), normal, law, speed, math.radians(degrees)
            )
            vn, vt = res.normal_velocity, res.incident_tangential_velocity
            out.append(
                (
                    res.tangential_velocity / vt,
                    res.angular_velocity,
                    math.degrees(res.contact_rebound_angle),
                )
            )
            e = min(res.restitution, 1.0)  # elastic: 1 to ~1e-9
            if analytic.slides_throughout(vn, vt, 0.0, radius, e, mu):
                theory = analytic.gross_sliding_rebound(vn, vt, 0.0, radius, e, mu)
                rows.append(
                    _row(
                        case,
                        material,
                        f"vt' at {degrees} deg, {history} [m/s]",
                        res.tangential_velocity,
                        theory[0],
                    )
                )
        curves[history] = np.array(out)
    return rows, curves


def _spin_test(case, material):
    """Test 6: a spinning sphere dropped on the plane (no centre tangential velocity)."""
    radius, vn, mu, e = (
        case.inputs[k] for k in ("radius [m]", "normal speed [m/s]", "friction [-]", "restitution")
    )
    grain = _grain(material, radius)
    k_hertz = cl.laws.Hertz.from_material(*grain.material()).k_hertz
    normal = cl.laws.HertzDamped(
        k_hertz, analytic.tsuji_damping_coefficient(k_hertz, grain.mass, e, "force")
    )
    law = cl.laws.Mindlin.from_material(*grain.material(), mu)
    rows, out = [], []
    for degrees in ANGLES:
        slip = vn * math.tan(math.radians(degrees))
        res = cl.simulate_oblique(
            grain, cl.Sensor.rigid(), normal, law, vn, 0.0, spin=-slip / radius
        )
        beta = -res.slip_after / slip
        out.append((3.5 * mu * (1 + e) * vn / slip, beta))
        if analytic.slides_throughout(vn, 0.0, -slip / radius, radius, res.restitution, mu):
            theory = 3.5 * mu * (1 + res.restitution) * vn / slip - 1.0
            rows.append(_row(case, material, f"beta at tan = {slip / vn:.3g} [-]", beta, theory))
    return rows, np.array(out)


def _figure(case, draw, out):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.0, 4.0), layout="constrained")
    draw(ax)
    ax.set_title(f"Chung & Ooi test {case.number}: {case.title}", fontsize=9)
    ax.legend(frameon=False, fontsize=8)
    path = Path(out) / f"chung_ooi_test{case.number}.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _draw_hertz(curves):
    def draw(ax):
        for name, (t, f) in curves.items():
            ax.plot(t * 1e6, f, label=f"{name}: contactlab")
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("contact force [N]")

    return draw


def _draw_restitution(curves):
    def draw(ax):
        for name, (asked, got) in curves.items():
            ax.plot(asked, got, "o-", label=f"{name}: contactlab")
        ax.plot([0, 1], [0, 1], "k:", label="requested")
        ax.set_xlabel("requested restitution [-]")
        ax.set_ylabel("realised restitution [-]")

    return draw


def _draw_oblique(curves, case):
    mu, speed = case.inputs["friction [-]"], case.inputs["speed [m/s]"]

    def draw(ax):
        angles = np.radians(ANGLES)
        for name, forms in curves.items():
            for history, data in forms.items():
                ax.plot(
                    ANGLES,
                    data[:, 0],
                    "o-" if history == "total" else "x--",
                    label=f"{name}, Mindlin {history}",
                )
        sliding = 1 - mu * 2 * speed * np.cos(angles) / (speed * np.sin(angles))
        ok = np.abs(speed * np.sin(angles)) >= 3.5 * mu * 2 * speed * np.cos(angles)
        ax.plot(np.array(ANGLES)[ok], sliding[ok], "k-", lw=2, label="gross sliding (theory)")
        ax.set_xlabel("incidence angle [deg]")
        ax.set_ylabel("tangential restitution vt'/vt [-]")

    return draw


def _draw_spin(curves):
    def draw(ax):
        for name, data in curves.items():
            ax.plot(data[:, 0], data[:, 1], "o-", label=f"{name}: contactlab")
            x = np.linspace(0.0, 1.0, 50)
            ax.plot(x, x - 1.0, "k-", lw=2, label="gross sliding (theory)")
        ax.set_xlabel("3.5 mu (1 + e) vn / slip [-]")
        ax.set_ylabel("beta = -slip'/slip [-]")

    return draw


def run_chung_ooi(out=None):
    """Run the tests; write one figure per test and ``chung_ooi.csv`` into ``out``.

    Parameters
    ----------
    out : str or path-like, optional
        Output folder (created); no files are written when None.

    Returns
    -------
    dict
        ``rows`` (one per graded number: test, material, quantity, contactlab, theory,
        lammps, relative_error, tolerance, passed), ``not_run`` ({test: reason}),
        ``figures`` (paths) and ``markdown`` (the table).
    """
    rows, not_run, figures = [], {}, []
    if out is not None:
        Path(out).mkdir(parents=True, exist_ok=True)
    for case in CASES:
        if case.not_run:
            not_run[case.number] = case.not_run
            continue
        curves, draw = {}, None
        for material in case.materials:
            if case.number in (1, 2):
                got, curves[material.name] = _hertz_test(case, material, case.number == 1)
            elif case.number == 3:
                got, curves[material.name] = _restitution_test(case, material)
            elif case.number == 4:
                got, curves[material.name] = _oblique_test(case, material)
            else:
                got, curves[material.name] = _spin_test(case, material)
            rows.extend(got)
        draw = {
            1: _draw_hertz,
            2: _draw_hertz,
            3: _draw_restitution,
            6: _draw_spin,
        }.get(case.number)
        draw = _draw_oblique(curves, case) if case.number == 4 else draw(curves)
        if out is not None:
            figures.append(_figure(case, draw, out))
    table = _markdown(rows, not_run)
    if out is not None:
        import pandas as pd

        pd.DataFrame(rows).to_csv(Path(out) / "chung_ooi.csv", index=False)
    return {"rows": rows, "not_run": not_run, "figures": figures, "markdown": table}


def _markdown(rows, not_run):
    lines = [
        "| test | material | quantity | contactlab | theory | LAMMPS | rel. error | tol. | pass |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['test']} | {r['material']} | {r['quantity']} | {r['contactlab']:.8g} | "
            f"{r['theory']:.8g} | not run | {r['relative_error']:.1e} | {r['tolerance']:.0e} | "
            f"{'pass' if r['passed'] else 'FAIL'} |"
        )
    for number, reason in not_run.items():
        lines.append(f"| {number} | - | not run: {reason} | | | | | | |")
    return "\n".join(lines)
