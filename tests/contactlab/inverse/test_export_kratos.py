"""Kratos' MaterialsDEM.json from a fit: Kratos' rules inverted exactly, numbers and fixed
keys only (the run through Kratos itself is ``tests/dem_check/engines/kratos/test_export.py``)."""

import json
import math

import numpy as np
import pytest
from documents import E_STAR, GRAIN, VELOCITY, fit_document
from hypothesis import given, settings
from hypothesis import strategies as st

import contactlab as cl
from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.inverse import export_dem
from contactlab.inverse.export.kratos import kratos_hertz_restitution, thornton_gamma
from contactlab.solver.wall import wall_impact

FIXED_STRINGS = {
    "grain",
    "plate",
    "SpheresPart",
    "RigidFacePart",
    "DEMRollingFrictionModelBounded",
    "DEM_D_Hertz_viscous_Coulomb",
    "DEM_D_Linear_viscous_Coulomb",
}


def _hertz_fit(restitution):
    k_hertz = analytic.hertz_stiffness(E_STAR, GRAIN.radius)
    law = cl.laws.HertzDamped(
        k_hertz, analytic.tsuji_damping_coefficient(k_hertz, GRAIN.mass, restitution)
    )
    fitted = {"effective_modulus": (E_STAR, "Pa"), "restitution": (restitution, "-")}
    return law, fit_document("hertz_damped", law, fitted)


@settings(max_examples=200, deadline=None)
@given(gamma=st.floats(thornton_gamma(0.999), thornton_gamma(0.001)))
def test_the_restitution_written_gives_kratos_gamma_exactly(gamma):
    e = kratos_hertz_restitution(gamma)
    # brentq to 1e-15 in e on a polynomial of slope up to ~1e3: a few ulp of gamma
    assert thornton_gamma(e) == pytest.approx(gamma, rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(restitution=st.floats(0.05, 0.98))
def test_kratos_force_from_the_file_is_the_fitted_law(restitution):
    """Kratos' DEM-FEM Hertz force rebuilt from the file's numbers (E, nu mixed at the
    wall, Kn = 2 E* sqrt(R d), F = 2/3 Kn d + 2 gamma sqrt(m Kn) d') equals the law's."""
    law, fit = _hertz_fit(restitution)
    document = json.loads(export_dem(fit, "kratos"))
    grain, plate = (m["Variables"] for m in document["materials"])
    relation = document["material_relations"][1]["Variables"]
    e_star = 1.0 / (
        (1.0 - grain["POISSON_RATIO"] ** 2) / grain["YOUNG_MODULUS"]
        + (1.0 - plate["POISSON_RATIO"] ** 2) / plate["YOUNG_MODULUS"]
    )
    gamma = thornton_gamma(relation["COEFFICIENT_OF_RESTITUTION"])
    d = np.linspace(1e-7, 1e-4, 50)
    rate = np.linspace(-2.0, 2.0, 50)
    kn = 2.0 * e_star * np.sqrt(GRAIN.radius * d)
    kratos = 2.0 / 3.0 * kn * d + 2.0 * gamma * np.sqrt(GRAIN.mass * kn) * rate
    expected = law.branch("load").force(d, rate)
    # E* mixed back from E (rounding), gamma through the inverted polynomial (1e-12)
    np.testing.assert_allclose(kratos, expected, rtol=1e-10, atol=1e-12 * np.abs(expected).max())


def test_linear_file_gives_the_fitted_stiffness_and_rebound():
    damping = analytic.linear_damping_from_restitution(1e5, 0.5, GRAIN.mass)
    law = cl.laws.LinearViscoelastic(1e5, damping)
    fit = fit_document("linear", law, {"stiffness": (1e5, "N/m"), "damping": (damping, "N*s/m")})
    document = json.loads(export_dem(fit, "kratos"))
    grain, plate = (m["Variables"] for m in document["materials"])
    e_star = 1.0 / (
        (1.0 - grain["POISSON_RATIO"] ** 2) / grain["YOUNG_MODULUS"]
        + (1.0 - plate["POISSON_RATIO"] ** 2) / plate["YOUNG_MODULUS"]
    )
    # Kn = pi 0.31225 E* R at a wall (DEM_D_Linear_viscous_Coulomb_CL.cpp); rounding only
    assert math.pi * 0.31225 * e_star * GRAIN.radius == pytest.approx(1e5, rel=1e-12)
    relation = document["material_relations"][1]["Variables"]
    expected = analytic.linear_restitution(1e5, damping, GRAIN.mass, convention="force")
    assert relation["COEFFICIENT_OF_RESTITUTION"] == pytest.approx(expected, rel=1e-14)
    assert relation["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] == "DEM_D_Linear_viscous_Coulomb"


def _strings(value):
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for item in value.values():
            yield from _strings(item)
    elif isinstance(value, list):
        for item in value:
            yield from _strings(item)


def test_only_numbers_and_fixed_keys_reach_the_file():
    """A source label cannot reach Kratos' input; hostile text is refused before any writer."""
    _law, fit = _hertz_fit(0.5)
    text = export_dem(fit, "kratos", source='FIT.json"} // injected {"')
    document = json.loads(text)
    assert "injected" not in text
    assert set(_strings(document)) <= FIXED_STRINGS
    keys = set(document)
    assert keys == {
        "materials",
        "material_relations",
        "material_assignation_table",
        "contactlab_export",
    }
    # the FIT.json schema (issue 24) refuses a unit that is not the law's, and a label
    # with a line end, for every target
    fit["parameters"]["restitution"]["unit"] = '-"}], "evil": [{"'
    with pytest.raises(ParameterError, match=r"\['restitution'\]\['unit'\]"):
        export_dem(fit, "kratos")
    with pytest.raises(ParameterError, match="source"):
        export_dem(_hertz_fit(0.5)[1], "kratos", source='FIT.json"} // injected\n{"')


def test_the_file_carries_the_step_and_the_fitted_rebound():
    law, fit = _hertz_fit(0.5)
    extra = json.loads(export_dem(fit, "kratos"))["contactlab_export"]
    exact = wall_impact(law, GRAIN.mass, VELOCITY)
    # contact time of the fitted law on a rigid plate over 200 (rounding only)
    assert extra["MaxTimeStep [s]"] == pytest.approx(exact.contact_time / 200, rel=1e-9)
    # the force-zero closed form (0.5503 for Tsuji e = 0.5) against the exact solver
    assert extra["fitted_rebound [-]"] == pytest.approx(exact.restitution, rel=1e-8)
