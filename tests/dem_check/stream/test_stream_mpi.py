"""The same stream on 1 and 2 MPI processes (``mpiexec`` from the mpich wheel).

Every rank draws the same particles from the case's seed; LAMMPS splits the box between
the ranks and sums the plate's forces over them. The truth must agree: only the order of
the force sums can differ (rounding), so touch times, speeds and peaks agree to 1e-9.
"""

import json
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pandas as pd
import pytest

from dem_check.stream import DEFAULT_CASE, Feed, Flow, run_stream  # noqa: F401 (CASE_CODE)

pytestmark = pytest.mark.lammps

CASE_CODE = (
    "DEFAULT_CASE.with_(duration=3e-3, feed=Feed(release=3e-3, spot=3e-3), slot=1e-3, "
    "flow=Flow(rate=1000.0, arrivals='regular'), seed=3)"
)
"""Three particles: two wheat grains and a straw (a rigid clump of six spheres: two
laws, two wall fixes, a rigid body split between the ranks' subdomains)."""

SCRIPT = f"""
import sys, warnings
warnings.simplefilter("ignore")
from dem_check.stream import DEFAULT_CASE, Feed, Flow
from dem_check.stream.result import run_stream
result = run_stream({CASE_CODE})
if result.rank == 0:
    result.truth.to_csv(sys.argv[1], index=False)
    print(result.ranks)
"""


def _mpiexec():
    found = shutil.which("mpiexec", path=str(Path(sys.executable).parent))
    if found is None:
        pytest.skip("mpiexec (the mpich wheel) is not installed next to this Python")
    return found


def test_two_ranks_give_the_same_truth(tmp_path):
    mpiexec = _mpiexec()
    out = tmp_path / "truth.csv"
    done = subprocess.run(
        [mpiexec, "-n", "2", sys.executable, "-c", SCRIPT, str(out)],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert json.loads(done.stdout.strip().splitlines()[-1]) == 2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        single = run_stream(eval(CASE_CODE)).truth  # the script's case
    parallel = pd.read_csv(out)
    assert set(single["kind"]) == {"wheat", "straw"}
    assert list(parallel["pid"]) == list(single["pid"])
    numeric = single.select_dtypes("number").columns
    # only the summation order of the plate force differs between 1 and 2 ranks
    pd.testing.assert_frame_equal(
        parallel[numeric], single[numeric], check_dtype=False, rtol=1e-9, atol=0.0
    )
