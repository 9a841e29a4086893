"""Batched damped-Hertz impacts: one row per impact, thousands per second.

:func:`hertz_impacts` solves every row of a frame as :func:`contactlab.simulate_impact`
solves a grain on a sensor (or a wall) through Tsuji's damped Hertz law
(:class:`~contactlab.laws.HertzDamped`, the EDEM and LIGGGHTS normal law; ``damping = 0``
is elastic Hertz), and adds the headline numbers as :class:`~contactlab.ImpactResult`
defines them. The work is done row by row in a compiled kernel
(:mod:`contactlab.kernels.hertz_impact`) that runs the single solver's own compiled
contact pieces; rows it hands back are solved by :func:`contactlab.simulate_impact`.
"""

import numpy as np

from contactlab.batch.frame import impact_columns, input_column
from contactlab.batch.rows import DEFAULT_CHUNK, fallback_row, run_kernel, solve_frame
from contactlab.kernels.impact_loop import solve_rows
from contactlab.laws import HertzDamped
from contactlab.validation import check_number

__all__ = ["DEFAULT_RTOL", "HERTZ_INPUTS", "hertz_impacts"]

HERTZ_INPUTS = impact_columns(
    input_column("k_hertz"),
    input_column("damping", low_open=False),
)
"""Input columns of :func:`hertz_impacts`."""

DEFAULT_RTOL = 1e-9
"""Relative tolerance of the integrator by default: every headline number within 1e-6
of the converged one. Measured on random rows over the tests' domain against rtol 1e-12:
worst 7e-8 at 1e-9; 1.4e-6 at 1e-8 (a sensor peak on an overdamped plate, where
``c1 v1`` carries the velocity's absolute tolerance); 1.5e-5 at 1e-6."""


def _solver(rtol):
    def solve(arrays, lo, hi, out, failures):
        columns = [np.ascontiguousarray(arrays[c.name][lo:hi]) for c in HERTZ_INPUTS]
        for i in run_kernel(solve_rows, columns, (1.5, 0.25, rtol), out):  # Tsuji: p, q
            m1, k1, c1, m2, k_hertz, damping, v0 = (float(col[i]) for col in columns)
            law = HertzDamped(k_hertz, damping)
            options = {"method": "adaptive", "rtol": rtol}
            fallback_row(out[i], failures, lo + i, m1, k1, c1, m2, law, v0, **options)

    return solve


def hertz_impacts(frame, *, rtol=DEFAULT_RTOL, chunk=DEFAULT_CHUNK, threads=1):
    """Damped-Hertz impacts, one per row, with the single-impact solver's numbers.

    Parameters
    ----------
    frame : pandas.DataFrame
        One row per impact with the sensor, grain and speed columns of
        :func:`contactlab.batch.linear_impacts` (``m1 [kg]``, ``k1 [N/m]``, ``c1 [N*s/m]``,
        ``m2 [kg]``, ``v0 [m/s]``) and, for the contact, ``k_hertz [N/m**1.5]`` (Hertz
        stiffness ``kH``) and ``damping [N*s/m**1.25]`` (``eta`` of
        ``kH d**1.5 + eta d**0.25 d'``, 0 for elastic Hertz); other columns are kept.
    rtol : float, default 1e-9
        Relative tolerance of the integrator (:data:`DEFAULT_RTOL`: every number within
        1e-6 of the converged one).
    chunk, threads
        As for :func:`contactlab.batch.linear_impacts`.

    Returns
    -------
    pandas.DataFrame
        A copy of ``frame`` with the columns of :func:`contactlab.batch.linear_impacts`:
        ``contact_time [s]``, ``sensor_response_time [s]``, ``peak_contact_force [N]``,
        ``peak_sensor_force [N]``, ``restitution [-]``, ``contacts [-]``.

    Raises
    ------
    ParameterError
        For a missing or non-numeric column, or a value out of range: the message names
        the column and the first bad row; or an ``rtol`` outside [1e-14, 1e-3].

    Notes
    -----
    Each row is ``simulate_impact(Grain(mass=m2), Sensor(m1, k1, c1),
    HertzDamped(k_hertz, damping), v0, method="adaptive", rtol=rtol)`` with its
    default window. The kernel integrates the same steps as the single solver (the
    same compiled DOP853 pieces) and reads the peaks and the lobe on their dense output
    where :class:`~contactlab.ImpactResult` refines them from its output grid: at
    the same ``rtol`` the two agree to about 1e-15.

    Examples
    --------
    >>> import pandas as pd
    >>> from contactlab.batch import hertz_impacts
    >>> frame = pd.DataFrame({"m1 [kg]": [float("inf")], "k1 [N/m]": [float("inf")],
    ...     "c1 [N*s/m]": [0.0], "m2 [kg]": [5.0e-5], "k_hertz [N/m**1.5]": [1e7],
    ...     "damping [N*s/m**1.25]": [0.0], "v0 [m/s]": [2.0]})
    >>> round(float(hertz_impacts(frame)["restitution [-]"].iloc[0]), 6)
    1.0
    """
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    return solve_frame(frame, HERTZ_INPUTS, _solver(rtol), chunk=chunk, threads=threads)
