"""Shared fixtures of the batch tests."""

import pytest


@pytest.fixture(scope="module")
def dask_client():
    """A Dask cluster of two single-thread workers in this process (quick to start;
    dashboard off, so no port to bind)."""
    distributed = pytest.importorskip("dask.distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        yield client
