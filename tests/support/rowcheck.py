"""Pieces the row-by-row tests of the linear and the Hertz batch solver share: random
sensors and grains, the paper's frame, relative differences and the bad rows every batch
solver names (imported by name: ``tests/conftest.py`` puts this folder on the path)."""

import numpy as np
import pandas as pd
import pytest

import contactlab as cl
from contactlab.errors import ParameterError

BODY_COLUMNS = ("m1 [kg]", "k1 [N/m]", "c1 [N*s/m]", "m2 [kg]")
"""The sensor's and the grain's columns, before the contact's two and ``v0 [m/s]``."""


def random_bodies(rng, n, most_damping=None):
    """Sensors 3 kHz - 300 kHz with damping ratios 1e-3 - ``most_damping`` (default
    10**0.5 = 3.2: under- and overdamped, beyond real sensors, whose plausible range ends
    at 1) and
    grains 0.01 - 30 times the sensor mass: ``(m1, k1, c1, m2)``, drawn in this order."""
    m1 = 10 ** rng.uniform(-4, -2, n)
    k1 = m1 * (2 * np.pi * 10 ** rng.uniform(3.5, 5.5, n)) ** 2
    top = 0.5 if most_damping is None else np.log10(most_damping)
    c1 = 2 * 10 ** rng.uniform(-3, top, n) * np.sqrt(k1 * m1)
    m2 = m1 * 10 ** rng.uniform(-2, 1.5, n)
    return m1, k1, c1, m2


def paper_frame(columns, stiffness, damping, n):
    """``n`` rows of the paper's sensor (40 kHz disc, damping ratio 0.02) and grain
    (50 mg at 2 m/s); the contact's stiffness (``columns[4]``) goes from 0.5 to 1.5 times
    ``stiffness`` along the rows."""
    sensor = cl.Sensor.from_disc(10e-3, 2e-3, 40e3, damping_ratio=0.02)
    values = (sensor.mass, sensor.stiffness, sensor.damping, 5.007e-5, stiffness, damping, 2.0)
    frame = pd.DataFrame(dict(zip(columns, values, strict=True)), index=range(n))
    frame[columns[4]] *= np.linspace(0.5, 1.5, n)
    return frame


def relative(a, b):
    """|a - b| / |b|, zero where both are NaN or equal (also where both are zero)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = np.abs(a - b) / np.abs(b)
    return np.where(np.isnan(a) & np.isnan(b), 0.0, np.where(a == b, 0.0, rel))


BAD_BODY_ROWS = [
    ("m2 [kg]", -1e-5, "column 'm2 [kg]' (grain mass) must be a number > 0"),
    ("v0 [m/s]", np.nan, "'v0 [m/s]'"),
    ("m1 [kg]", np.inf, "immovable wall (k1 = inf)"),
]
"""``(column, value, message)``: bad sensor and grain values every batch solver names."""


def assert_bad_row_named(impacts, frame, column, value, message):
    """``impacts(frame)`` with ``value`` in rows 'c' and 'e' of ``column`` names the column
    and the first bad row by position and index."""
    frame = frame.set_index(pd.Index(list("abcdef")))
    frame.loc[["c", "e"], column] = value
    with pytest.raises(ParameterError, match=r"row 2 \(index 'c'\)") as info:
        impacts(frame)
    assert message in str(info.value)
