"""pytest plugin of contactlab: the paper's grains and sensors, and golden reference traces.

Registered through the ``pytest11`` entry point, so installing contactlab makes it
available in every test suite, with nothing to import:

Fixtures
    ``paper_grain`` (5.0 mm), ``paper_grain_small`` (2.5 mm), ``paper_sensor`` (40 kHz
    disc), ``rigid_sensor`` (immovable wall) and ``golden`` (a
    :class:`~contactlab.testing.golden.GoldenStore`: ``golden.check(name, result)``).
Command-line flag
    ``--contactlab-update-golden``: write golden references that are missing or no
    longer match; every file written is listed at the end of the session.
ini option
    ``contactlab_golden_dir``: folder of the golden references, relative to the rootdir
    (default ``tests/golden``).
Marker
    ``golden``: added to every test that uses the ``golden`` fixture, so
    ``pytest -m golden --contactlab-update-golden`` rewrites references and runs nothing
    else.

contactlab is imported inside the fixtures, not when the plugin loads, so test sessions
that do not use them do not pay for importing numpy and scipy.
"""

from pathlib import Path

import pytest

_WRITTEN = pytest.StashKey[list]()
"""Lines recording the golden files written during the session."""

PAPER_DISC = {"diameter": 10e-3, "thickness": 2e-3}
"""The paper's sensor disc: 10 mm x 2 mm steel, a moving mass of 1.233 g [m]."""


def pytest_addoption(parser):
    """Register ``--contactlab-update-golden`` and the ``contactlab_golden_dir`` ini option."""
    group = parser.getgroup("contactlab", "contactlab golden reference traces")
    group.addoption(
        "--contactlab-update-golden",
        action="store_true",
        default=False,
        dest="contactlab_update_golden",
        help="write golden reference traces that are missing or no longer match (the "
        "files written are listed at the end; review and commit them)",
    )
    parser.addini(
        "contactlab_golden_dir",
        help="folder of contactlab golden reference traces, relative to the rootdir",
        default="tests/golden",
    )


def pytest_configure(config):
    """Register the ``golden`` marker and start the record of files written."""
    config.addinivalue_line(
        "markers",
        "golden: compares against contactlab golden reference traces (added automatically "
        "to tests that use the golden fixture)",
    )
    config.stash[_WRITTEN] = []


def golden_dir(config):
    """Folder of the golden references: the ini option, relative to the rootdir."""
    return Path(config.rootpath) / config.getini("contactlab_golden_dir")


def pytest_report_header(config):
    """Say so in the header when golden references may be written."""
    if config.getoption("contactlab_update_golden"):
        return f"contactlab: updating golden references in {golden_dir(config)}"
    return None


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    """Mark every test that uses the ``golden`` fixture (before ``-m`` selects)."""
    for item in items:
        if "golden" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.golden)


def pytest_terminal_summary(terminalreporter, config):
    """List the golden files written in this session."""
    written = config.stash.get(_WRITTEN, [])
    if written:
        terminalreporter.section("contactlab golden references written")
        for line in written:
            terminalreporter.write_line(line)
        terminalreporter.write_line("Review the changes (git diff) and commit them.")


def _paper_grain(diameter):
    """The paper's grain material (Keska et al. 2021, Sec. 2.2) at ``diameter`` [m]."""
    from contactlab import Grain

    return Grain(diameter=diameter, density=765.0, shear_modulus=9e6, poisson_ratio=0.2)


@pytest.fixture
def paper_grain():
    """The paper's grain: 5.0 mm, 765 kg/m**3 (50.07 mg), G = 9 MPa, nu = 0.2."""
    return _paper_grain(5.0e-3)


@pytest.fixture
def paper_grain_small():
    """The paper's small grain: 2.5 mm, same material as ``paper_grain`` (6.26 mg)."""
    return _paper_grain(2.5e-3)


@pytest.fixture
def paper_sensor():
    """The paper's 40 kHz disc sensor (10 mm x 2 mm steel), damping ratio 0.02 (our
    choice: the paper leaves it open; quartz sensors have 0.01-0.05)."""
    from contactlab import Sensor

    return Sensor.from_disc(resonance=40e3, damping_ratio=0.02, **PAPER_DISC)


@pytest.fixture
def rigid_sensor():
    """An immovable wall: the signal equals the contact force."""
    from contactlab import Sensor

    return Sensor.rigid()


@pytest.fixture
def golden(request):
    """Golden reference traces in ``contactlab_golden_dir``: ``golden.check(name, result)``.

    Compares an ImpactResult (or a measured dem_check Trace) with the stored reference
    ``name``; with ``--contactlab-update-golden`` writes it instead when it is missing or
    no longer matches. See :class:`contactlab.testing.golden.GoldenStore`.
    """
    from contactlab.testing.golden import GoldenStore

    config = request.config
    return GoldenStore(
        golden_dir(config),
        update=config.getoption("contactlab_update_golden"),
        log=config.stash[_WRITTEN],
    )
