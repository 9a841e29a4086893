"""A record's impacts analysed on several processes (``workers`` of
:func:`dem_check.campaign.run_campaign`).

Each analysed impact is read on its own (:func:`dem_check.campaign.analysis.analyse_impact`:
its signal numbers, the crosstalk removal and the force's reconstruction, dense linear
algebra of a few hundred unknowns), so the impacts of one record share nothing but the
detection, the record's noise levels and its structure modes. With ``workers > 1`` they
are shared with forked processes (Linux' ``fork``: the record is not copied or pickled;
a platform without it reads the impacts one after the other) and each process reads a
share of the impacts. Every process keeps the one BLAS thread the campaign set, so each
impact's arithmetic, and its row, are those of the one-process reading
(``tests/dem_check/campaign/test_campaign_workers.py``).
"""

import multiprocessing
from concurrent.futures import ProcessPoolExecutor

from dem_check.campaign.analysis import analyse_impact

__all__ = ["analysed_impacts"]

_SHARED = None
"""The record's detection and analysis settings while its impacts are read (set before
the processes are forked, so that they inherit it)."""


def _analysed(k):
    found, settings = _SHARED
    return analyse_impact(found, found.impacts[k], *settings)


def analysed_impacts(found, indices, settings, workers):
    """The row and gallery traces of each impact of ``indices`` (of ``found.impacts``).

    Parameters
    ----------
    found : Detection
        The record's detection.
    indices : list of int
        The impacts to analyse.
    settings : tuple
        ``(sensor, grain, fit, crosstalk, modes, noise)`` of
        :func:`~dem_check.campaign.analysis.analyse_impact`.
    workers : int
        Processes to read them on (1: this one).

    Returns
    -------
    dict
        ``{index: (row, traces)}``.
    """
    global _SHARED
    forking = "fork" in multiprocessing.get_all_start_methods()
    _SHARED = (found, settings)
    try:
        if workers == 1 or len(indices) < 2 or not forking:
            return {k: _analysed(k) for k in indices}
        context = multiprocessing.get_context("fork")
        with ProcessPoolExecutor(min(workers, len(indices)), mp_context=context) as pool:
            return dict(zip(indices, pool.map(_analysed, indices), strict=True))
    finally:
        _SHARED = None
