"""The ``batch`` command: a CSV table of impacts, one per row, through a batch solver.

The table's columns are the batch solver's, named with their units (``m1 [kg]``,
``k1 [N/m]``, ...; ``docs/batch.md``); other columns are kept. A bad cell is named by its
file, line (the header is line 1) and column; a blank line is a bad row, not skipped.
"""

import sys
import time
from pathlib import Path

import pandas as pd

from contactlab.batch.rows import ERROR_COLUMN
from contactlab.errors import ParameterError
from contactlab.tables import write_csv

__all__ = ["BATCH_LAWS", "add_batch_parser", "read_table"]

BATCH_LAWS = ("linear", "hertz")
"""Laws of the ``batch`` command: linear (Kelvin-Voigt) and damped Hertz (Tsuji)."""


def _solver(law):
    from contactlab import batch

    if law == "linear":
        return batch.linear_impacts, batch.LINEAR_INPUTS
    return batch.hertz_impacts, batch.HERTZ_INPUTS


def read_table(path, columns):
    """Read a CSV table of impacts; rows are labelled with their line in the file.

    Parameters
    ----------
    path : str or Path
        CSV file, header on line 1, no multi-line fields.
    columns : sequence of contactlab.batch.frame.Column
        The columns the solver needs (checked for numbers here, for ranges by it).

    Returns
    -------
    pandas.DataFrame
        The table, indexed ``"line N"``.

    Raises
    ------
    ParameterError
        The file is missing or empty, or a needed column holds a cell that is not a
        number (named by file, line and column).
    """
    path = Path(path)
    if not path.is_file():
        raise ParameterError(f"table file not found: {path}")
    try:
        frame = pd.read_csv(path, skip_blank_lines=False)
    except pd.errors.EmptyDataError:
        raise ParameterError(f"{path}: the table is empty (a header line is needed)") from None
    frame.index = pd.Index([f"line {n}" for n in range(2, 2 + len(frame))])
    for column in columns:
        if column.name not in frame.columns:
            continue  # the solver names every missing column at once
        cells = frame[column.name]
        numbers = pd.to_numeric(cells, errors="coerce")
        bad = numbers.isna() & cells.notna()
        if bad.any():
            line = bad.idxmax()
            raise ParameterError(
                f"{path}, {line}: column {column.name!r} holds {cells[line]!r}, not a number"
            )
        frame[column.name] = numbers.astype(float)
    return frame


def _batch(args):
    solve, columns = _solver(args.law)
    options = {"threads": args.threads}
    if args.rtol is not None:
        if args.law != "hertz":
            raise ParameterError("--rtol applies to --law hertz only (linear impacts are exact)")
        options["rtol"] = args.rtol
    frame = read_table(args.table, columns)
    from contactlab.batch.warm_up import warm_up

    compile_seconds = warm_up()  # compiled once, then loaded: timed apart from the solve
    start = time.perf_counter()
    try:
        solved = solve(frame, **options)
    except ParameterError as exc:
        raise ParameterError(f"{args.table}: {exc}") from None
    seconds = time.perf_counter() - start
    # The user's own text columns are copied through: formula cells neutralised, text quoted.
    write_csv(solved, args.out if args.out else sys.stdout)
    where = f"wrote {args.out}: " if args.out else ""
    failed = int(solved[ERROR_COLUMN].ne("").sum()) if ERROR_COLUMN in solved else 0
    print(
        f"{where}{len(solved) - failed} impacts solved in {seconds:.2f} s (solvers compiled or "
        f"loaded before, in {compile_seconds:.2f} s)",
        file=sys.stderr,
    )
    if failed:
        print(
            f"{failed} of {len(solved)} rows could not be solved: NaN in their results, the "
            f"reason in the {ERROR_COLUMN!r} column",
            file=sys.stderr,
        )
        return 1
    return 0


def add_batch_parser(sub):
    """The ``batch`` command."""
    p = sub.add_parser(
        "batch",
        help="many impacts from a CSV table (one per row) with the batch solvers",
        description="Solve one impact per row of a CSV table and add contact_time [s], "
        "sensor_response_time [s], peak_contact_force [N], peak_sensor_force [N], restitution [-] "
        "and contacts [-]. Columns: m1 [kg], k1 [N/m] (inf: a wall), c1 [N*s/m], m2 [kg], "
        "v0 [m/s], and k2 [N/m], c2 [N*s/m] (linear) or k_hertz [N/m**1.5], "
        "damping [N*s/m**1.25] (hertz).",
    )
    p.add_argument("table", help="CSV file, header on line 1, one impact per row")
    p.add_argument("--law", choices=BATCH_LAWS, required=True, help="contact law of every row")
    p.add_argument("--out", metavar="CSV", help="write the result here (default: stdout)")
    p.add_argument("--threads", type=int, help="threads (default: every core)")
    p.add_argument("--rtol", type=float, help="integrator tolerance, hertz (default 1e-9)")
    p.set_defaults(func=_batch)
