"""Batched impacts on a Dask cluster: the frame split by rows, one task per partition.

Every partition is solved by :func:`contactlab.batch.linear_impacts` (or
:func:`~contactlab.batch.hertz_impacts`) on a worker and the results are put back in
the input order, so the cluster never changes a number: the result equals
``linear_impacts(frame)`` exactly. The frame is checked here first, so a bad row is
named by its position in the whole frame, not in a partition.
"""

import contextlib
import functools
import math

import pandas as pd

from contactlab.batch.frame import check_frame, chunk_bounds
from contactlab.batch.hertz import DEFAULT_RTOL, HERTZ_INPUTS, hertz_impacts
from contactlab.batch.linear import LINEAR_INPUTS, linear_impacts
from contactlab.batch.rows import warn_implausible
from contactlab.errors import ParameterError
from contactlab.plausibility import internal
from contactlab.validation import check_count, check_number

__all__ = ["check_client", "connected_client", "dask_hertz_impacts", "dask_linear_impacts"]

PARTITIONS_PER_THREAD = 2
"""Partitions per worker thread by default (a little balancing, little overhead)."""


def _client_class():
    try:
        from dask.distributed import Client
    except ImportError as exc:
        raise ImportError(
            "running on a Dask cluster needs dask.distributed: pip install 'contactlab[dask]'"
        ) from exc
    return Client


def check_client(client):
    """Return ``client`` after checking it is None, a ``dask.distributed.Client`` or a
    scheduler address (non-empty text); nothing is connected.

    Raises
    ------
    ParameterError
        Naming ``client``, for anything else.
    """
    if client is None or (isinstance(client, str) and client):
        return client
    if not isinstance(client, _client_class()):
        raise ParameterError(
            f"client must be a dask.distributed.Client or a scheduler address; got {client!r}"
        )
    return client


@contextlib.contextmanager
def connected_client(client):
    """A connected Client from a Client or a scheduler address (dask imported lazily)."""
    if check_client(client) is None:
        raise ParameterError("client must be a dask.distributed.Client or a scheduler address")
    if isinstance(client, str):
        with _client_class()(client) as owned:
            yield owned
    else:
        yield client


def _quietly(impacts, piece):
    """``impacts(piece)`` without plausibility warnings: the whole frame was checked once,
    before it was partitioned."""
    with internal():
        return impacts(piece)


def _on_cluster(impacts, columns, frame, client, partitions):
    """``impacts(frame)`` on a cluster: row partitions, results in the input order."""
    warn_implausible(check_frame(frame, columns), frame)
    if partitions is not None:  # before connecting: a bad count must not wait for a cluster
        partitions = check_count("partitions", partitions)
    with connected_client(client) as connected:
        if partitions is None:
            threads = max(1, sum(connected.nthreads().values()))
            partitions = max(1, min(len(frame), PARTITIONS_PER_THREAD * threads))
        size = max(1, math.ceil(len(frame) / partitions))
        pieces = [frame.iloc[lo:hi] for lo, hi in chunk_bounds(len(frame), size)]
        if not pieces:
            return impacts(frame)
        futures = connected.map(functools.partial(_quietly, impacts), pieces, pure=False)
        return pd.concat(connected.gather(futures))


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
    return _on_cluster(linear_impacts, LINEAR_INPUTS, frame, client, partitions)


def dask_hertz_impacts(frame, client, *, rtol=DEFAULT_RTOL, partitions=None):
    """:func:`~contactlab.batch.hertz_impacts` on a Dask cluster, partitioned by rows.

    Parameters
    ----------
    frame : pandas.DataFrame
        Input frame of :func:`~contactlab.batch.hertz_impacts`.
    client, partitions
        As for :func:`dask_linear_impacts`.
    rtol : float, default 1e-9
        Relative tolerance of the integrator.

    Returns
    -------
    pandas.DataFrame
        Exactly ``hertz_impacts(frame, rtol=rtol)``.
    """
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    impacts = functools.partial(hertz_impacts, rtol=rtol)
    return _on_cluster(impacts, HERTZ_INPUTS, frame, client, partitions)
