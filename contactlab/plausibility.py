"""Ranges that real grains, seeds and force sensors span, and the checks that use them.

A value outside its range is legal but unusual: :func:`check_plausible` issues a
:class:`~contactlab.errors.PlausibilityWarning` whose message names the likely unit slip
("diameter = 5 m is outside ...; did you mean 0.005 m (5 given in mm)?"). Impossible
values (not a number, zero or negative where a size must be positive, a Poisson ratio
outside (-1, 0.5]) raise :class:`~contactlab.errors.ParameterError` in the validators of
:mod:`contactlab.validation`; values beyond the ranges here are only warned about,
since DEM practice scales densities and moduli by 1000 on purpose (the Chung & Ooi
test 8 variants in :mod:`contactlab.benchmarks.chung_ooi`). The table with its sources
is ``docs/plausibility.md``; this module is its single source of numbers.

Code inside the package that calls a public entry with values it made itself (a wall
impact for a law's restitution, the rows a batch solver hands back, a fit's trial
velocities) runs inside :func:`internal`, so the user is warned once, where the value
entered, and not again on every internal call.
"""

import contextlib
import contextvars
import os
import sys
import warnings
from dataclasses import dataclass

import numpy as np

from contactlab.errors import ParameterError, PlausibilityWarning
from contactlab.validation import check_choice, check_number, check_samples, check_text

__all__ = [
    "RANGES",
    "Range",
    "check_plausible",
    "implausible_rows",
    "internal",
    "likely_slips",
]


@dataclass(frozen=True)
class Range:
    """What real objects span for one quantity, in SI units.

    Attributes
    ----------
    what : str
        The objects, for messages ("grains and seeds").
    unit : str
        SI unit of the value.
    low, high : float
        The plausible range [unit]; outside it a :class:`PlausibilityWarning`.
    slips : tuple of (float, str)
        Likely slips: ``(factor, unit typed)``; ``value * factor`` is the SI value had the
        number been typed in that unit (5 typed meaning mm: factor 1e-3).
    source : str
        Where the range comes from (the table of ``docs/plausibility.md``).
    """

    what: str
    unit: str
    low: float
    high: float
    slips: tuple = ()
    source: str = ""


RANGES = {
    "grain_diameter": Range(
        "grains, seeds and calibration balls",
        "m",
        0.1e-3,
        50e-3,
        ((1e-3, "mm"), (1e-2, "cm"), (1e-6, "um")),
        source="fine sand 0.1 mm; rapeseed 1.6-2.0 mm to maize 6.2-7.6 mm (species presets); beans "
        "and calibration balls up to 25-50 mm",
    ),
    "grain_density": Range(
        "grains, seeds and calibration balls",
        "kg/m^3",
        200.0,
        16000.0,
        ((1e3, "g/cm^3"),),
        source="oilseeds and hulled seeds 300-1500 (species presets: 1085-1455), quartz 2650, "
        "steel balls 7850, tungsten carbide 15600",
    ),
    "grain_mass": Range(
        "grains, seeds and calibration balls",
        "kg",
        1e-10,
        1.0,
        ((1e-3, "g"), (1e-6, "mg")),
        source="the diameter and density ranges: a 0.1 mm sand grain (1.4e-9 kg) to a 50 mm "
        "steel ball (0.51 kg), with a decade of margin below",
    ),
    "youngs_modulus": Range(
        "grains, seeds and calibration balls",
        "Pa",
        0.5e6,
        7e11,
        ((1e6, "MPa"), (1e9, "GPa")),
        source="moist rapeseed 'several MPa', seeds 40-600 MPa (shared/notes/species-data.md), "
        "glass 70 GPa, steel 210 GPa, tungsten carbide 600-700 GPa",
    ),
    "shear_modulus": Range(
        "grains, seeds and calibration balls",
        "Pa",
        0.2e6,
        3e11,
        ((1e6, "MPa"), (1e9, "GPa")),
        source="the Young's modulus range over 2 (1 + nu), nu in 0.1-0.5",
    ),
    "sensor_resonance": Range(
        "force sensors",
        "Hz",
        1e3,
        500e3,
        ((1e3, "kHz"),),
        source="force plates about 1-5 kHz; commercial piezoelectric impact sensors 20-70 kHz; "
        "the paper studies 20-200 kHz (Keska et al. 2021); small quartz cells to a few 100 kHz",
    ),
    "sensor_mass": Range(
        "force sensors",
        "kg",
        1e-5,
        10.0,
        ((1e-3, "g"),),
        source="a 3 mm x 0.2 mm steel cap (11 mg) to a force plate's top plate (kilograms); "
        "the paper's disc 1.233 g",
    ),
    "sensor_damping_ratio": Range(
        "force sensors",
        "-",
        0.0,
        1.0,
        ((1e-2, "%"),),
        source="quartz sensors 0.01-0.05; the paper's software screen implies 0.8; above 1 the "
        "sensor is over-damped and rings no more",
    ),
    "disc_diameter": Range(
        "sensor discs",
        "m",
        1e-3,
        0.3,
        ((1e-3, "mm"), (1e-2, "cm")),
        source="impact caps of a few mm to force-plate tops of 0.3 m; the paper's disc 10 mm",
    ),
    "disc_thickness": Range(
        "sensor discs",
        "m",
        0.1e-3,
        50e-3,
        ((1e-3, "mm"), (1e-2, "cm")),
        source="0.1 mm foils to 50 mm plates; the paper's disc 2 mm",
    ),
    "impact_velocity": Range(
        "grain impacts",
        "m/s",
        0.05,
        50.0,
        ((1e-2, "cm/s"), (1e-3, "mm/s"), (1 / 3.6, "km/h")),
        source="a 0.13 mm drop (0.05 m/s) to pneumatic conveying and throwers (20-50 m/s); the "
        "paper 0.5-10 m/s; the traces of shared/notes/species-data.md 0.17-8.8 m/s",
    ),
    "sensitivity": Range(
        "force sensors with their amplifiers",
        "V/N",
        1e-5,
        10.0,
        ((1e-3, "mV/N"), (1e-6, "uV/N")),
        source="IEPE force sensors about 0.1-100 mV/N (e.g. 11.24 mV/N, data/traces); charge "
        "amplifiers scale a few pC/N to at most volts per newton",
    ),
}
"""Every quantity's range; ``docs/plausibility.md`` shows this table with its sources."""

_PACKAGES = tuple(
    os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), name) + os.sep
    for name in ("contactlab", "dem_check")
)


def _caller_level():
    """``stacklevel`` of the first frame outside the two packages: the warning points at
    the user's line, however deep inside the package the check ran."""
    frame, level = sys._getframe(1), 1
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGES):
        frame, level = frame.f_back, level + 1
    return level


def _number(x):
    """``x`` to 4 significant digits, without a forced exponent (40000, 0.005, 2e+08)."""
    return f"{float(f'{x:.4g}'):g}"


_QUIET = contextvars.ContextVar("contactlab_plausibility_quiet", default=False)


@contextlib.contextmanager
def internal():
    """Inside this block the checks do not warn: the values were made by the package."""
    token = _QUIET.set(True)
    try:
        yield
    finally:
        _QUIET.reset(token)


def likely_slips(key, value):
    """The readings of ``value`` under the quantity's likely unit slips that fall in range.

    Parameters
    ----------
    key, value
        As for :func:`check_plausible`: the range's key, and the value as given in the
        range's SI unit.

    Returns
    -------
    list of (float, str)
        ``(SI value, unit the number was probably typed in)`` for every slip whose reading
        lies inside the plausible range.
    """
    spec = _spec(key)
    value = check_number("value", value)
    return [
        (value * factor, unit)
        for factor, unit in spec.slips
        if spec.low <= value * factor <= spec.high
    ]


def _spec(key):
    """The :data:`RANGES` entry of ``key``; an unknown key is a ParameterError listing them."""
    return RANGES[check_choice("key", key, tuple(RANGES))]


def _message(key, name, value):
    spec = RANGES[key]
    text = (
        f"{name} = {value:g} {spec.unit} is outside what real {spec.what} span "
        f"({_number(spec.low)} to {_number(spec.high)} {spec.unit})"
    )
    slips = likely_slips(key, value)
    if slips:
        readings = " or ".join(
            f"{_number(si)} {spec.unit} ({value:g} given in {u})" for si, u in slips
        )
        text += f"; did you mean {readings}?"
    return text + " (docs/plausibility.md)"


def check_plausible(key, value, name=None):
    """Warn when ``value`` lies outside the range real objects span; return it.

    Parameters
    ----------
    key : str
        A key of :data:`RANGES` (``"grain_diameter"``, ``"impact_velocity"``, ...).
    value : float
        A finite number, in SI units.
    name : str, optional
        The parameter's name in the message (default: ``key``).

    Returns
    -------
    float
        ``value``, unchanged: nothing is clipped.

    Raises
    ------
    ParameterError
        An unknown ``key``, or a ``value`` that is not a finite real number.

    Warns
    -----
    PlausibilityWarning
        Outside the plausible range, with the likely unit slip when there is one.
    """
    spec = _spec(key)
    name = key if name is None else check_text("name", name)
    check_number(f"value of {name}", value)
    if not _QUIET.get() and not spec.low <= value <= spec.high:
        warnings.warn(_message(key, name, value), PlausibilityWarning, stacklevel=_caller_level())
    return value


def implausible_rows(key, values, labels, name=None):
    """One warning for every row of a table whose value lies outside the range.

    Parameters
    ----------
    key : str
        A key of :data:`RANGES`.
    values : array_like of float
        One value per row [SI unit of the range]; infinite values (a wall) are not checked.
    labels : sequence
        The rows' labels, named in the message.
    name : str, optional
        The column's name in the message.

    Returns
    -------
    list
        The labels of the rows outside the range (one warning names them all).

    Raises
    ------
    ParameterError
        An unknown ``key``; ``values`` not a 1-D array of numbers or holding NaN; or
        ``labels`` not one per value.
    """
    spec = _spec(key)
    values = check_samples("values", values, finite=False)
    if np.isnan(values).any():
        raise ParameterError(f"values must be numbers or inf (a wall); got NaN in {key!r}")
    try:
        count = len(labels)
    except TypeError:
        count = None
    if count != values.size:
        raise ParameterError(
            f"labels must hold one label per value ({values.size}); got {labels!r}"
        )
    name = key if name is None else check_text("name", name)
    outside = np.isfinite(values) & ((values < spec.low) | (values > spec.high))
    rows = [labels[i] for i in np.flatnonzero(outside)]
    if rows and not _QUIET.get():
        shown = ", ".join(str(r) for r in rows[:5]) + (" ..." if len(rows) > 5 else "")
        first = int(np.flatnonzero(outside)[0])
        warnings.warn(
            f"{len(rows)} row(s) ({shown}): {_message(key, name, float(values[first]))}"
            + (" in the first of them" if len(rows) > 1 else ""),
            PlausibilityWarning,
            stacklevel=_caller_level(),
        )
    return rows
