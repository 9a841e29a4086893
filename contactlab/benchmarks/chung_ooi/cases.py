"""The nine Chung & Ooi tests: what each compares, its materials, and where each number is from.

Sources (read for this module; every number below names one):

``[Yade-T1]`` ... ``[Yade-T4]``
    Yade's scripts of Chung & Ooi's tests 1-4 (Angelidakis, Chareyre, Caulk 2023), files
    ``Test1.py`` ... ``Test4.py`` ("Benchmarks from Chung and Ooi (2011)").
``[Kratos]``
    KratosMultiphysics DEMApplication nightly benchmark class (``Benchmark1`` ...
    ``Benchmark9``: initial velocities, radii, friction, restitution of each test).

Tests whose inputs the sources read did not fix are listed with the reason and not run:
a number is never guessed.
"""

from dataclasses import dataclass, field

__all__ = ["CASES", "Case", "Material"]


@dataclass(frozen=True)
class Material:
    """Sphere material: Young's modulus [Pa], Poisson ratio [-], density [kg/m**3]."""

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    source: str


GLASS = Material("glass", 4.8e10, 0.20, 2800.0, "[Yade-T1]")
LIMESTONE = Material("limestone", 2.0e10, 0.25, 2500.0, "[Yade-T1]")
AL_ALLOY_T2 = Material("aluminium alloy", 7.0e10, 0.30, 2699.0, "[Yade-T2]")
MG_ALLOY = Material("magnesium alloy", 4.0e10, 0.35, 1800.0, "[Yade-T2]")
AL_OXIDE = Material("aluminium oxide", 3.8e11, 0.23, 4000.0, "[Yade-T3], [Yade-T4]")
CAST_IRON = Material("cast iron", 1.0e11, 0.25, 7000.0, "[Yade-T3]")
AL_ALLOY = Material("aluminium alloy", 7.0e10, 0.33, 2700.0, "[Yade-T4]")


@dataclass(frozen=True)
class Case:
    """One test: its number, title, inputs (with sources) and compared quantities."""

    number: int
    title: str
    compared: str
    materials: tuple = ()
    inputs: dict = field(default_factory=dict)
    sources: str = ""
    not_run: str = ""


CASES = (
    Case(
        1,
        "Elastic normal impact of two identical spheres",
        "contact duration, peak force, peak overlap (Hertz)",
        (GLASS, LIMESTONE),
        {"radius [m]": 0.010, "speed of each sphere [m/s]": 10.0},
        "radius, speeds [Yade-T1], [Kratos] Benchmark1 (10 m/s each)",
    ),
    Case(
        2,
        "Elastic normal impact of a sphere with a rigid plane",
        "contact duration, peak force, peak overlap (Hertz)",
        (AL_ALLOY_T2, MG_ALLOY),
        {"radius [m]": 0.10, "speed [m/s]": 0.2},
        "radius, speed [Yade-T2]; 0.2 m/s also [Kratos] Benchmark2",
    ),
    Case(
        3,
        "Normal contact with different coefficients of restitution",
        "rebound over impact speed against the requested restitution",
        (AL_OXIDE, CAST_IRON),
        {"radius [m]": 0.0025, "speed [m/s]": 3.9, "restitution [-]": (0.2, 0.4, 0.6, 0.8, 1.0)},
        "radius, speed, restitution list [Yade-T3]",
    ),
    Case(
        4,
        "Oblique impact on a rigid plane, constant speed, incidence 5-85 deg",
        "tangential restitution vt'/vt, spin after, contact-point rebound angle",
        (AL_OXIDE, AL_ALLOY),
        {"radius [m]": 0.0025, "speed [m/s]": 3.9, "friction [-]": 0.092},
        "radius, speed, friction [Yade-T4]; 3.9 m/s, R 2.5 mm also [Kratos] Benchmark4",
    ),
    Case(
        5,
        "Oblique impact on a rigid plane, constant normal speed, varying tangential speed",
        "vs'/(mu vn') and R w'/(mu vn) against vs/(mu vn)",
        not_run="[Kratos] Benchmark5 gives vn 5 m/s, R 1e-5 m, mu 0.3 and names steel and "
        "polyethylene; their moduli, Poisson ratios and densities were not in the sources "
        "read",
    ),
    Case(
        6,
        "Impact of a spinning sphere on a rigid plane, constant normal speed",
        "beta = -slip'/slip against 3.5 mu (1 + e) vn / slip; tangent of recoil angle",
        (AL_ALLOY,),
        {"radius [m]": 0.1, "normal speed [m/s]": 0.2, "friction [-]": 0.4, "restitution": 0.5},
        "radius, speed, friction, restitution [Kratos] Benchmark6 (aluminium alloy and nylon; "
        "aluminium alloy data [Yade-T4]; nylon's were not in the sources read)",
    ),
    Case(
        7,
        "Impact of two identical spinning spheres, constant normal speed",
        "tangential velocity and spin after against the initial spin",
        not_run="the sources read ([Kratos] Benchmark7, a Yade script) give the two spheres "
        "opposite spins, under which their contact points do not slip relative to each "
        "other; the sense of rotation Chung & Ooi used could not be confirmed",
    ),
    Case(
        8,
        "Impact of two spheres of different size, constant normal speed, varying spin",
        "beta and tangent of recoil angle, as test 6",
        not_run="the second sphere's size and material were not in the sources read",
    ),
    Case(
        9,
        "The ninth Kratos nightly DEM benchmark",
        "-",
        not_run="Chung & Ooi (2011) define eight tests; Kratos runs a ninth whose definition "
        "was not in the sources read",
    ),
)
"""The tests in Chung & Ooi's order."""
