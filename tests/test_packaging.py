"""A wheel carries every data file the package reads, and works installed from it.

The wheel is built from a copy of the sources (pip builds in place, and the work tree
must stay clean), then installed without its dependencies into a folder of its own that
comes first on the path, so the commands below run the installed copy, not the sources.
"""

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "contactlab" / "data"
SOURCES = ("pyproject.toml", "README.md", "contactlab", "dem_check")


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """The project's wheel, built by pip from a copy of the sources, offline: the build
    back end (setuptools, wheel) comes from the test extra, not from an isolated download."""
    tmp = tmp_path_factory.mktemp("wheel")
    source = tmp / "source"
    for name in SOURCES:
        path = ROOT / name
        if path.is_dir():
            shutil.copytree(path, source / name, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            source.mkdir(exist_ok=True)
            shutil.copy(path, source / name)
    built = subprocess.run(
        [
            *(sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation"),
            *("-q", "-w", str(tmp), str(source)),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert built.returncode == 0, built.stderr
    (path,) = tmp.glob("contactlab-*.whl")
    return path


def test_the_wheel_holds_every_data_file(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    expected = {
        f"contactlab/data/{p.relative_to(DATA).as_posix()}"
        for p in DATA.rglob("*")
        if p.is_file() and "__pycache__" not in p.parts
    }
    assert len(expected) >= 13  # 5 presets, 6 species and their README, the template
    assert expected <= names, sorted(expected - names)


def _installed(wheel, target, *code):
    """Run Python code against the wheel installed in ``target`` (not the sources)."""
    env = {**os.environ, "PYTHONPATH": str(target)}
    return subprocess.run(
        [sys.executable, "-c", *code],
        capture_output=True,
        text=True,
        cwd=target.parent,
        env=env,
        check=False,
    )


def test_presets_species_and_template_work_from_an_installed_wheel(wheel, tmp_path):
    target = tmp_path / "site"
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(target), wheel],
        check=True,
        capture_output=True,
    )
    code = (
        "import sys, contactlab; assert contactlab.__file__.startswith(sys.argv[1]), "
        "contactlab.__file__\n"
        "from contactlab.cli import main\n"
        "for argv in (['presets'], ['presets', '--show', 'fig6'], ['advise', '--list'],"
        " ['init', sys.argv[1] + '/case.toml']):\n"
        "    assert main(argv) == 0, argv\n"
    )
    run = _installed(wheel, target, code, str(target))
    assert run.returncode == 0, run.stderr
    assert run.stdout.split()[:5] == ["fig5", "fig6", "fig7", "fig8", "fig9"]
    assert "[sensor]" in run.stdout and "wheat" in run.stdout
    assert (target / "case.toml").read_text() == (DATA / "template.toml").read_text()
