"""Batched exact linear impacts: one row per impact, thousands per second.

:func:`linear_impacts` solves every row of a frame as :func:`contactlab.simulate_impact`
solves a grain on a sensor (or a wall) through a linear spring-dashpot
(:class:`~contactlab.laws.LinearViscoelastic`), and adds the headline numbers as
:class:`~contactlab.ImpactResult` defines them. The work is done row by row in a compiled
kernel (:mod:`contactlab.batch.linear_kernel`); rows the kernel does not take (modes too
close to critical damping for the modal form, a grain that settles on the plate after
:data:`contactlab.solver.impact.MAX_CONTACTS` contacts) are solved by
:func:`contactlab.simulate_impact` itself, so every row gets the single solver's answer.
"""

import math
import os
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from contactlab.batch.frame import Column, check_frame, chunk_bounds
from contactlab.batch.linear_kernel import OUTPUTS, STATUS_OK, solve_rows
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import LinearViscoelastic
from contactlab.solver import simulate_impact
from contactlab.validation import check_count

__all__ = [
    "LINEAR_INPUTS",
    "RESULT_COLUMNS",
    "check_threads",
    "linear_impacts",
    "solve_linear",
]

LINEAR_INPUTS = (
    Column("m1 [kg]", "sensor moving mass", allow_inf=True),
    Column("k1 [N/m]", "sensor stiffness, inf for an immovable wall", allow_inf=True),
    Column("c1 [N*s/m]", "sensor damping", low_open=False),
    Column("m2 [kg]", "grain mass"),
    Column("k2 [N/m]", "contact stiffness"),
    Column("c2 [N*s/m]", "contact damping", low_open=False),
    Column("v0 [m/s]", "impact speed"),
)
"""Input columns of :func:`linear_impacts`."""

RESULT_COLUMNS = (
    "contact_time [s]",
    "response_time [s]",
    "peak_contact_force [N]",
    "peak_sensor_force [N]",
    "restitution [-]",
    "contacts [-]",
)
"""Columns :func:`linear_impacts` adds, in the order of the kernel's outputs."""

DEFAULT_CHUNK = 100_000
"""Rows solved per call of the kernel: bounds the working memory (about 100 bytes a row
beyond the output columns) whatever the frame's length."""


def _check_sensor_pairs(arrays, frame):
    """An infinite mass needs an infinite stiffness and back (as :class:`Sensor` asks)."""
    m1, k1 = arrays["m1 [kg]"], arrays["k1 [N/m]"]
    bad = np.flatnonzero(np.isinf(m1) & ~np.isinf(k1))
    if bad.size:
        i = int(bad[0])
        raise ParameterError(
            f"column 'm1 [kg]' is inf only for an immovable wall (k1 = inf); row {i} "
            f"(index {frame.index[i]!r}) has k1 = {k1[i]!r}"
        )


def _single(row, threshold=0.0):
    """One row by :func:`contactlab.simulate_impact` (rows the kernel hands back)."""
    m1, k1, c1, m2, k2, c2, v0 = row
    sensor = Sensor.rigid() if math.isinf(k1) else Sensor(mass=m1, stiffness=k1, damping=c1)
    law = LinearViscoelastic(stiffness=k2, damping=c2)
    res = simulate_impact(Grain.from_mass(m2), sensor, law, v0, threshold=threshold)
    return (
        res.contact_time,
        res.sensor_response_time,
        res.peak_contact_force,
        res.peak_sensor_force,
        res.restitution,
        len(res.contact_intervals),
    )


def solve_linear(arrays, lo, hi, out):
    """Solve rows ``lo:hi`` of checked input arrays into ``out`` (hi - lo, 6).

    Returns the number of rows the single solver took over.
    """
    columns = [np.ascontiguousarray(arrays[c.name][lo:hi]) for c in LINEAR_INPUTS]
    status = np.empty(hi - lo, dtype=np.int64)
    solve_rows(*columns, out, status)
    handed = np.flatnonzero(status != STATUS_OK)
    for i in handed:
        out[i] = _single([float(col[i]) for col in columns])
    return handed.size


CHUNKS_PER_THREAD = 4
"""Chunks per thread when several threads share a frame (rows differ in cost: the
scan follows the sensor's resonance, so a few chunks each keep the threads busy)."""


def check_threads(threads):
    """Threads to use: an int >= 1, or None for every core of this machine."""
    if threads is None:
        return os.cpu_count() or 1
    return check_count("threads", threads)


def _solve_chunks(arrays, results, chunk, threads):
    """Solve every row of the checked arrays into ``results``, ``threads`` at a time."""
    rows = len(results)
    if threads > 1:
        chunk = max(1, min(chunk, math.ceil(rows / (CHUNKS_PER_THREAD * threads))))
    bounds = chunk_bounds(rows, chunk)
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        if threads == 1 or len(bounds) == 1:
            for lo, hi in bounds:
                solve_linear(arrays, lo, hi, results[lo:hi])
            return
        with ThreadPoolExecutor(max_workers=threads) as pool:
            jobs = [pool.submit(solve_linear, arrays, lo, hi, results[lo:hi]) for lo, hi in bounds]
            for job in jobs:
                job.result()


def linear_impacts(frame, *, chunk=DEFAULT_CHUNK, threads=1):
    """Exact linear impacts, one per row, with the single-impact solver's numbers.

    Parameters
    ----------
    frame : pandas.DataFrame
        One row per impact with the columns ``m1 [kg]`` (sensor moving mass), ``k1 [N/m]``
        (sensor stiffness; ``inf`` for an immovable wall, when ``m1`` may be ``inf`` too
        and ``m1``, ``c1`` are not used), ``c1 [N*s/m]`` (sensor damping), ``m2 [kg]``
        (grain mass), ``k2 [N/m]`` (contact stiffness), ``c2 [N*s/m]`` (contact damping)
        and ``v0 [m/s]`` (impact speed); other columns are kept.
    chunk : int, default 100 000
        Rows solved at a time (working memory is proportional to it).
    threads : int or None, default 1
        Threads solving chunks side by side (the compiled kernel runs without Python's
        global interpreter lock); ``None`` uses every core. The numbers do not depend on
        it.

    Returns
    -------
    pandas.DataFrame
        A copy of ``frame`` (same index and order) with the columns
        ``contact_time [s]`` (first contact), ``response_time [s]`` (first lobe of the
        sensor signal S1 above zero, as ``ImpactResult.sensor_response_time``; nan when
        it does not end in the window), ``peak_contact_force [N]`` (largest S2 in the
        first contact), ``peak_sensor_force [N]`` (largest S1 in that lobe),
        ``restitution [-]`` (rebound speed after the last contact over ``v0``) and
        ``contacts [-]`` (contacts in the window, re-contacts included).

    Raises
    ------
    ParameterError
        For a missing or non-numeric column, or a value out of range (NaN, a negative
        mass, ...): the message names the column and the first bad row.

    Notes
    -----
    Each row is the impact ``simulate_impact(Grain(mass=m2), Sensor(m1, k1, c1),
    LinearViscoelastic(k2, c2), v0)`` with its default window (the first contact and
    five sensor periods of ringing, at least 1.5 contact times), threshold 0. The kernel
    finds the events with the single solver's scan and root tolerance and reads the
    peaks and the lobe exactly, where ``ImpactResult`` refines them from its output
    grid (:mod:`contactlab.batch.linear_kernel`): the two agree to about 1e-12
    relative, except where two local maxima of a signal are closer than the grid can
    tell apart.

    Examples
    --------
    >>> import pandas as pd
    >>> from contactlab.batch import linear_impacts
    >>> frame = pd.DataFrame({"m1 [kg]": [1.233e-3], "k1 [N/m]": [7.79e7],
    ...     "c1 [N*s/m]": [12.4], "m2 [kg]": [5.0e-5], "k2 [N/m]": [1e5],
    ...     "c2 [N*s/m]": [1.0], "v0 [m/s]": [2.0]})
    >>> round(linear_impacts(frame)["contacts [-]"].iloc[0])
    1
    """
    chunk = check_count("chunk", chunk)
    threads = check_threads(threads)
    arrays = check_frame(frame, LINEAR_INPUTS, chunk)
    _check_sensor_pairs(arrays, frame)
    results = np.empty((len(frame), OUTPUTS))
    _solve_chunks(arrays, results, chunk, threads)
    out = frame.copy()
    for j, name in enumerate(RESULT_COLUMNS):
        out[name] = results[:, j]
    return out
