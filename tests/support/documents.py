"""Input documents the tests of both packages write: the paper's base case as a TOML config
and the FIT.json layout of a known law (imported by name: ``tests/conftest.py`` puts this
folder on the path)."""

import contactlab as cl

GRAIN = cl.Grain(diameter=5e-3, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)
"""The grain of the fit documents: the paper's 5 mm grain, ``E = 21.6 MPa``, ``nu = 0.2``."""

E_STAR = 2.25e7
"""The grain's effective modulus on a rigid flat, ``E / (1 - nu**2)`` [Pa]."""

VELOCITY = 2.0
"""Impact speed of the fit documents [m/s]."""

PAPER_CASE = """
[grain]
diameter = 5.0e-3
density = 765.0
[contact]
law = "linear"
stiffness = 1.0e5
damping = 1.0
[sensor]
resonance = 40.0e3
mass = 1.233e-3
damping_ratio = 0.02
[simulation]
velocity = 2.0
duration = 500.0e-6
"""
"""The paper's base case (Figure 6: linear law, 40 kHz sensor) as a TOML config."""

PAPER_SENSOR = "resonance = 40.0e3\nmass = 1.233e-3\ndamping_ratio = 0.02"
"""The ``[sensor]`` table's keys in :data:`PAPER_CASE`."""


def fit_document(law_name, law, fitted, grain=GRAIN, velocity=VELOCITY):
    """The FIT.json layout of ``ContactFit.to_dict`` for a known law, fitted exactly.

    Parameters
    ----------
    law_name : str
        The law's name in FIT.json (``"linear"``, ``"hertz_damped"``).
    law : ContactLaw
        The law the parameters give.
    fitted : dict
        Fitted name -> ``(value, unit)``; each with a zero standard error.
    grain : Grain, default GRAIN
    velocity : float, default VELOCITY
        Impact speed [m/s].

    Returns
    -------
    dict
    """
    entry = {"stderr": 0.0, "ci95": [None, None], "identifiable": True}
    return {
        "law": law_name,
        "law_parameters": law.parameters(),
        "parameters": {k: {"value": v, "unit": u, **entry} for k, (v, u) in fitted.items()},
        "velocity [m/s]": velocity,
        "grain": grain.to_dict(),
    }
