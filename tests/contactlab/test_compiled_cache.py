"""A damaged numba cache is rebuilt with one warning, never a crash (issue 24).

numba 0.68 reads its ``*.nbi``/``*.nbc`` pickles catching only a missing file: a
zero-length or overwritten file raised ``EOFError``/``UnpicklingError`` from the first
solver call, in every new process. :mod:`contactlab.compiled` rebuilds such an entry.
The cache is redirected to a temporary folder (``NUMBA_CACHE_DIR``) and a small compiled
module (Brent's root search, a few seconds to compile) runs in fresh processes, since a
process that has compiled a function never reads its cache again.
"""

import ast
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from contactlab.batch.warm_up import COMPILED_MODULES

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = """
import warnings
import numpy as np
from contactlab.errors import CompiledCacheWarning
from contactlab.kernels.brent import brent_next, brent_start
warnings.simplefilter("always", CompiledCacheWarning)
work = np.zeros(9)
print(brent_start(work, 0.0, -1.0, 2.0, 1.0), brent_next(work, 0.5))
"""
"""Brent on f(x) = x - 1 over [0, 2]: the secant's first guess is 1.0, the root."""


def _run(cache):
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    return subprocess.run(
        [sys.executable, "-c", SCRIPT], env=environment, capture_output=True, text=True,
        timeout=300, check=False,
    )  # fmt: skip


@pytest.fixture(scope="module")
def damaged(tmp_path_factory):
    """A warm cache, two of its files damaged, then one run on it: (folder, run, clean run)."""
    cache = tmp_path_factory.mktemp("numba-cache")
    clean = _run(cache)
    assert clean.returncode == 0, clean.stderr
    (folder,) = {path.parent for path in cache.rglob("*.nbi")}
    (start_index,) = folder.glob("brent.brent_start-*.nbi")
    (next_data,) = folder.glob("brent.brent_next-*.1.nbc")
    start_index.write_bytes(b"garbage, not a pickle")  # UnpicklingError before the fix
    next_data.write_bytes(b"")  # EOFError before the fix
    return folder, _run(cache), clean


def test_a_damaged_cache_is_rebuilt_with_one_warning_naming_its_folder(damaged):
    folder, run, clean = damaged
    assert run.returncode == 0, run.stderr
    assert run.stdout == clean.stdout  # the same root search, now recompiled
    assert run.stderr.count("CompiledCacheWarning") == 1, run.stderr  # once per folder
    assert f"damaged numba cache in {folder}" in run.stderr
    assert "make clean-numba" in run.stderr


def test_the_rebuilt_cache_files_read_again(damaged):
    folder, _, _ = damaged
    for index in folder.glob("brent.brent_*.nbi"):
        with index.open("rb") as stream:
            pickle.load(stream)  # numba's version stamp
            _, overloads = pickle.loads(stream.read())
        assert overloads, f"{index.name} lists no compiled signature"
        for data in overloads.values():
            pickle.loads((folder / data).read_bytes())


def test_every_cached_compiled_function_uses_the_rebuilding_njit():
    """A module that caches compiled code imports ``njit`` from contactlab.compiled."""
    offenders = []
    for path in sorted((ROOT / "contactlab").rglob("*.py")) + sorted(
        (ROOT / "dem_check").rglob("*.py")
    ):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            numba_import = isinstance(node, ast.ImportFrom) and node.module == "numba"
            if numba_import and any(alias.name in ("njit", "jit") for alias in node.names):
                offenders.append(str(path.relative_to(ROOT)))
            if isinstance(node, ast.Attribute) and node.attr in ("njit", "jit"):
                if isinstance(node.value, ast.Name) and node.value.id == "numba":
                    if path.name != "compiled.py":
                        offenders.append(str(path.relative_to(ROOT)))
    assert not offenders, f"use 'from contactlab.compiled import njit' in {offenders}"


def _compiles_on_its_own(decorator):
    """Whether a decorator is ``njit(..., cache=True)`` without ``inline="always"``."""
    if not (isinstance(decorator, ast.Call) and getattr(decorator.func, "id", "") == "njit"):
        return False
    keywords = {k.arg: getattr(k.value, "value", None) for k in decorator.keywords}
    return keywords.get("cache") is True and keywords.get("inline") != "always"


@pytest.mark.parametrize("name", COMPILED_MODULES)
def test_every_module_the_warm_check_reads_caches_a_function_of_its_own(name):
    """``cache_is_warm`` looks for each listed module's ``*.nbi`` files: a module whose
    functions are all inlined into their callers never writes one, and the check would
    call a warm cache cold forever (the command lines then announce a compile on every
    run; found when model_rhs's functions were inlined)."""
    source = ROOT / (name.replace(".", "/") + ".py")
    tree = ast.parse(source.read_text(encoding="utf-8"))
    functions = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)]
    assert any(_compiles_on_its_own(d) for f in functions for d in f.decorator_list), name


LOCK_SCRIPT = (
    """
import fcntl, os
import numba.core.caching as caching

def held(folder):
    '''How another open file description finds the folder: "exclusive", "shared" or "free".'''
    descriptor = os.open(folder, os.O_RDONLY)
    try:
        for mode, name in ((fcntl.LOCK_EX, "free"), (fcntl.LOCK_SH, "shared")):
            try:
                fcntl.flock(descriptor, mode | fcntl.LOCK_NB)
                return name
            except BlockingIOError:
                pass
        return "exclusive"
    finally:
        os.close(descriptor)

def spy(method, label):
    def spied(self, *args):
        print(label, held(os.path.dirname(self._index_path)))
        return method(self, *args)
    return spied

caching.IndexDataCacheFile.save = spy(caching.IndexDataCacheFile.save, "save")
caching.IndexDataCacheFile.load = spy(caching.IndexDataCacheFile.load, "load")
"""
    + SCRIPT
    + """
from contactlab.batch.warm_up import cache_misses
print("compiled", *cache_misses())
"""
)


def test_the_cache_index_is_written_under_an_exclusive_lock_and_read_under_a_shared_one(
    tmp_path,
):
    """numba updates an index by read-modify-write: two processes compiling two signatures
    of one function (the parallel warm-up, pytest's workers) could pair one's index entry
    with the other's data file. A compile (loads that miss, then saves) and a load."""
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    runs = [
        subprocess.run(
            [sys.executable, "-c", LOCK_SCRIPT], env=environment, capture_output=True,
            text=True, timeout=300, check=True,
        ).stdout.splitlines()
        for _ in range(2)
    ]  # fmt: skip
    compiled, loaded = ([line for line in run if line.startswith(("save", "load"))] for run in runs)
    # every function compiled (brent_start, brent_next, a callee) is looked up, then saved
    saves = compiled.count("save exclusive")
    assert saves >= 2 and sorted(compiled) == ["load shared"] * saves + ["save exclusive"] * saves
    assert loaded == ["load shared"] * 2, loaded  # the callee is in its callers' code
    first = runs[0][-1].split()  # cache_misses names what the first run compiled
    assert first[0] == "compiled" and {"brent.brent_next", "brent.brent_start"} <= {
        name.removeprefix("contactlab.kernels.") for name in first[1:]
    }, first
    assert runs[1][-1] == "compiled"  # cache_misses: nothing compiled in the second run


def test_after_the_warm_up_a_new_process_loads_every_solver_from_the_cache():
    """The parallel warm-up's processes saved every entry its calls need, none lost: a new
    process making the same calls compiles nothing (run after ``contactlab warm-up``, as
    ``make test`` does)."""
    script = "from contactlab.batch import warm_up as w\n[g() for g in w._GROUPS]\n"
    script += "print(w.cache_is_warm(), *w.cache_misses())"
    run = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=600, check=True
    )
    warm, *missed = run.stdout.split()
    assert missed == [], f"compiled instead of loaded: {missed}"
    # every listed module has cache files, so the next command line announces no compile
    # (session 17: the Gauss rule, compiled only inside cached callers, had none)
    assert warm == "True"
