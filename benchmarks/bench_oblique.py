"""One oblique Hertz-Mindlin impact: contactlab against scipy's solve_ivp (issue 17 target).

Chung & Ooi's test 4 grain (aluminium oxide, R = 2.5 mm, 3.9 m/s) on a rigid flat, Hertz
normal and Mindlin tangential ("total" and "incremental"), at 5 deg (stick and slip
phases) and 45 deg (gross sliding); target median < 20 ms per impact with its headline
numbers and a 20 001-sample output grid.

The reference is scipy's ``solve_ivp`` (DOP853, the same rtol 1e-9 and atol) on the same
equations and the same phase logic: each stick or slide phase integrated until a
terminal event (the model's own event functions), then restarted in the next phase.
Both rebounds are printed. ``contactlab`` is timed twice: the full call (output grid and
peak forces included) and the contact integration alone (``_solve_contact``, the same
work as the reference).
Medians of repeated runs: the machine is shared.
"""

import math
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp

import contactlab as cl
from contactlab.solver.oblique import STICK, ObliqueModel, _solve_contact
from contactlab.solver.system import System

REPEATS = 21
GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
NORMAL = cl.laws.Hertz.from_material(*GRAIN.material())
SPEED, RTOL = 3.9, 1e-9


def median_time(fn):
    fn()
    times = []
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def ours(law, angle):
    res = cl.simulate_oblique(GRAIN, cl.Sensor.rigid(), NORMAL, law, SPEED, angle, rtol=RTOL)
    return res.tangential_velocity, res.angular_velocity, res.peak_tangential_force


def ours_contact_only(law, angle):
    """The contact integration alone: simulate_oblique without its output grid."""
    radius = GRAIN.radius
    model = ObliqueModel(
        System(GRAIN, cl.Sensor.rigid()), NORMAL, law, radius, 0.4 * GRAIN.mass * radius**2
    )
    y0 = np.array([0.0, 0.0, 0.0, SPEED * math.cos(angle), SPEED * math.sin(angle), 0.0, 0.0])
    return _solve_contact(model, y0, RTOL, (SPEED, GRAIN.mass * SPEED / 1e-6))[1][4:6]


def scipy_reference(law, angle):
    """The same phases with solve_ivp, phase by phase until the contact ends."""
    radius = GRAIN.radius
    model = ObliqueModel(
        System(GRAIN, cl.Sensor.rigid()), NORMAL, law, radius, 0.4 * GRAIN.mass * radius**2
    )
    length = SPEED * 1e-6
    history = length if law.history_kind == "displacement" else GRAIN.mass * SPEED / 1e-6
    atol = 1e-3 * RTOL * np.array([length, SPEED, length, SPEED, SPEED, SPEED / radius, history])
    y = np.array([0.0, 0.0, 0.0, SPEED * math.cos(angle), SPEED * math.sin(angle), 0.0, 0.0])
    phase = model.touch_phase(y, 1e-9, RTOL, atol)
    t = 0.0
    while True:
        rhs = model.rhs(phase)
        values, directions = model.events(phase)
        events = []
        for j, direction in enumerate(directions):

            def event(_t, z, j=j, values=values):
                return values(z)[j]

            event.terminal, event.direction = True, direction
            events.append(event)
        sol = solve_ivp(
            lambda _t, z, rhs=rhs: rhs(z),
            (t, t + 1e-3),
            y,
            method="DOP853",
            rtol=RTOL,
            atol=atol,
            events=events,
            dense_output=True,
            first_step=1e-10 if t == 0.0 else None,
        )
        hits = [(ts[0], j) for j, ts in enumerate(sol.t_events) if ts.size]
        t, j = min(hits)
        y = sol.sol(t)
        if j == 0:
            return y[4], y[5]
        if phase == STICK:
            phase = +1 if j == 1 else -1
        else:
            cap = phase * law.friction * max(model.normal(y[2] - y[0], y[3] - y[1]), 0.0)
            y[6] = law.history_on_cap(cap, y[2] - y[0], y[4] - radius * y[5])
            phase = STICK


def main():
    print(f"oblique Hertz-Mindlin impact, R = {GRAIN.radius * 1e3} mm, {SPEED} m/s, rtol {RTOL}")
    for history in ("total", "incremental"):
        law = cl.laws.Mindlin.from_material(3.8e11, 0.23, GRAIN.radius, 0.092, history=history)
        for degrees in (5.0, 45.0):
            angle = math.radians(degrees)
            a, b = ours(law, angle), scipy_reference(law, angle)
            t_ours = median_time(lambda law=law, angle=angle: ours(law, angle))
            t_core = median_time(lambda law=law, angle=angle: ours_contact_only(law, angle))
            t_ref = median_time(lambda law=law, angle=angle: scipy_reference(law, angle))
            print(
                f"{history:12s} {degrees:4.0f} deg: contactlab {t_ours * 1e3:6.2f} ms "
                f"(target < 20; contact alone {t_core * 1e3:5.2f} ms), solve_ivp "
                f"{t_ref * 1e3:6.2f} ms, ratio solve_ivp / contact alone {t_ref / t_core:4.2f};"
                f" vt' {a[0]:.9f} vs {b[0]:.9f} m/s, spin' {a[1]:.6f} vs {b[1]:.6f} rad/s"
            )


if __name__ == "__main__":
    main()
