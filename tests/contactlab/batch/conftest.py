"""Shared fixtures of the batch tests."""

import pytest


@pytest.fixture(scope="module")
def dask_client():
    """A Dask cluster of two single-thread workers in this process (quick to start; the
    dashboard on a free port: with ``None`` distributed binds its default 8787, and two
    test workers starting clusters at once collided there)."""
    distributed = pytest.importorskip("dask.distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        yield client
