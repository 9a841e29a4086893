"""The nine Chung & Ooi tests: what each compares, its materials, and where each number is from.

Chung Y.C., Ooi J.Y. (2011) Granular Matter 13, 643-656 define tests 1-8; the ninth is the
ninth of the KratosMultiphysics nightly DEM benchmarks ("Basic DEM Benchmarking": two
identical spheres, several restitution coefficients). Sources read for this module (every
number below names one):

``[Yade-T1]`` ... ``[Yade-T4]``
    Yade's scripts of Chung & Ooi's tests 1-4 (Angelidakis, Chareyre, Caulk 2023), files
    ``Test1.py`` ... ``Test4.py`` ("Benchmarks from Chung and Ooi (2011)").
``[Kratos-B<n>]``
    KratosMultiphysics/Kratos DEMApplication: the nightly benchmark inputs
    ``test_examples/basic_benchmarks/benchmark<n>DEM.mdpa`` (material, radii, velocities)
    and ``python_scripts/DEM_benchmarks_class.py`` class ``Benchmark<n>`` (velocities,
    friction, restitution, the compared quantities); the titles of tests 5-9 from
    ``docs/pages/Applications/Discrete_Element_Modelling_Application/General/
    Basic-DEM-Benchmarking.md``.
``[Kratos-paper]``
    The same repository's digitised curves of the paper,
    ``tests/DEM3D_chung_ooi_tests/paper_data_5_to_8/benchmark5_graph2.dat`` (test 5,
    normalised spin) and ``benchmark8_graph1.dat`` (test 8, beta), drawn in the figures.
``[pysph-T<n>]``
    pysph's DEM examples of the paper (dineshadepu/pysph,
    ``pysph/examples/dem/discontinuous_dem/chung_test_<n>.py``): the second material of
    tests 5 (polyethylene), 7 (copper) and 8 (nylon).

Where the sources disagree the choice is written next to the number (:data:`DISAGREEMENTS`).
"""

from dataclasses import dataclass, field

__all__ = ["CASES", "DISAGREEMENTS", "Case", "Material"]


@dataclass(frozen=True)
class Material:
    """Sphere material: Young's modulus [Pa], Poisson ratio [-], density [kg/m**3]."""

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    source: str


GLASS = Material("glass", 4.8e10, 0.20, 2800.0, "[Yade-T1]")
LIMESTONE = Material("limestone", 2.0e10, 0.25, 2500.0, "[Yade-T1], [Kratos-B9]")
AL_ALLOY_T2 = Material("aluminium alloy", 7.0e10, 0.30, 2699.0, "[Yade-T2]")
MG_ALLOY = Material("magnesium alloy", 4.0e10, 0.35, 1800.0, "[Yade-T2]")
AL_OXIDE = Material("aluminium oxide", 3.8e11, 0.23, 4000.0, "[Yade-T3], [Yade-T4]")
CAST_IRON = Material("cast iron", 1.0e11, 0.25, 7000.0, "[Yade-T3]")
AL_ALLOY = Material(
    "aluminium alloy", 7.0e10, 0.33, 2700.0, "[Yade-T4], [Kratos-B6], [Kratos-B7], [Kratos-B8]"
)
STEEL = Material("steel", 2.08e11, 0.30, 7850.0, "[Kratos-B5], [pysph-T5]")
POLYETHYLENE = Material("polyethylene", 1.0e9, 0.40, 1400.0, "[pysph-T5]")
COPPER = Material("copper", 1.2e11, 0.35, 8900.0, "[pysph-T7]")
NYLON = Material("nylon", 2.5e9, 0.40, 1000.0, "[pysph-T8]")

TEST8_PARTNERS = {
    "aluminium alloy": Material(
        "aluminium alloy x1000 (stiffness, density)", 7.0e13, 0.33, 2.7e6, "[Kratos-B8]"
    ),
    "nylon": Material("nylon, density x1000", 2.5e9, 0.40, 1.0e6, "[pysph-T8] case B"),
}
"""Test 8's second sphere (radius 0.5 m) for each first-sphere material."""

DISAGREEMENTS = {
    7: "[pysph-T7] writes the aluminium alloy's E as 7e11 Pa, ten times [Kratos-B7], "
    "[Yade-T4] and [pysph-T8]; 7e10 Pa is used (the tangential force is zero in this test, "
    "so no graded number depends on E)",
    8: "the second sphere: [Kratos-B8] scales E and density by 1000 (aluminium alloy); "
    "[pysph-T8] scales density by 1000 and either the shear modulus of both spheres by "
    "1000 (case A) or nothing (case B). Kratos' input is used for aluminium alloy and "
    "pysph's case B for nylon; the graded beta in gross sliding does not depend on it",
    9: "[Kratos-B9] mdpa and its older class give 10 m/s per sphere, the newer class 200 m/s; "
    "both are run (the damped Hertz restitution does not depend on speed). Kratos' list "
    "includes e = 0, which no damped Hertz law ending at zero force reaches (the damping "
    "would be infinite); it is not run",
}
"""Where two sources disagree: test -> what each says and what is used."""


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
        "radius, speeds [Yade-T1], [Kratos-B1] class (10 m/s each)",
    ),
    Case(
        2,
        "Elastic normal impact of a sphere with a rigid plane",
        "contact duration, peak force, peak overlap (Hertz)",
        (AL_ALLOY_T2, MG_ALLOY),
        {"radius [m]": 0.10, "speed [m/s]": 0.2},
        "radius, speed [Yade-T2]; 0.2 m/s also [Kratos-B2] class",
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
        "radius, speed, friction [Yade-T4]; 3.9 m/s, R 2.5 mm also [Kratos-B4] class",
    ),
    Case(
        5,
        "Oblique impact on a rigid plane, constant normal speed, varying tangential speed",
        "psi2 = slip'/(mu vn') and R w'/(mu vn) against psi1 = vt/(mu vn)",
        (STEEL, POLYETHYLENE),
        {"radius [m]": 1e-5, "normal speed [m/s]": 5.0, "friction [-]": 0.3, "restitution": 1.0},
        "radius, normal speed, friction, restitution [Kratos-B5] (mdpa and class), "
        "[pysph-T5]; vt = vn tan(theta), theta 5-85 deg [Kratos-B5]",
    ),
    Case(
        6,
        "Impact of a spinning sphere on a rigid plane, constant normal speed",
        "beta = -slip'/slip against 3.5 mu (1 + e) vn / slip",
        (AL_ALLOY, NYLON),
        {"radius [m]": 0.1, "normal speed [m/s]": 0.2, "friction [-]": 0.4, "restitution": 0.5},
        "radius, speed, friction, restitution [Kratos-B6] (mdpa and class); spin "
        "-vn tan(theta)/R, theta 5-85 deg [Kratos-B6]",
    ),
    Case(
        7,
        "Impact of two identical spinning spheres, constant normal speed",
        "each sphere's spin and tangential velocity after against before",
        (AL_ALLOY, COPPER),
        {
            "radius [m]": 0.1,
            "speed of each sphere [m/s]": 0.2,
            "friction [-]": 0.4,
            "restitution": 0.5,
        },
        "radius, speeds, friction, restitution [Kratos-B7] (mdpa and class), [pysph-T7]; "
        "spins +w and -w about the same axis, w = (vn/R) tan(theta), theta 5-85 deg "
        "[Kratos-B7], [pysph-T7]: the contact points move together (no slip)",
    ),
    Case(
        8,
        "Impact of two spheres of different size, constant normal speed, varying spin",
        "beta = -slip'/slip against 3.5 mu (1 + e) vn / slip, as test 6",
        (AL_ALLOY, NYLON),
        {
            "radius [m]": 0.1,
            "second radius [m]": 0.5,
            "normal speed [m/s]": 0.2,
            "friction [-]": 0.4,
            "restitution": 0.5,
        },
        "radii, speed, friction, restitution [Kratos-B8] (mdpa and class), [pysph-T8]; "
        "second sphere at rest, see TEST8_PARTNERS",
    ),
    Case(
        9,
        "Impact of two identical spheres, constant normal speed, several restitutions",
        "rebound over impact relative speed against the requested restitution",
        (LIMESTONE,),
        {
            "radius [m]": 0.01,
            "speed of each sphere [m/s]": (10.0, 200.0),
            "restitution [-]": (0.2, 0.4, 0.6, 0.8, 1.0),
        },
        "radius, material, speeds [Kratos-B9] (mdpa: 10 m/s; newer class: 200 m/s), "
        "restitution list [Kratos-B9] class (0, 0.2, ..., 1)",
    ),
)
"""The tests in Chung & Ooi's order (the ninth Kratos')."""
