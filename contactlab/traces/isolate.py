"""Running a file reader in a child process, so that a crash in a C library costs a
:class:`~contactlab.errors.TraceFormatError`, not the process.

h5py's HDF5 library dereferences what a damaged file says: 2 of 1 000 byte-mutated copies
of a small HDF5 trace end the reading process with a segmentation fault
(``benchmarks/fuzz_traces.py``), which no ``except`` can catch and which would end a whole
campaign. :func:`run_isolated` reads in a forked child (copy-on-write, some 10-50 ms)
and turns the child's death into a refusal naming the file.
"""

import faulthandler
import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

from contactlab.traces.checks import fail

__all__ = ["run_isolated"]


def _in_child(function, *args):
    """Run in the child: a crash is reported by the parent, not dumped here (pytest and
    ``python -X faulthandler`` enable the dump, which the fork inherits)."""
    faulthandler.disable()
    return function(*args)


def run_isolated(path, function, *args):
    """``function(*args)`` in a forked child process; its result or its exception.

    Parameters
    ----------
    path : str
        The file being read (named in the refusal).
    function : callable
        A module-level function (the child runs it; the result and any exception come back
        pickled).
    *args
        Its arguments.

    Raises
    ------
    TraceFormatError
        If the child dies (a segmentation fault in a C library): the file is refused.

    Notes
    -----
    Where ``fork`` is not available (Windows, macOS' default) the function runs in this
    process, unprotected.
    """
    if "fork" not in multiprocessing.get_all_start_methods():
        return function(*args)
    context = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(max_workers=1, mp_context=context) as pool:
        try:
            return pool.submit(_in_child, function, *args).result()
        except BrokenProcessPool:
            raise fail(
                path,
                "binary",
                "the reading library crashed on this file (damaged or hostile): refused",
            ) from None
