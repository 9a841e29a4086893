"""Names from a user's stream case cannot run as spreadsheet formulas or break a line
(issue 24: every string written into an export is validated or neutralised)."""

import numpy as np
import pandas as pd
import pytest

from contactlab.errors import ParameterError
from dem_check.stream import ParticleKind
from dem_check.stream.result import StreamResult
from dem_check.traces import Trace

CONTACT = {"law": "linear", "stiffness": 1e5}


@pytest.mark.parametrize("name", ["wheat\nshell touch x", "chaff\r", "a\x00b", 3.0])
def test_a_particle_name_is_one_printable_line_of_text(name):
    with pytest.raises(ParameterError, match="particles name"):
        ParticleKind(name=name, diameter=(4e-3, 5e-3), density=(1200.0, 1400.0), contact=CONTACT)


def test_written_tables_neutralise_formula_names(tmp_path):
    kind = '=HYPERLINK("http://x")'
    result = StreamResult.__new__(StreamResult)  # a stand-in: the tables, no LAMMPS run
    result.steps = pd.DataFrame({"t [s]": [0.0, 1e-6], "sensor_force [N]": [0.0, -1.0]})
    result.truth = pd.DataFrame({"pid": [0], "kind": [kind], "touch [s]": [-1e-6]})
    result.particles = pd.DataFrame({"kind": [kind], "mass [kg]": [5e-5]})
    result.script, result.time_step = "units si\n", 1e-7
    trace = Trace(np.array([0.0, 1e-6]), np.array([0.0, 1.0]), "N")
    result.write(tmp_path, trace)
    truth = pd.read_csv(tmp_path / "truth.csv")
    particles = pd.read_csv(tmp_path / "particles.csv")
    # the text cell is shown as text ('=...), the negative number stays a number
    assert truth["kind"][0] == "'" + kind and particles["kind"][0] == "'" + kind
    assert truth["touch [s]"][0] == -1e-6
