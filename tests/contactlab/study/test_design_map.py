"""The design map: errors over resonance x diameter, against the study's own points."""

import numpy as np
import pytest

from contactlab.cli import main
from contactlab.errors import ParameterError
from contactlab.laws import LinearViscoelastic
from contactlab.study import StudySetup, design_map, simulate_point

RESONANCES = [20e3, 70e3, 200e3]
DIAMETERS = [2.5e-3, 5e-3]

QUANTITIES = (
    "contact_time [s]",
    "sensor_response_time [s]",
    "peak_contact_force [N]",
    "peak_sensor_force [N]",
)


@pytest.mark.parametrize("damping", [1.0, 0.0])
def test_map_points_are_the_study_points(damping):
    """Each map point (batch solver) equals simulate_point at that point (single solver)."""
    setup = StudySetup.paper(law=LinearViscoelastic(stiffness=1e5, damping=damping))
    result = design_map(setup, RESONANCES, DIAMETERS)
    assert len(result.table) == len(RESONANCES) * len(DIAMETERS)
    for row in result.table.itertuples(index=False):
        point = {"grain.diameter": row[1], "sensor.resonance": row[0]}
        single = simulate_point(setup, point, [1.0])
        for name in QUANTITIES:
            mapped = result.table.loc[
                (result.table["resonance [Hz]"] == row[0])
                & (result.table["diameter [m]"] == row[1]),
                name,
            ].item()
            # batch and single solver agree to 1e-9 (docs/batch.md); the single solver reads
            # the lobe on its output grid, refined to the same root, so 1e-7 is ample
            assert mapped == pytest.approx(single[name][0], rel=1e-7), name


def test_force_error_falls_with_resonance_for_an_elastic_contact():
    """The paper's conclusion 2: a faster sensor reads the peak force better."""
    setup = StudySetup.paper(law=LinearViscoelastic(stiffness=1e5, damping=0.0))
    result = design_map(setup, np.geomspace(10e3, 300e3, 12), [5e-3])
    errors = np.abs(result.grid("force_error [%]")[0])
    assert errors[-3:].max() < errors[:3].min()


def test_grid_shape_orders_diameters_by_rows():
    result = design_map(resonances=RESONANCES, diameters=DIAMETERS)
    grid = result.grid("time_error [%]")
    assert grid.shape == (len(DIAMETERS), len(RESONANCES))
    first = result.table.iloc[1]  # resonance varies fastest
    assert (first["resonance [Hz]"], first["diameter [m]"]) == (RESONANCES[1], DIAMETERS[0])
    assert grid[0, 1] == first["time_error [%]"]


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"resonances": []}, "resonances"),
        ({"resonances": [40e3, 20e3]}, "resonances"),
        ({"diameters": [-1e-3, 5e-3]}, "diameters"),
        ({"diameters": [1e-3, float("nan")]}, "diameters"),
    ],
)
def test_bad_grid_names_the_parameter(kwargs, name):
    with pytest.raises(ParameterError, match=name):
        design_map(**kwargs)


def test_map_command_writes_table_and_figures(tmp_path, capsys):
    assert main(["map", "--out", str(tmp_path), "--damping", "0"]) == 0
    written = {p.name for p in tmp_path.iterdir()}
    assert written == {"design_map.csv", "design_map.png", "design_map.svg"}
    assert "wrote" in capsys.readouterr().out
