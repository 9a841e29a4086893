"""Time each law's impact on an immovable wall and the two-mass linear impact.

Prints the median of several runs (this machine is shared: medians, not minima) and, for
the linear two-mass case of the solver issue, ratios against scipy's solve_ivp DOP853 at
rtol 1e-10 and against the paper's explicit Euler at dt = 1e-10 s (a shortened Euler run,
extrapolated linearly in the number of steps, as stated in the output).
"""

import statistics
import time
import warnings

import numpy as np
from scipy.integrate import solve_ivp

import contactlab as cl
from contactlab import laws

REPEATS = 15


def median_time(fn, repeats=REPEATS):
    fn()  # warm-up
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    grain = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
    mass = grain.mass
    e, nu, r = grain.material()
    cases = {
        "linear": laws.LinearViscoelastic(1e5, 1.0),
        "hertz": laws.Hertz.from_material(e, nu, r),
        "hertz_damped": laws.HertzDamped.from_material(e, nu, r, 0.5, mass),
        "kuwabara_kono": laws.KuwabaraKono(laws.Hertz.from_material(e, nu, r).k_hertz, 1e-6),
        "hunt_crossley": laws.HuntCrossley(laws.Hertz.from_material(e, nu, r).k_hertz, 1.5, 0.2),
        "walton_braun": laws.WaltonBraun(1e5, 2e5),
        "linear_plastic": laws.LinearPlastic(1e5, 3.0),
        "thornton": laws.Thornton.from_material(e, nu, r, 1e6),
        "plastic_trapezoid": laws.PlasticTrapezoid(70e-6, 7e-6),
    }
    print("Rigid-wall impact per law (v0 = 2 m/s, 20 001 output samples), median of", REPEATS)
    for name, law in cases.items():
        t = median_time(lambda law=law: cl.simulate_impact(grain, cl.Sensor.rigid(), law, 2.0))
        print(f"  {name:18s} {t * 1e3:8.2f} ms")

    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    law = cases["linear"]
    ours = median_time(lambda: cl.simulate_impact(grain, sensor, law, 2.0, 500e-6))
    hertz = cases["hertz_damped"]
    ours_hertz = median_time(lambda: cl.simulate_impact(grain, sensor, hertz, 2.0, 500e-6))

    m1, k1, c1 = sensor.mass, sensor.stiffness, sensor.damping
    t_eval = np.linspace(0.0, 500e-6, 20001)

    def rhs(t, y):
        s2 = max(1e5 * (y[2] - y[0]) + 1.0 * (y[3] - y[1]), 0.0) if y[2] > y[0] else 0.0
        return [y[1], (s2 - k1 * y[0] - c1 * y[1]) / m1, y[3], -s2 / mass]

    def scipy_run():
        solve_ivp(rhs, (0, 500e-6), [0, 0, 0, 2.0], "DOP853", t_eval=t_eval, rtol=1e-10, atol=1e-16)

    scipy_t = median_time(scipy_run, repeats=3)
    euler_window = 5e-6
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        euler_short = median_time(
            lambda: cl.simulate_impact(
                grain, sensor, law, 2.0, euler_window, method="euler", time_step=1e-10
            ),
            repeats=1,
        )
    euler_t = euler_short * 500e-6 / euler_window
    print("\nTwo-mass linear impact, 40 kHz sensor, 500 us window, 20 001 samples:")
    print(f"  contactlab exact           {ours * 1e3:10.2f} ms")
    print(f"  scipy DOP853 rtol 1e-10    {scipy_t * 1e3:10.2f} ms   ratio {scipy_t / ours:8.1f}x")
    print(
        f"  paper's Euler dt 1e-10     {euler_t:10.2f} s    ratio {euler_t / ours:8.0f}x "
        f"(extrapolated from a {euler_window * 1e6:g} us run of {euler_short:.2f} s)"
    )
    print(f"Two-mass damped Hertz impact, same sensor: {ours_hertz * 1e3:.2f} ms")


if __name__ == "__main__":
    main()
