"""PicoScope CSV::

    Time,Channel A,Channel B
    (ms),(mV),(mV)

    -5.00000000,0.12345678,-0.98765432
    -4.99200000,∞,-0.98000000

Units in parentheses on row 2 (``ms``/``us``/``ns``/``s`` and ``mV``/``V``), a blank line,
then the data. Overrange samples are written as ``∞``/``-∞`` (or ``Infinity``/
``-Infinity``): they are kept as ``inf`` and their indices listed in
``metadata["overrange"]``, never dropped. The time column is kept as written (relative
to the trigger).
"""

import math
import re

import numpy as np

from contactlab.traces.textblock import named_columns
from contactlab.traces.textwrite import output_units, write_text
from contactlab.validation import check_choice

__all__ = ["OVERRANGE_TOKENS", "parse_header", "sniff", "write"]

OVERRANGE_TOKENS = {"∞": math.inf, "+∞": math.inf, "-∞": -math.inf}
"""PicoScope's overrange cells besides the ``Infinity`` spellings pandas reads itself."""

_PARENTHESISED = re.compile(r"\(.*\)")


def sniff(head):
    """``Time,...`` then a row of parenthesised units."""
    units = head.cells(1)
    return head.cells(0)[:1] == ["Time"] and all(_PARENTHESISED.fullmatch(u) for u in units)


def parse_header(head):
    """Describe the data of a PicoScope CSV file.

    Returns
    -------
    Block
    """
    first = 2
    while first < len(head.lines) and not head.lines[first].strip():
        first += 1
    return named_columns(head, "picoscope", first + 1, specials=OVERRANGE_TOKENS)


def write(path, trace, *, time_unit="ms", value_unit="mV", channel="Channel A", infinity="∞"):
    """Write a trace in the PicoScope CSV layout.

    Parameters
    ----------
    path : str or os.PathLike
    trace : Trace
    time_unit, value_unit : str
        Units of the columns (``"ms"``, ``"us"``; ``"mV"``, ``"V"``).
    channel : str, default "Channel A"
    infinity : {"∞", "Infinity"}
        How overrange (infinite) samples are written; ``-`` is prefixed for negative ones.
    """
    check_choice("infinity", infinity, ("∞", "Infinity"))  # the spellings the reader knows
    t_unit, v_unit = output_units(trace, time_unit, value_unit)
    values = v_unit.from_si(trace.values)
    if np.isinf(values).any():
        text = values.astype(str).astype(object)
        text[values == np.inf] = infinity
        text[values == -np.inf] = "-" + infinity
        values = text
    header = [f"Time,{channel}", f"({t_unit.text}),({v_unit.text})", ""]
    write_text(path, header, [t_unit.from_si(trace.t), values])
