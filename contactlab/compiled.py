"""numba's ``njit``, with a damaged on-disk cache rebuilt instead of crashing.

The compiled solvers are cached as ``*.nbi`` (index) and ``*.nbc`` (data) pickles beside
their sources (:mod:`contactlab.batch.warm_up`). numba 0.68 catches only a missing file
when it reads them: a zero-length, truncated or overwritten file (a full disk, a copy
cut short, a shared drive) raised ``EOFError`` or ``pickle.UnpicklingError`` from the
first call of any solver (issue 24), and kept doing so in every new process. A cache from
another numba version or CPU is not damage: numba's own version stamp and index key
already make it a miss.

Every compiled module imports :func:`njit` from here instead of from numba. A cache entry
that cannot be read is then reported once per cache folder with a
:class:`~contactlab.errors.CompiledCacheWarning` naming the folder and the cure
(``make clean-numba``), its index is emptied (numba's ``FunctionCache.flush``) and the
function is compiled again, which rewrites the entry.

Processes that compile at the same time (the parallel warm-up, pytest's workers) share
these files, and numba updates an index by reading it, adding an entry and writing it back
(``IndexDataCacheFile.save``): two processes saving two signatures of one function both
read the same index, both name their data ``<function>.1.nbc``, and whichever writes last
wins the index while the other's data may sit under its key. Every index is therefore read
under a shared ``flock`` on its cache folder and written under an exclusive one (POSIX;
without ``fcntl``, on Windows, the warm-up compiles in one process).
"""

import contextlib
import os
import warnings

import numba
from numba.core.caching import FunctionCache

from contactlab.errors import CompiledCacheWarning

try:
    import fcntl
except ImportError:  # Windows: no flock
    fcntl = None

__all__ = ["CAN_LOCK", "njit"]

CAN_LOCK = fcntl is not None
"""Whether the cache files are locked, so that several processes may compile at once."""

_REPORTED = set()
"""Cache folders already reported in this process."""


class _RebuildingCache(FunctionCache):
    """numba's per-function cache; an entry that fails to load is rebuilt, not raised."""

    def __init__(self, py_func):
        super().__init__(py_func)
        self.function_name = f"{py_func.__module__}.{py_func.__qualname__}"

    def save_overload(self, sig, data):
        with _folder_lock(self.cache_path, exclusive=True):
            super().save_overload(sig, data)

    def load_overload(self, sig, target_context):
        try:
            with _folder_lock(self.cache_path, exclusive=False):
                return super().load_overload(sig, target_context)
        except Exception as exc:  # anything failing while reading a cache entry is damage
            if self.cache_path not in _REPORTED:
                _REPORTED.add(self.cache_path)
                warnings.warn(
                    f"damaged numba cache in {self.cache_path} ({type(exc).__name__}: {exc} "
                    f"while loading {self.function_name}): compiling it again and rewriting "
                    "the entry; if this repeats, delete the cache ('make clean-numba', "
                    "or the *.nbi and *.nbc files in that folder)",
                    CompiledCacheWarning,
                    stacklevel=2,
                )
            with _folder_lock(self.cache_path, exclusive=True):
                self.flush()  # an empty index: the save after compiling writes a readable one
            return None


@contextlib.contextmanager
def _folder_lock(folder, exclusive):
    """Hold numba's cache ``folder`` locked (``flock`` on the folder itself, no lock file).

    Parameters
    ----------
    folder : str
        The cache folder; created if missing (numba creates it on its first save).
    exclusive : bool
        True to write an index (one writer, no reader), False to read one.
    """
    if fcntl is None:
        yield
        return
    os.makedirs(folder, exist_ok=True)
    descriptor = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX if exclusive else fcntl.LOCK_SH)
        yield
    finally:
        os.close(descriptor)  # releases the lock


def njit(*args, borrowed=False, **options):
    """:func:`numba.njit`, whose ``cache=True`` rebuilds a damaged cache entry.

    Used as ``@njit(cache=True, error_model="numpy")`` (or bare ``@njit``); the options
    are numba's, and one of ours:

    borrowed : bool, default False
        The function only reads and writes the arrays it is given: it allocates none and
        returns none (nor a tuple holding one). It is then compiled without numba's
        reference counts (numba's ``_nrt=False``). numba increments the count of every
        array argument on entry and decrements it at the argument's last use with
        atomic instructions, and its pruning pass pairs them only inside one basic block
        or a simple diamond: a small helper with branches, called at every scan point or
        root iteration, paid eight atomic operations a call, and they took about a third
        of the linear batch's time (perf, issue 25). An allocation in such a function
        fails to compile; returning a borrowed array would hand the caller a reference
        it does not own, so ``tests/contactlab/test_borrowed_kernels.py`` checks the
        compiled signatures of every borrowed function in :mod:`contactlab.kernels`.
    """
    if borrowed:
        options["_nrt"] = False
    if args and callable(args[0]):
        return _rebuilding(numba.njit(*args, **options))
    decorate = numba.njit(*args, **options)
    return lambda function: _rebuilding(decorate(function))


def _rebuilding(dispatcher):
    if isinstance(getattr(dispatcher, "_cache", None), FunctionCache):
        dispatcher._cache = _RebuildingCache(dispatcher.py_func)
    return dispatcher
