"""Running a batch: chunks on threads, the single solver for handed-back rows, the result.

The batch solvers (:mod:`contactlab.batch.linear`, :mod:`contactlab.batch.hertz`) share
everything but their kernel: the frame is checked (:func:`contactlab.batch.frame.check_frame`),
solved in chunks that bound the working memory, several at a time on threads (the
compiled kernels release Python's global interpreter lock), rows a kernel hands back
are solved by :func:`contactlab.simulate_impact` as an
:class:`~contactlab.config.ImpactConfig` (:func:`row_config`, :func:`single_impact`), and the
headline numbers are added to a copy of the frame (:data:`RESULT_COLUMNS`).
"""

import math
import os
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from contactlab.batch.frame import check_frame, chunk_bounds
from contactlab.bodies import Grain, Sensor
from contactlab.config import ImpactConfig
from contactlab.errors import ParameterError, RowFailedWarning
from contactlab.kernels.modal import STATUS_OK
from contactlab.plausibility import implausible_rows, internal
from contactlab.quantities import columns
from contactlab.validation import check_count

__all__ = [
    "CHUNKS_PER_THREAD",
    "DEFAULT_CHUNK",
    "ERROR_COLUMN",
    "RESULT_COLUMNS",
    "RESULT_NAMES",
    "check_threads",
    "fallback_row",
    "result_row",
    "row_config",
    "run_kernel",
    "single_impact",
    "solve_frame",
    "warn_implausible",
]

RESULT_NAMES = (
    "contact_time",
    "sensor_response_time",
    "peak_contact_force",
    "peak_sensor_force",
    "restitution",
    "contacts",
)
"""Quantities a batch solver adds (:mod:`contactlab.quantities`), in the order of its
kernel's outputs: attributes of :class:`contactlab.ImpactResult`."""

RESULT_COLUMNS = columns(*RESULT_NAMES)
"""Columns a batch solver adds, in the order of its kernel's outputs."""

ERROR_COLUMN = "error"
"""Column added when a row could not be solved: its reason (empty for solved rows)."""

DEFAULT_CHUNK = 100_000
"""Rows solved per call of a kernel: bounds the working memory (about 100 bytes a row
beyond the output columns) whatever the frame's length."""

CHUNKS_PER_THREAD = 4
"""Chunks per thread when several threads share a frame (rows differ in cost: the
scan follows the sensor's resonance, so a few chunks each keep the threads busy)."""


def check_threads(threads):
    """Threads to use: an int >= 1, or None for every core of this machine."""
    if threads is None:
        return os.cpu_count() or 1
    return check_count("threads", threads)


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


def warn_implausible(arrays, frame):
    """One :class:`~contactlab.errors.PlausibilityWarning` per quantity, naming the rows
    whose grain mass, impact speed or sensor lies outside what real ones span (walls,
    ``k1 = inf``, are not checked)."""
    m1, k1, c1 = arrays["m1 [kg]"], arrays["k1 [N/m]"], arrays["c1 [N*s/m]"]
    labels = frame.index
    implausible_rows("grain_mass", arrays["m2 [kg]"], labels, "m2 [kg]")
    implausible_rows("impact_velocity", arrays["v0 [m/s]"], labels, "v0 [m/s]")
    moving = np.isfinite(k1)
    with np.errstate(divide="ignore", invalid="ignore"):
        resonance = np.where(moving, np.sqrt(k1 / m1) / (2.0 * math.pi), np.inf)
        ratio = np.where(moving, c1 / (2.0 * np.sqrt(k1 * m1)), np.inf)
    implausible_rows("sensor_mass", np.where(moving, m1, np.inf), labels, "m1 [kg]")
    implausible_rows("sensor_resonance", resonance, labels, "sensor resonance [Hz]")
    implausible_rows("sensor_damping_ratio", ratio, labels, "sensor damping ratio [-]")


def single_impact(config, **options):
    """One set-up by :func:`contactlab.simulate_impact`: the six headline numbers, in the
    order of :data:`RESULT_COLUMNS`.

    Parameters
    ----------
    config : contactlab.config.ImpactConfig
        The set-up (:func:`row_config` makes one of a batch row).
    **options
        Keywords of :func:`contactlab.simulate_impact` (``method``, ``rtol``, ...).
    """
    with internal():
        return result_row(config.simulate(**options))


def result_row(result):
    """The numbers of :data:`RESULT_NAMES` of an :class:`~contactlab.ImpactResult`, in
    order (a tuple)."""
    return tuple(getattr(result, name) for name in RESULT_NAMES)


def row_config(m1, k1, c1, m2, law, v0):
    """The :class:`~contactlab.config.ImpactConfig` of one batch row (``k1 = inf``: an
    immovable wall; masses [kg], ``k1`` [N/m], ``c1`` [N*s/m], ``v0`` [m/s]). The frame
    was checked for plausibility as a whole: no warning per row here."""
    with internal():
        sensor = Sensor.rigid() if math.isinf(k1) else Sensor(mass=m1, stiffness=k1, damping=c1)
        return ImpactConfig(Grain.from_mass(m2), sensor, law, {"velocity": v0})


KERNEL_ERRORS = (ArithmeticError, ValueError, np.linalg.LinAlgError)
"""What a compiled kernel raises on a row it cannot take (an overflowing matrix, a zero
division): the chunk is then run row by row and only that row is handed back."""


def run_kernel(kernel, columns, args, out):
    """Run a compiled batch kernel on a chunk; return the rows to hand back (0-based).

    ``kernel(*columns, *args, out, status)`` fills ``out`` and a status per row. If it
    raises for the chunk, each row is run alone, and a row that raises again is handed
    back with the others whose status is not :data:`STATUS_OK`.
    """
    status = np.empty(len(out), dtype=np.int64)
    try:
        kernel(*columns, *args, out, status)
    except KERNEL_ERRORS:
        for i in range(len(out)):
            try:
                kernel(*(c[i : i + 1] for c in columns), *args, out[i : i + 1], status[i : i + 1])
            except KERNEL_ERRORS:
                status[i] = -1
    return np.flatnonzero(status != STATUS_OK)


def fallback_row(out, failures, row, m1, k1, c1, m2, law, v0, **options):
    """Solve one handed-back row by :func:`single_impact` into ``out``; if the single
    solver refuses or fails, write NaN and record why in ``failures[row]`` (0-based row
    of the frame), so that one unsolvable row never costs the others their numbers."""
    try:
        out[:] = single_impact(row_config(m1, k1, c1, m2, law, v0), **options)
    except (ValueError, ArithmeticError, RuntimeError, np.linalg.LinAlgError) as exc:
        out[:] = math.nan
        failures[row] = f"{type(exc).__name__}: {exc}"


def _solve_chunks(solve, arrays, results, chunk, threads, failures):
    """Solve every row of the checked arrays into ``results``, ``threads`` at a time."""
    rows = len(results)
    if threads > 1:
        chunk = max(1, min(chunk, math.ceil(rows / (CHUNKS_PER_THREAD * threads))))
    bounds = chunk_bounds(rows, chunk)
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        if threads == 1 or len(bounds) == 1:
            for lo, hi in bounds:
                solve(arrays, lo, hi, results[lo:hi], failures)
            return
        with ThreadPoolExecutor(max_workers=threads) as pool:
            jobs = [
                pool.submit(solve, arrays, lo, hi, results[lo:hi], failures) for lo, hi in bounds
            ]
            for job in jobs:
                job.result()


def solve_frame(frame, columns, solve, *, chunk=DEFAULT_CHUNK, threads=1, results=RESULT_COLUMNS):
    """Check a batch frame, solve it chunk by chunk, return it with the results added.

    Parameters
    ----------
    frame : pandas.DataFrame
        One row per impact.
    columns : sequence of contactlab.batch.frame.Column
        The input columns (``m1 [kg]`` and ``k1 [N/m]`` among them).
    solve : callable
        ``solve(arrays, lo, hi, out, failures)``: rows ``lo:hi`` of the checked arrays
        into ``out`` (hi - lo, 6); a row no solver can solve gets NaN there and its reason
        in ``failures`` (:func:`fallback_row`).
    chunk : int
        Rows solved at a time.
    threads : int or None
        Threads (None: every core).
    results : sequence of str, default :data:`RESULT_COLUMNS`
        Names of the columns ``solve`` fills, in order.

    Returns
    -------
    pandas.DataFrame
        A copy of ``frame`` with the ``results`` columns added. If a row could not be
        solved, its numbers are NaN, an ``error`` column gives its reason (empty for the
        other rows, which are all solved) and a :class:`RowFailedWarning` names the rows.
    """
    chunk = check_count("chunk", chunk)
    threads = check_threads(threads)
    arrays = check_frame(frame, columns, chunk)
    _check_sensor_pairs(arrays, frame)
    warn_implausible(arrays, frame)
    names, results = results, np.empty((len(frame), len(results)))
    failures = {}
    _solve_chunks(solve, arrays, results, chunk, threads, failures)
    out = frame.copy()
    for j, name in enumerate(names):
        out[name] = results[:, j]
    if failures:
        rows = sorted(failures)
        out[ERROR_COLUMN] = ""
        out.iloc[rows, out.columns.get_loc(ERROR_COLUMN)] = [failures[i] for i in rows]
        first = rows[0]
        warnings.warn(
            f"{len(rows)} of {len(frame)} rows could not be solved (NaN, reason in column "
            f"{ERROR_COLUMN!r}); row {first} (index {frame.index[first]!r}): {failures[first]}",
            RowFailedWarning,
            stacklevel=3,
        )
    return out
