"""Benchmark: the reconstructed peak and contact time on forces the project did not model.

An independent check of :func:`contactlab.inverse.reconstruct_force` (issue 22): the
force is a closed-form half-sine, or a Hertz impact integrated by scipy's ``solve_ivp``
(``m x'' = -K x**1.5``, not contactlab's solver), passed through the 40 kHz disc sensor
(damping ratio 0.02) by scipy's ``lsim`` on a grid ten times finer, sampled at 1 or
2 MHz with white or AR(1) (coefficient 0.9) noise of 2 % or 5 % of the peak (peak over
noise 50 and 20), 8 noise seeds each. Both contact-edge rules are run on the same
signals: ``significance`` (the default: the contact where the force is significantly
above zero, its edges extrapolated along the flanks) and ``level`` (2 % of the peak and
the dip rule, as before); on the Hertz force also the significance rule with Hertz's
power law at the flanks (``flank_exponent=1.5``); on a linear spring-dashpot's force
(closed form, damping ratio 0.177: it jumps to 42 % of its peak at the touch) the
significance rule with a line on each flank and with the contact family
(``contact_family=("linear", 0.177)``: the start at half the jump); on each force also
the peak and contact time of its family fitted to the signal (``family fit``: the
undamped linear family for the half-sine, undamped Hertz, the spring-dashpot's).
Printed: the
largest and mean relative errors against the closed-form (half-sine, spring-dashpot) or
integrated (Hertz) peak and contact time, and their mean (bias).

Run: ``.venv/bin/python benchmarks/bench_contact_time.py [--seeds 8] [--shape NAME]``
"""

import argparse
import os

import numpy as np
import pandas as pd
import scipy.signal as sg
from scipy.integrate import solve_ivp

import contactlab as cl
from contactlab.inverse import reconstruct_force

SENSOR = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
PEAK, CONTACT = 3.0, 100e-6  # [N], [s]


def half_sine(t):
    """``PEAK sin(pi t / CONTACT)`` on the contact, zero outside; its peak and duration."""
    inside = (t >= 0.0) & (t <= CONTACT)
    return np.where(inside, PEAK * np.sin(np.pi * np.clip(t, 0, CONTACT) / CONTACT), 0.0), (
        PEAK,
        CONTACT,
    )


def hertz(t):
    """A Hertz impact ``m x'' = -K x**1.5`` of about PEAK and CONTACT (``solve_ivp``, rtol
    1e-10), interpolated on ``t``; its integrated peak and duration."""
    # the largest compression x_m = T v / 2.9432 (Johnson 1985, 11.4) sets K from the
    # peak K x_m**1.5 and m from x_m**2.5 = 5 m v**2 / (4 K); the integration gives the truth
    v = 1.0
    x_m = CONTACT * v / 2.9432
    k = PEAK / x_m**1.5
    m = 4.0 * k * x_m**2.5 / (5.0 * v**2)

    def rhs(_, state):
        x, u = state
        return [u, -k * max(x, 0.0) ** 1.5 / m]

    def leave(_, state):
        return state[0]

    leave.terminal, leave.direction = True, -1
    fine = np.linspace(0.0, 3.0 * CONTACT, 30001)
    sol = solve_ivp(
        rhs, (0.0, fine[-1]), [1e-30, v], t_eval=fine, events=leave, rtol=1e-10, atol=1e-16
    )
    duration = float(sol.t_events[0][0])
    force = k * np.maximum(sol.y[0], 0.0) ** 1.5
    return np.interp(t, sol.t, force, left=0.0, right=0.0), (float(force.max()), duration)


DAMPING = 0.177
"""Damping ratio of :func:`damped_linear` [-] (the hard test grain's, k2 = 4e4 N/m,
c2 = 0.5 N*s/m, 50 mg: its force jumps to 42 % of its peak at the touch)."""


def damped_linear(t):
    """A linear spring-dashpot impact on a rigid wall in closed form, ``x = v / wd
    exp(-zeta w0 t) sin(wd t)``, ``F / m = w0**2 x + 2 zeta w0 x'`` until the force
    returns to zero, scaled to PEAK and CONTACT; its peak and duration."""
    zeta, w0 = DAMPING, 1.0
    wd = w0 * np.sqrt(1.0 - zeta**2)

    def unit(s):  # force over m v of the unit oscillator (w0 = 1)
        decay = np.exp(-zeta * w0 * s)
        x = decay * np.sin(wd * s) / wd
        v = decay * (np.cos(wd * s) - zeta * w0 * np.sin(wd * s) / wd)
        return w0**2 * x + 2.0 * zeta * w0 * v

    # the grain leaves where the force returns to zero (closed form:
    # tan(wd s) = -2 zeta sqrt(1 - zeta**2) / (1 - 2 zeta**2), in (pi / 2, pi))
    leave = (np.pi + np.arctan(-2.0 * zeta * np.sqrt(1.0 - zeta**2) / (1.0 - 2.0 * zeta**2))) / wd
    fine = np.linspace(0.0, leave, 200001)
    top = float(unit(fine).max())
    s = np.clip(t, 0.0, None) * leave / CONTACT
    force = np.where((t >= 0.0) & (s <= leave), PEAK * unit(s) / top, 0.0)
    return force, (PEAK, CONTACT)


RULES = {
    "half_sine": [("significance", 1.0), ("level", 1.0), ("family fit", ("linear", 0.0))],
    "hertz": [
        ("significance", 1.0),
        ("significance", 1.5),
        ("level", 1.0),
        ("family fit", ("hertz", 0.0)),
    ],
    "damped_linear": [
        ("significance", 1.0),
        ("significance", ("linear", DAMPING)),
        ("family fit", ("linear", DAMPING)),
    ],
}
"""Contact-edge rules and flank exponents (or a contact family, ``(name, damping)``) run
on each shape: ``significance`` and ``level`` read the regularised force (its largest
value, its edges; ``read_family=False``), ``family fit`` reads the family fitted to the
signal (:mod:`contactlab.inverse.reconstruct_family`; the half-sine is the undamped
linear family's force)."""


def signal(shape, rate):
    """Time [s], sensor signal [N] (``lsim`` on a ten times finer grid) and the truth."""
    t = np.arange(-1e-3, 2e-3, 1.0 / rate)
    fine = np.linspace(t[0], t[-1], 10 * (t.size - 1) + 1)
    force, truth = shape(fine)
    w, zeta = SENSOR.angular_frequency, SENSOR.damping_ratio
    system = sg.lti([2.0 * zeta * w, w**2], [1.0, 2.0 * zeta * w, w**2])
    _, response, _ = sg.lsim(system, force, fine - fine[0])
    return t, response[::10], truth


def noise(kind, size, seed):
    """Unit-standard-deviation white or AR(1) (coefficient 0.9) noise."""
    w = np.random.default_rng(seed).normal(size=size + 2000)
    x = w if kind == "white" else sg.lfilter([1.0], [1.0, -0.9], w)
    x = x[2000:]
    return x / x.std()


SHAPES = {f.__name__: f for f in (half_sine, hertz, damped_linear)}
"""The forces run, by name (``--shape``)."""


def run(seeds, shapes=tuple(SHAPES)):
    rows = []
    for shape in (SHAPES[name] for name in shapes):
        for rate in (1e6, 2e6):
            t, clean, (peak, duration) = signal(shape, rate)
            for kind in ("white", "ar1"):
                for level in (0.02, 0.05):
                    for seed in range(seeds):
                        y = clean + level * peak * noise(kind, t.size, seed)
                        for rule, flanks in RULES[shape.__name__]:
                            family = flanks if isinstance(flanks, tuple) else None
                            m = reconstruct_force(
                                t,
                                y,
                                SENSOR,
                                contact_edges="significance" if rule == "family fit" else rule,
                                flank_exponent=1.0 if family else flanks,
                                contact_family=family,
                                read_family=rule == "family fit",
                            ).metrics
                            rows.append(
                                {
                                    "case": f"{shape.__name__} {rate / 1e6:g} MHz {kind} "
                                    f"{level:.0%}",
                                    "rule": f"{rule}, "
                                    + (f"family {family}" if family else f"p = {flanks:g}"),
                                    "peak": m.peak / peak - 1.0,
                                    "contact_time": m.duration / duration - 1.0,
                                }
                            )
    table = pd.DataFrame(rows)
    grouped = table.groupby(["case", "rule"], sort=False)[["peak", "contact_time"]]
    summary = pd.concat(
        {
            "largest": grouped.agg(lambda v: np.abs(v).max()),
            "mean": grouped.agg(lambda v: np.abs(v).mean()),
            "bias": grouped.mean(),
        },
        axis=1,
    )
    print((100 * summary).round(2).to_string())
    both = table.groupby("rule")[["peak", "contact_time"]]
    print("over all cases (largest / mean |error| %):")
    print((100 * both.agg(lambda v: np.abs(v).max())).round(2).to_string())
    print((100 * both.agg(lambda v: np.abs(v).mean())).round(2).to_string())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--shape", action="append", choices=list(SHAPES))
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.1f} (1 min)")
    run(args.seeds, args.shape or tuple(SHAPES))


if __name__ == "__main__":
    main()
