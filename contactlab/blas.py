"""One BLAS thread while a measurement is read: the linear algebra of a trace's fits is
small (a few hundred to a few thousand rows, a handful of columns), where OpenBLAS'
threads cost more than they give.

Measured on the 2-core machine (`docs/campaign.md`, Speed): ``run_campaign`` on a 1.5 M
sample record at load 1, 7.0 s with one thread against 10-14 s with OpenBLAS' default;
``compare_laws`` on the Keysight sample trace at load 6, 3.1-3.4 s of CPU against
10.9-14.1 s.
"""

import functools

from threadpoolctl import ThreadpoolController

from contactlab.errors import ParameterError

__all__ = ["one_blas_thread", "with_one_blas_thread"]

_CONTROLLER = None
"""The BLAS libraries found at the first call (:class:`threadpoolctl.ThreadpoolController`)."""


def one_blas_thread():
    """Limit every loaded BLAS library to one thread until the limit is restored.

    The libraries are looked up once, at the first call (numpy's and scipy's BLAS are
    loaded by then; looking them up costs about 3 ms, the limit itself microseconds).

    Returns
    -------
    threadpoolctl's limiter
        A context manager (or call its ``restore_original_limits``) that gives the
        libraries their threads back.
    """
    global _CONTROLLER
    if _CONTROLLER is None:
        _CONTROLLER = ThreadpoolController()
    return _CONTROLLER.limit(limits=1, user_api="blas")


def with_one_blas_thread(function):
    """Decorate ``function`` to run with :func:`one_blas_thread` (its signature and
    docstring kept).

    Raises
    ------
    ParameterError
        If ``function`` is not callable.
    """
    if not callable(function):
        raise ParameterError(f"function must be callable, not {type(function).__name__}")

    @functools.wraps(function)
    def limited(*args, **kwargs):
        with one_blas_thread():
            return function(*args, **kwargs)

    return limited
