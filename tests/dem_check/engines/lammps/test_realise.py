"""The LAMMPS export realised: a user's deck made of the snippet rebounds as the fitted law.

The snippet (``export_dem(fit, "lammps")``) is included in the smallest deck its header
asks for and run; the impact is read from LAMMPS and set against the fitted law's exact
wall impact (:func:`contactlab.solver.wall_impact`). Without ``limit_damping`` the same
inputs realise the other codes' zero-overlap rebound (the MercuryDPM row of the table in
``docs/dem_check.md``), measured here too.
"""

import pytest
from documents import E_STAR, GRAIN, VELOCITY, fit_document

import contactlab as cl
from contactlab import analytic
from contactlab.inverse import export_dem
from contactlab.inverse.export.contact import contact_from_fit
from contactlab.inverse.export.rebound import realised_rebound
from contactlab.solver import wall_impact
from dem_check.engines.lammps.realise import realise_snippet

pytestmark = pytest.mark.lammps


def _fits():
    k_hertz = analytic.hertz_stiffness(E_STAR, GRAIN.radius)
    hertz_damped = cl.laws.HertzDamped(
        k_hertz, analytic.tsuji_damping_coefficient(k_hertz, GRAIN.mass, 0.5)
    )
    linear = cl.laws.LinearViscoelastic(1e5, 1.0)
    return {
        "linear": (
            linear,
            fit_document("linear", linear, {"stiffness": (1e5, "N/m"), "damping": (1.0, "N*s/m")}),
        ),
        "hertz_damped": (
            hertz_damped,
            fit_document(
                "hertz_damped",
                hertz_damped,
                {"effective_modulus": (E_STAR, "Pa"), "restitution": (0.5, "-")},
            ),
        ),
        "hertz": (
            cl.laws.Hertz(k_hertz),
            fit_document("hertz", cl.laws.Hertz(k_hertz), {"effective_modulus": (E_STAR, "Pa")}),
        ),
    }


@pytest.mark.parametrize("name", ["linear", "hertz_damped", "hertz"])
def test_export_realises_the_fitted_law_on_a_rigid_plate(tmp_path, name):
    law, fit = _fits()[name]
    snippet = tmp_path / "contact.lmp"
    snippet.write_text(export_dem(fit, "lammps"), encoding="utf-8")
    exact = wall_impact(law, GRAIN.mass, VELOCITY)
    impact = realise_snippet(snippet, GRAIN, VELOCITY, exact.contact_time)
    # 200 steps per contact, damping first order: measured <= 0.16 % over release
    # phases (linear), 0.1 % (Tsuji), 1e-6 (Hertz); the bound is 1 %
    assert impact.restitution == pytest.approx(exact.restitution, rel=0.01)
    # contact time counted in whole steps (0.5 % of it), sampled peaks (measured
    # <= 0.31 %): the 3 %
    assert impact.contact_time == pytest.approx(exact.contact_time, rel=0.03)
    assert impact.peak_force == pytest.approx(exact.peak_contact_force, rel=0.03)
    assert impact.min_force >= 0.0  # limit_damping: never tensile


@pytest.mark.parametrize("name", ["linear", "hertz_damped"])
def test_without_limit_damping_the_zero_overlap_rebound_is_realised(tmp_path, name):
    """The MercuryDPM row: a damper that may pull ends the contact at zero overlap."""
    law, fit = _fits()[name]
    text = export_dem(fit, "lammps").replace(" limit_damping", "")
    snippet = tmp_path / "contact.lmp"
    snippet.write_text(text, encoding="utf-8")
    exact = wall_impact(law, GRAIN.mass, VELOCITY)
    impact = realise_snippet(snippet, GRAIN, VELOCITY, exact.contact_time)
    contact = contact_from_fit(fit, "test", None, 210e9, 0.3, None)
    overlap_rebound = realised_rebound(contact, "overlap")
    # same 200-step first-order error as above (measured <= 0.07 %)
    assert impact.restitution == pytest.approx(overlap_rebound, rel=0.01)
    # and it is not the fitted law's: 0.500 vs 0.550 (Tsuji), 0.500 vs 0.540 (linear)
    assert impact.restitution < 0.95 * exact.restitution
    assert impact.min_force < -0.01 * impact.peak_force  # the damper pulls at the end


# --- hostile fit files (issue 24): LAMMPS runs the snippet and nothing in it executes ---
# A fit's source label (the CLI sets it to the FIT.json path) may carry shell and include
# commands; export_dem refuses them where they would start a line
# (tests/contactlab/inverse/test_export_injection.py). Here LAMMPS includes the snippets
# it accepts and runs the impact; a marker file the commands would create must not exist.
# The control writes the same command on its own line, as the exporter did before issue
# 24, and LAMMPS does create the marker: the check can fail.


def _run(tmp_path, text):
    snippet = tmp_path / "contact.lmp"
    snippet.write_text(text, encoding="utf-8")
    law = _fits()["linear"][0]
    return realise_snippet(
        snippet, GRAIN, VELOCITY, wall_impact(law, GRAIN.mass, VELOCITY).contact_time
    )


def _labels(marker, evil):
    return [
        f"shell touch {marker}",
        f"include {evil}",
        f'" ; shell touch {marker} ; "',
        f"$(shell touch {marker}) ${{x}} & shell touch {marker}",
    ]


def test_accepted_labels_execute_nothing_in_lammps(tmp_path):
    marker = tmp_path / "injected"
    evil = tmp_path / "evil.lmp"
    evil.write_text(f"shell touch {marker}\n", encoding="utf-8")
    for label in _labels(marker, evil):
        impact = _run(tmp_path, export_dem(_fits()["linear"][1], "lammps", source=label))
        assert not marker.exists(), label
        assert impact.restitution > 0.0  # the deck ran to the end: an impact was recorded


def test_the_control_a_command_on_its_own_line_does_execute(tmp_path):
    marker = tmp_path / "injected"
    text = export_dem(_fits()["linear"][1], "lammps", source="SOURCE")
    # what a unit of "N/m\nshell touch ...\n#" wrote before the schema
    text = text.replace("# source: SOURCE", f"# source: x\nshell touch {marker}\n#")
    _run(tmp_path, text)
    assert marker.exists()
