"""Keysight (Agilent) InfiniiVision CSV::

    x-axis,1,2
    second,Volt,Volt
    -999.00E-09,1.2500E-03,-3.1250E-03

Row 1 names the channels (``"1"``, ``"2"``; select them by name, ``channel="1"``), row 2
gives the units, and the numbers use engineering notation. The time column is kept as
written; time is relative to the trigger.
"""

from decimal import Decimal

import numpy as np

from contactlab.errors import ParameterError
from contactlab.traces.textblock import named_columns
from contactlab.traces.textwrite import write_text

__all__ = ["engineering", "parse_header", "sniff", "write"]


def sniff(head):
    """``x-axis,...`` first."""
    return head.cells(0)[:1] == ["x-axis"]


def parse_header(head):
    """Describe the data of a Keysight InfiniiVision CSV file.

    Returns
    -------
    Block
    """
    return named_columns(head, "keysight", 3)


def engineering(x):
    """``x`` in engineering notation with every digit of its shortest repr.

    The exponent is a multiple of 3 and the mantissa has at least two decimals, as
    Keysight writes (``-999.00E-09``); the string reads back as exactly ``x``.
    """
    x = float(x)
    if not np.isfinite(x):
        return repr(x)
    if x == 0:
        return "-0.00E+00" if np.signbit(x) else "0.00E+00"
    sign, digits, exponent = Decimal(repr(x)).as_tuple()
    leading = len(digits) + exponent - 1
    power = leading - leading % 3
    whole = leading - power + 1
    text = "".join(map(str, digits)).ljust(whole + 2, "0")
    return f"{'-' if sign else ''}{text[:whole]}.{text[whole:]}E{power:+03d}"


def write(path, trace, *, channel="1"):
    """Write a volt trace in the Keysight InfiniiVision CSV layout (engineering notation)."""
    if trace.unit != "V":
        raise ParameterError(f"this writer stores volts; the trace is in {trace.unit!r}")
    columns = [np.array([engineering(x) for x in a], dtype=object) for a in (trace.t, trace.values)]
    write_text(path, [f"x-axis,{channel}", "second,Volt"], columns)
