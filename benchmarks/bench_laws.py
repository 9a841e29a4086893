"""Time each law's impact on an immovable wall (median of several runs: the machine is
shared, medians rather than minima). The two-mass targets are in ``bench_solver.py``."""

from timing import median_time

import contactlab as cl
from contactlab import laws

REPEATS = 15


def main():
    grain = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
    mass = grain.mass
    material = grain.material()
    cases = {
        "linear": laws.LinearViscoelastic(1e5, 1.0),
        "hertz": laws.Hertz.from_material(material),
        "hertz_damped": laws.HertzDamped.from_material(material, 0.5, mass),
        "kuwabara_kono": laws.KuwabaraKono(laws.Hertz.from_material(material).k_hertz, 1e-6),
        "hunt_crossley": laws.HuntCrossley(laws.Hertz.from_material(material).k_hertz, 1.5, 0.2),
        "walton_braun": laws.WaltonBraun(1e5, 2e5),
        "linear_plastic": laws.LinearPlastic(1e5, 3.0),
        "thornton": laws.Thornton.from_material(material, 1e6),
        "plastic_trapezoid": laws.PlasticTrapezoid(70e-6, 7e-6),
    }
    print("Rigid-wall impact per law (v0 = 2 m/s, 20 001 output samples), median of", REPEATS)
    for name, law in cases.items():
        t = median_time(
            lambda law=law: cl.simulate_impact(grain, cl.Sensor.rigid(), law, 2.0), REPEATS
        )
        print(f"  {name:18s} {t * 1e3:8.2f} ms")


if __name__ == "__main__":
    main()
