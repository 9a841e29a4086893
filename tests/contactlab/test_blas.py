"""One BLAS thread while a trace is read (:mod:`contactlab.blas`): the limit holds inside
the readers and is given back after them."""

import inspect

import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from contactlab.blas import with_one_blas_thread
from contactlab.compare.impacts import compare_trace
from contactlab.inverse.compare_laws import compare_laws
from contactlab.inverse.fit import fit_contact
from contactlab.inverse.identify import identify_sensor
from contactlab.inverse.reconstruct import reconstruct_force


def _blas_threads():
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_one_thread_inside_and_the_threads_given_back_after():
    # the suite runs on one thread (tests/conftest.py): give the libraries two first
    with threadpool_limits(limits=2, user_api="blas"):
        assert set(_blas_threads()) == {2}
        inside = with_one_blas_thread(_blas_threads)()
        assert set(inside) == {1}
        assert set(_blas_threads()) == {2}


@pytest.mark.parametrize(
    "reader", [fit_contact, compare_laws, reconstruct_force, identify_sensor, compare_trace]
)
def test_the_single_trace_readers_are_limited_and_keep_their_signature(reader):
    assert reader.__wrapped__.__name__ == reader.__name__
    assert inspect.signature(reader) == inspect.signature(reader.__wrapped__)
    assert reader.__doc__ == reader.__wrapped__.__doc__
