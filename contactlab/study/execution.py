"""Run independent tasks serially, on local processes or on a Dask cluster, in order.

Every backend returns the results in task order, and the tasks carry everything they
need (random draws included), so the backend never changes a result.
"""

import math
import sys
from concurrent.futures import ProcessPoolExecutor

from contactlab.batch.dask import connected_client
from contactlab.entry_checks import check_flag
from contactlab.validation import check_count  # re-exported: a public name of this module

__all__ = ["check_count", "progress_bar", "run_tasks"]

CHUNKS_PER_SLOT = 4
"""Chunks per worker slot by default: few enough that pickling costs little, enough that
the load still balances when points differ in cost."""


def progress_bar(total, progress, desc, unit="task"):
    """A tqdm bar, or None. ``progress=None`` shows one only on an interactive terminal."""
    progress = check_flag("progress", progress, optional=True)
    if progress is None:
        progress = sys.stderr.isatty()
    if not progress:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=desc, unit=unit, leave=False)


def _run_chunk(fn, chunk):
    return [fn(task) for task in chunk]


def _dask_map(client, fn, chunks, bar):
    from dask.distributed import as_completed

    futures = client.map(_run_chunk, [fn] * len(chunks), chunks, pure=False)
    if bar is not None:
        sizes = {future.key: len(chunk) for future, chunk in zip(futures, chunks, strict=True)}
        for future in as_completed(futures):
            bar.update(sizes[future.key])
    return client.gather(futures)


def _process_map(workers, fn, chunks, bar):
    out = []
    with ProcessPoolExecutor(max_workers=workers) as pool:
        for chunk, result in zip(
            chunks, pool.map(_run_chunk, [fn] * len(chunks), chunks), strict=True
        ):
            out.append(result)
            if bar is not None:
                bar.update(len(chunk))
    return out


def _serial_map(fn, chunks, bar):
    out = []
    for chunk in chunks:
        out.append(_run_chunk(fn, chunk))
        if bar is not None:
            bar.update(len(chunk))
    return out


def _split(tasks, chunksize, slots):
    if chunksize is None:
        chunksize = max(1, math.ceil(len(tasks) / (CHUNKS_PER_SLOT * slots)))
    chunksize = check_count("chunksize", chunksize)
    return [tasks[i : i + chunksize] for i in range(0, len(tasks), chunksize)]


def run_tasks(fn, tasks, *, workers=1, client=None, chunksize=None, progress=None, desc=None):
    """Apply ``fn`` to every task and return the results in task order.

    Parameters
    ----------
    fn : callable
        A module-level function (it is pickled to the workers).
    tasks : sequence
        Picklable task arguments, one call each.
    workers : int, default 1
        Local worker processes (:class:`concurrent.futures.ProcessPoolExecutor`); 1 runs
        in this process. Ignored when ``client`` is given.
    client : dask.distributed.Client or str, optional
        Run on this Dask cluster, or on the scheduler at this address (connected and
        closed here). Needs the ``contactlab[dask]`` extra.
    chunksize : int, optional
        Tasks sent to a worker at a time; default :data:`CHUNKS_PER_SLOT` chunks per
        worker slot (process, or Dask worker thread).
    progress : bool, optional
        Show a tqdm progress bar; default only when stderr is a terminal.
    desc : str, optional
        Label of the progress bar.

    Returns
    -------
    list
        ``[fn(task) for task in tasks]``, computed where asked.
    """
    tasks = list(tasks)
    workers = check_count("workers", workers)
    bar = progress_bar(len(tasks), progress, desc)
    try:
        if client is not None:
            with connected_client(client) as connected:
                slots = max(1, sum(connected.nthreads().values()))
                results = _dask_map(connected, fn, _split(tasks, chunksize, slots), bar)
        elif workers > 1:
            results = _process_map(workers, fn, _split(tasks, chunksize, workers), bar)
        else:
            results = _serial_map(fn, _split(tasks, chunksize, 1), bar)
    finally:
        if bar is not None:
            bar.close()
    return [r for chunk in results for r in chunk]
