"""Batched oblique impacts: the single solver's numbers, row by row."""

import math
import re

import numpy as np
import pandas as pd
import pytest

import contactlab as cl
from contactlab.batch.oblique import OBLIQUE_RESULTS, oblique_impacts
from contactlab.errors import ParameterError

GRAIN = cl.Grain(diameter=5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23)
HERTZ = cl.laws.Hertz.from_material(GRAIN.material())
MINDLIN = cl.laws.Mindlin.from_material(cl.analytic.Material(3.8e11, 0.23, GRAIN.radius), 0.092)
ETA = 0.3 * math.sqrt(HERTZ.k_hertz * GRAIN.mass)


def _frame(angles, spins, k1=math.inf, m1=math.inf, c1=0.0, damping=0.0):
    return pd.DataFrame(
        {
            "m1 [kg]": m1,
            "k1 [N/m]": k1,
            "c1 [N*s/m]": c1,
            "m2 [kg]": GRAIN.mass,
            "k_hertz [N/m**1.5]": HERTZ.k_hertz,
            "damping [N*s/m**1.25]": damping,
            "k_mindlin [N/m**1.5]": MINDLIN.k_mindlin,
            "friction [-]": MINDLIN.friction,
            "v0 [m/s]": 3.9,
            "radius [m]": GRAIN.radius,
            "angle [rad]": angles,
            "spin [rad/s]": spins,
        }
    )


def _single(row, sensor, normal, history, damping, lever_arm):
    law = cl.laws.Mindlin(MINDLIN.k_mindlin, MINDLIN.friction, history, damping)
    res = cl.simulate_oblique(
        GRAIN,
        sensor,
        normal,
        law,
        3.9,
        row["angle [rad]"],
        spin=row["spin [rad/s]"],
        lever_arm=lever_arm,
    )
    return [
        res.contact_time,
        res.restitution,
        res.tangential_velocity,
        res.angular_velocity,
        res.rebound_angle,
        res.contact_rebound_angle,
        res.tangential_restitution,
        len(res.phases),
    ]


@pytest.mark.parametrize(
    ("moving", "history", "damping", "lever_arm"),
    [
        (False, "total", "none", "radius"),
        (True, "incremental", "none", "radius"),
        (False, "incremental_rescaled", "tied", "contact"),  # Kratos' rules
    ],
)
def test_rows_are_the_single_solver(moving, history, damping, lever_arm):
    """Angles from normal to grazing, spins of both signs; the sensor or a flat."""
    angles = np.radians([0.0, 5.0, 30.0, 60.0, 89.0])
    spins = np.array([200.0, 0.0, -500.0, 1000.0, 0.0])
    eta = ETA if damping == "tied" else 0.0
    if moving:
        frame, sensor = _frame(angles, spins, 1e7, 1e-3, 2.0, eta), cl.Sensor(1e-3, 1e7, 2.0)
    else:
        frame, sensor = _frame(angles, spins, damping=eta), cl.Sensor.rigid()
    out = oblique_impacts(frame, history=history, damping=damping, lever_arm=lever_arm)
    normal = cl.laws.HertzDamped(HERTZ.k_hertz, eta)
    for i in range(len(frame)):
        expected = _single(frame.iloc[i], sensor, normal, history, damping, lever_arm)
        # the same compiled loop on the same parameters, packed by two routes: to rounding
        np.testing.assert_allclose(
            out.iloc[i][list(OBLIQUE_RESULTS)].to_numpy(float), expected, rtol=1e-13, atol=1e-300
        )


def test_normal_incidence_without_spin_has_no_tangential_motion():
    """At 0 deg and no spin nothing drives the tangential side; elastic Hertz: e = 1."""
    out = oblique_impacts(_frame([0.0], [0.0]))
    assert out["tangential_velocity [m/s]"].iloc[0] == 0.0
    assert out["angular_velocity [rad/s]"].iloc[0] == 0.0
    assert math.isnan(out["tangential_restitution [-]"].iloc[0])  # no slip before
    assert out["restitution [-]"].iloc[0] == pytest.approx(1.0, abs=1e-7)  # rtol 1e-9 x steps


@pytest.mark.parametrize(
    ("column", "value"),
    [("angle [rad]", math.pi / 2), ("angle [rad]", -0.1), ("spin [rad/s]", math.inf)],
)
def test_bad_columns_name_column_and_row(column, value):
    frame = _frame([0.1, 0.2], [1.0, -1.0])
    frame.loc[1, column] = value
    with pytest.raises(ParameterError, match=rf"'{re.escape(column)}'.*row 1"):
        oblique_impacts(frame)


def test_bad_options():
    frame = _frame([0.1], [0.0])
    with pytest.raises(ParameterError, match="history"):
        oblique_impacts(frame, history="rescaled")
    with pytest.raises(ParameterError, match="not supported"):
        oblique_impacts(frame, history="total", damping="tied")
    with pytest.raises(ParameterError, match="lever_arm"):
        oblique_impacts(frame, lever_arm="centre")


def test_a_row_no_solver_finishes_costs_no_other_row():
    """A contact still open after a second (k_hertz 1e-9 N/m**1.5 at 5 cm/s: minutes
    long) is handed back to simulate_oblique, which refuses it: NaN and its reason."""
    frame = _frame([0.1, 0.1], [0.0, 0.0])
    frame.loc[1, "k_hertz [N/m**1.5]"] = 1e-9
    frame.loc[1, "v0 [m/s]"] = 0.05
    with pytest.warns(cl.errors.RowFailedWarning, match="1 of 2 rows"):
        out = oblique_impacts(frame)
    assert np.isnan(out[list(OBLIQUE_RESULTS)].iloc[1]).all()
    assert "had not ended" in out["error"].iloc[1]
    assert out["error"].iloc[0] == ""
    assert out["restitution [-]"].iloc[0] == pytest.approx(1.0, abs=1e-7)  # elastic Hertz
