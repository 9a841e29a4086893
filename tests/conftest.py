"""Shared test settings: the paper's grain and sensors."""

import matplotlib
import pytest

import contactlab as cl

matplotlib.use("Agg")

PAPER_MASS = 765.0 * 3.141592653589793 * (5e-3) ** 3 / 6.0
"""The paper's 5 mm grain at 765 kg/m^3 [kg]."""


@pytest.fixture
def paper_grain():
    """The paper's grain: 5.0 mm, 765 kg/m^3, G = 9 MPa, nu = 0.2."""
    return cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)


@pytest.fixture
def paper_sensor():
    """The paper's 40 kHz disc sensor (10 mm x 2 mm steel), damping ratio 0.02."""
    return cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
