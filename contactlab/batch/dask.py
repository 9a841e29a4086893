"""Batched impacts on a Dask cluster: the frame split by rows, one task per partition.

Every partition is solved by :func:`contactlab.batch.linear_impacts` on a worker and the
results are put back in the input order, so the cluster never changes a number: the
result equals ``linear_impacts(frame)`` exactly. The frame is checked here first, so a
bad row is named by its position in the whole frame, not in a partition.
"""

import contextlib
import math

import pandas as pd

from contactlab.batch.frame import check_frame, chunk_bounds
from contactlab.batch.linear import LINEAR_INPUTS, linear_impacts
from contactlab.errors import ParameterError
from contactlab.validation import check_count

__all__ = ["connected_client", "dask_linear_impacts"]

PARTITIONS_PER_THREAD = 2
"""Partitions per worker thread by default (a little balancing, little overhead)."""


@contextlib.contextmanager
def connected_client(client):
    """A connected Client from a Client or a scheduler address (dask imported lazily)."""
    try:
        from dask.distributed import Client
    except ImportError as exc:
        raise ImportError(
            "running on a Dask cluster needs dask.distributed: pip install 'contactlab[dask]'"
        ) from exc
    if isinstance(client, Client):
        yield client
    elif isinstance(client, str):
        with Client(client) as owned:
            yield owned
    else:
        raise ParameterError(
            f"client must be a dask.distributed.Client or a scheduler address; got {client!r}"
        )


def dask_linear_impacts(frame, client, *, partitions=None):
    """:func:`~contactlab.batch.linear_impacts` on a Dask cluster, partitioned by rows.

    Parameters
    ----------
    frame : pandas.DataFrame
        Input frame of :func:`~contactlab.batch.linear_impacts`.
    client : dask.distributed.Client or str
        The cluster, or its scheduler's address (connected and closed here).
    partitions : int, optional
        Number of row partitions; default two per worker thread (at most one per row).

    Returns
    -------
    pandas.DataFrame
        Exactly ``linear_impacts(frame)``.
    """
    check_frame(frame, LINEAR_INPUTS)
    with connected_client(client) as connected:
        if partitions is None:
            threads = max(1, sum(connected.nthreads().values()))
            partitions = max(1, min(len(frame), PARTITIONS_PER_THREAD * threads))
        partitions = check_count("partitions", partitions)
        size = max(1, math.ceil(len(frame) / partitions))
        pieces = [frame.iloc[lo:hi] for lo, hi in chunk_bounds(len(frame), size)]
        if not pieces:
            return linear_impacts(frame)
        futures = connected.map(linear_impacts, pieces, pure=False)
        return pd.concat(connected.gather(futures))
