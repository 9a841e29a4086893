"""Shared test settings.

The paper's grains and sensors (``paper_grain``, ``paper_grain_small``, ``paper_sensor``,
``rigid_sensor``) and the ``golden`` fixture come from contactlab's pytest plugin
(:mod:`contactlab.testing.plugin`), loaded through its entry point.
"""

import matplotlib

matplotlib.use("Agg")

pytest_plugins = ["pytester"]  # the plugin's own tests run pytest in temporary folders

PAPER_MASS = 765.0 * 3.141592653589793 * (5e-3) ** 3 / 6.0
"""The paper's 5 mm grain at 765 kg/m^3 [kg]."""
