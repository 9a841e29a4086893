"""CSV tables safe to open in a spreadsheet (CSV injection, OWASP).

Every CSV table contactlab and dem_check write passes through :func:`spreadsheet_safe`
when it can hold text a user supplied (a file name, a metadata entry, a column of the
user's own batch table): a spreadsheet runs a cell starting with ``=``, ``+``, ``-``,
``@``, tab or carriage return as a formula (``=cmd|' /C calc'!A0``).
:func:`write_csv` writes such a table with every text cell quoted, so a line break
inside a cell (a carriage return in a file name) cannot split its row.
"""

import csv

import pandas as pd

from contactlab.entry_checks import check_instance

__all__ = ["FORMULA_STARTS", "spreadsheet_safe", "write_csv"]

FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
"""First characters that make a spreadsheet read a CSV cell as a formula (OWASP, CSV
injection)."""


def _neutral(cell):
    """``cell`` with a leading ``'`` if it is text starting with a formula character."""
    return "'" + cell if isinstance(cell, str) and cell.startswith(FORMULA_STARTS) else cell


def spreadsheet_safe(table):
    """A copy of ``table`` whose text cells cannot run as spreadsheet formulas.

    A text cell starting with one of :data:`FORMULA_STARTS` (a file named
    ``=HYPERLINK(...).csv``, a metadata entry, a text column of a batch table) gets a
    leading ``'``, which spreadsheets show as text; numbers are untouched (a negative
    number is a number, not text), and so are column names that are not text formulas.

    Parameters
    ----------
    table : pandas.DataFrame
        The table to write; left unchanged.

    Returns
    -------
    pandas.DataFrame
        The copy, same index, columns and numeric dtypes.

    Raises
    ------
    ParameterError
        ``table`` is not a DataFrame.
    """
    table = check_instance("table", table, pd.DataFrame).copy()
    for column in table.columns:
        if not pd.api.types.is_numeric_dtype(table[column]):
            table[column] = table[column].map(_neutral)
    table.columns = [_neutral(str(c)) for c in table.columns]
    return table


def write_csv(table, target, *, index=False, **options):
    """Write ``table`` as CSV, safe for spreadsheets and with every text cell quoted.

    The table goes through :func:`spreadsheet_safe`, then
    :meth:`pandas.DataFrame.to_csv` with ``quoting=csv.QUOTE_NONNUMERIC``: pandas' default
    minimal quoting leaves a carriage return inside a text cell unquoted, and every CSV
    reader then splits the row there (a file name holding one lost its row's values in
    the campaign's ``files.csv``). Numbers stay bare; a missing value is written ``""``,
    which :func:`pandas.read_csv` reads back as NaN.

    Parameters
    ----------
    table : pandas.DataFrame
        The table to write; left unchanged.
    target : str, path-like or file-like
        Where to write (a ``.gz`` suffix compresses, as in pandas).
    index : bool, default False
        Write the row labels as the first column.
    **options
        Further keywords of :meth:`pandas.DataFrame.to_csv` (not ``quoting``).

    Returns
    -------
    None
    """
    spreadsheet_safe(table).to_csv(target, index=index, quoting=csv.QUOTE_NONNUMERIC, **options)
