"""Units as trace files spell them, and their exact conversion to SI.

Instruments write units in many spellings: ``s``, ``ms``, ``(us)``, ``µs``, ``Second``,
``Volt``, ``mV``, ``Volts``. :func:`parse_unit` maps each to an SI base unit and a power of
ten, and :class:`Unit` converts arrays with a single correctly rounded multiplication or
division by an exact power of ten (``x / 1000`` rather than ``x * 1e-3``, whose factor is
not representable), so a value read in mV is within half an ulp of the volts it denotes.

Only units whose meaning is certain are accepted; anything else is reported by the
caller, never guessed.
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["SI_VALUE_UNITS", "Unit", "parse_unit"]

SI_VALUE_UNITS = ("V", "N", "A")
"""SI base units a trace's values may carry: volts, newtons, amperes (current probes)."""

_PREFIXES = {"": 0, "p": -12, "n": -9, "u": -6, "µ": -6, "μ": -6, "m": -3, "k": 3}
_SYMBOLS = {"s": "s", "V": "V", "N": "N", "A": "A"}
_WORDS = {
    "second": "s",
    "seconds": "s",
    "sec": "s",
    "volt": "V",
    "volts": "V",
    "newton": "N",
    "newtons": "N",
    "amp": "A",
    "amps": "A",
    "ampere": "A",
    "amperes": "A",
}


@dataclass(frozen=True)
class Unit:
    """A unit as written in a file, with its SI base and power of ten.

    A quantity ``x`` written in this unit is ``x * 10**exponent`` in the SI unit ``si``.
    """

    text: str
    """The unit as the file wrote it, without brackets, e.g. ``"mV"`` or ``"Second"``."""
    si: str
    """SI base unit: ``"s"``, ``"V"``, ``"N"`` or ``"A"``."""
    exponent: int
    """Power of ten from the written unit to the SI unit (``-3`` for ``mV``)."""

    @property
    def is_time(self):
        """Whether this is a unit of time."""
        return self.si == "s"

    def to_si(self, x):
        """Values in this unit converted to SI (a new array unless the unit is SI)."""
        return _scale(x, self.exponent)

    def from_si(self, x):
        """SI values converted to this unit (the inverse of :meth:`to_si`)."""
        return _scale(x, -self.exponent)


def _scale(x, exponent):
    if exponent == 0:
        return x
    factor = 10.0 ** abs(exponent)  # exact for |exponent| <= 22
    return np.multiply(x, factor) if exponent > 0 else np.divide(x, factor)


def parse_unit(text):
    """Parse a unit string such as ``"ms"``, ``"(mV)"``, ``"Volt"`` or ``"µs"``.

    Parameters
    ----------
    text : str
        The unit, optionally wrapped in one pair of brackets or parentheses.

    Returns
    -------
    Unit or None
        ``None`` when the spelling is not one this module knows for certain.
    """
    bare = text.strip()
    if len(bare) >= 2 and bare[0] + bare[-1] in ("()", "[]"):
        bare = bare[1:-1].strip()
    word = _WORDS.get(bare.lower())
    if word is not None:
        return Unit(bare, word, 0)
    for prefix, exponent in _PREFIXES.items():
        symbol = bare[len(prefix) :]
        if bare.startswith(prefix) and symbol in _SYMBOLS:
            return Unit(bare, _SYMBOLS[symbol], exponent)
    return None
