"""Batched exact linear impacts: one row per impact, thousands per second.

:func:`linear_impacts` solves every row of a frame as :func:`contactlab.simulate_impact`
solves a grain on a sensor (or a wall) through a linear spring-dashpot
(:class:`~contactlab.laws.LinearViscoelastic`), and adds the headline numbers as
:class:`~contactlab.ImpactResult` defines them. The work is done row by row in the
compiled impact loop that :func:`contactlab.simulate_impact` runs too
(:mod:`contactlab.kernels.impact_loop`); rows it does not take (modes too
close to critical damping for the modal form, a grain that settles on the plate after
:data:`contactlab.kernels.rules.MAX_CONTACTS` contacts) are solved by
:func:`contactlab.simulate_impact` itself, so every row gets the single solver's answer.
"""

import numpy as np

from contactlab.batch.frame import impact_columns, input_column
from contactlab.batch.rows import (
    DEFAULT_CHUNK,
    RESULT_COLUMNS,
    fallback_row,
    run_kernel,
    solve_frame,
)
from contactlab.kernels.impact_loop import solve_rows
from contactlab.laws import LinearViscoelastic

__all__ = ["LINEAR_INPUTS", "RESULT_COLUMNS", "linear_impacts", "solve_linear"]

LINEAR_INPUTS = impact_columns(
    input_column("k2"),
    input_column("c2", low_open=False),
)
"""Input columns of :func:`linear_impacts`."""


def solve_linear(arrays, lo, hi, out, failures):
    """Solve rows ``lo:hi`` of checked input arrays into ``out`` (hi - lo, 6).

    Returns the number of rows the single solver took over.
    """
    columns = [np.ascontiguousarray(arrays[c.name][lo:hi]) for c in LINEAR_INPUTS]
    handed = run_kernel(solve_rows, columns, (1.0, 0.0, 0.0), out)  # p = 1, q = 0: linear
    for i in handed:
        m1, k1, c1, m2, k2, c2, v0 = (float(col[i]) for col in columns)
        fallback_row(out[i], failures, lo + i, m1, k1, c1, m2, LinearViscoelastic(k2, c2), v0)
    return handed.size


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
        ``contact_time [s]`` (first contact), ``sensor_response_time [s]`` (first lobe of the
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
    grid (:mod:`contactlab.kernels.impact_loop`): the two agree to about 1e-12
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
    return solve_frame(frame, LINEAR_INPUTS, solve_linear, chunk=chunk, threads=threads)
