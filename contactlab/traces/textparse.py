"""Parsing a data block into float columns: a fast vectorised path and an exact line parser.

:func:`parse_block` parses only the data block with ``pandas.read_csv(engine="c")``
straight into float64 columns (correctly rounded, so written reprs read back bit for
bit). Anything it rejects (a non-numeric or missing cell, a wrong cell count, an
undecodable byte, a layout's own overrange token such as ``∞``), and any block that holds
the words ``true`` or ``false`` (pandas would read them as 1 and 0), goes through a
line-by-line parser that either reads it (special tokens, trailing blank lines) or raises
:class:`~contactlab.errors.TraceFormatError` naming the file and the 1-based line. The
slow path costs time only on files that need it.
"""

import csv
import math
import re

import numpy as np
import pandas as pd

from contactlab.traces import checks

__all__ = ["parse_block"]

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_WITH_UNIT = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*[A-Za-zµμ]+")
_COMMA_HINT = " (decimal commas split a number into two cells; decimal points needed)"
_BOOLEAN_WORDS = (b"true", b"false")
"""Words pandas' C parser turns into 1.0 and 0.0 (in any case) in a column made of them:
a data block that holds one goes to the line parser, which refuses them as not numbers."""
_INFINITIES = {
    "inf": math.inf,
    "+inf": math.inf,
    "-inf": -math.inf,
    "infinity": math.inf,
    "+infinity": math.inf,
    "-infinity": -math.inf,
}


def parse_block(head, block, offset, used):
    """Parse the used columns of a data block: fast and vectorised, or line by line when the
    fast path refuses.

    Parameters
    ----------
    head : Head
        The file's head (:mod:`contactlab.traces.texthead`).
    block : Block
        The layout's description of the block (:mod:`contactlab.traces.textblock`).
    offset : int
        Byte offset of the first data row in the content :meth:`Head.open_data` returns.
    used : sequence of Column
        The columns to read (time, then the channel).

    Returns
    -------
    list of numpy.ndarray
        One float64 array per used column.
    """
    indices = [c.index for c in used]
    options = {
        "header": None,
        "sep": block.delimiter,
        "engine": "c",
        "dtype": np.float64,
        "quoting": csv.QUOTE_NONE,
        "skip_blank_lines": False,
        "keep_default_na": False,
        "na_values": [""],
        "lineterminator": "\n",
        "encoding": head.data_encoding,
    }
    if block.n_fields is None and block.max_fields is None:
        options["usecols"] = sorted(set(indices))
    with head.open_data() as fh:
        fh.seek(offset)
        booleans = _scan_block(head, block, fh)
        fh.seek(offset)
        try:
            frame = None if booleans else pd.read_csv(fh, **options)
        except ValueError:  # pandas' ParserError, EmptyDataError and UnicodeDecodeError too
            frame = None
    if frame is None:
        return _parse_lines(head, block, offset, used)
    if block.n_fields is not None and frame.shape[1] != block.n_fields:
        return _parse_lines(head, block, offset, used)
    too_many = block.max_fields is not None and (
        frame.shape[1] > block.max_fields
        or frame.iloc[:, _last(block) + 1 :].notna().any(axis=None)
    )
    if too_many or frame.shape[1] <= max(indices):
        return _parse_lines(head, block, offset, used)
    arrays = [frame[i].to_numpy() for i in indices]
    if any(np.isnan(a).any() for a in arrays):
        return _parse_lines(head, block, offset, used)
    # Keep only the used columns alive (the frame's block may hold other channels).
    return [a if frame.shape[1] <= 2 else a.copy() for a in arrays]


def _last(block):
    """0-based index of the block's last column; cells after it must be empty."""
    return max(c.index for c in (block.time, *block.channels))


def _scan_block(head, block, fh):
    """One streaming pass over the rest of ``fh`` (1 MiB chunks, bounded memory): refuse a
    NUL byte (no text layout has one: a zero-filled tail, a binary file) and more rows than
    :data:`~contactlab.traces.checks.MAX_SAMPLES` (before anything is parsed), and say
    whether the block holds ``true`` or ``false`` in any case."""
    tail, booleans, lines = b"", False, 0
    while chunk := fh.read(1 << 20):
        nul = chunk.find(b"\x00")
        if nul >= 0:
            line = block.first_line + lines + chunk.count(b"\n", 0, nul)
            raise head.fail(line, "a NUL byte in the data (a zero-filled or binary tail)")
        lines += chunk.count(b"\n")
        if lines > checks.MAX_SAMPLES:
            raise head.fail(
                block.first_line + checks.MAX_SAMPLES,
                f"more than {checks.MAX_SAMPLES} rows of samples (the limit of one trace)",
            )
        text = tail + chunk.lower()
        booleans = booleans or any(word in text for word in _BOOLEAN_WORDS)
        tail = text[-4:]  # "false" may straddle two chunks
    return booleans


def _cell(token, specials):
    text = token.strip()
    if _NUMBER.fullmatch(text):
        return float(text)
    value = specials.get(text, _INFINITIES.get(text.casefold()))
    if value is not None:
        return value
    if not text:
        raise ValueError("missing cell")
    if _WITH_UNIT.fullmatch(text):
        raise ValueError(f"{text!r} carries a unit; units belong in the header (mixed units)")
    raise ValueError(f"{text!r} is not a number")


def _parse_lines(head, block, offset, used):
    """Parse the block line by line: slow, exact about where a fault lies."""
    columns = [[] for _ in used]
    blank = None
    with head.open_data() as fh:
        fh.seek(offset)
        for number, raw in enumerate(fh, start=block.first_line):
            text = raw.rstrip(b"\r\n").decode(head.data_encoding, errors="replace")
            if not text.strip():
                blank = blank or number
                continue
            if blank is not None:
                raise head.fail(blank, "blank line inside the data")
            cells = text.split(block.delimiter)
            if block.n_fields is not None and len(cells) != block.n_fields:
                raise head.fail(
                    number,
                    f"{len(cells)} cells where the header has {block.n_fields}"
                    + (_COMMA_HINT if len(cells) > block.n_fields else ""),
                )
            if block.max_fields is not None and any(c.strip() for c in cells[_last(block) + 1 :]):
                raise head.fail(
                    number,
                    f"a cell after the layout's last column is not empty{_COMMA_HINT}",
                )
            if block.max_fields is not None and len(cells) > block.max_fields:
                raise head.fail(
                    number,
                    f"{len(cells)} cells where the layout has at most {block.max_fields}"
                    f"{_COMMA_HINT}",
                )
            for out, column in zip(columns, used, strict=True):
                token = cells[column.index] if column.index < len(cells) else ""
                try:
                    out.append(_cell(token, block.specials))
                except ValueError as exc:
                    raise head.fail(number, f"column {column.name!r}: {exc}") from None
    if not columns[0]:
        raise head.fail(block.first_line, "no data rows after the header")
    return [np.array(c, dtype=np.float64) for c in columns]
