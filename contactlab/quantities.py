"""One vocabulary: every quantity's name, unit and meaning, defined once.

Results (:class:`contactlab.ImpactResult`, :class:`contactlab.ObliqueResult`, the DEM
engines' results), the batch frames, the study's tables, the campaign's tables and the
comparisons all name a quantity the same way, and a table's column is ``"name [unit]"``
(:func:`column`), so ``contact_time [s]`` is one thing wherever it appears.

A name that was once used for the same thing is kept in :data:`DEPRECATED` and still
read by :func:`column` and :func:`quantity`, with a :class:`DeprecationWarning` naming
the new one; tables are written with the new names only.

>>> column("contact_time")
'contact_time [s]'
>>> QUANTITIES["peak_sensor_force"].unit
'N'
"""

import difflib
import warnings
from dataclasses import dataclass

from contactlab.errors import ParameterError

__all__ = ["DEPRECATED", "QUANTITIES", "Quantity", "column", "columns", "quantity"]


@dataclass(frozen=True)
class Quantity:
    """One quantity of the vocabulary.

    Attributes
    ----------
    name : str
        Its name in code and tables (an attribute of a result, a column's stem).
    unit : str
        SI unit (``"-"`` for a ratio or a count).
    meaning : str
        What it is, in one line.
    """

    name: str
    unit: str
    meaning: str

    @property
    def column(self):
        """The column name: ``"name [unit]"``."""
        return f"{self.name} [{self.unit}]"


def _vocabulary(*entries):
    return {name: Quantity(name, unit, meaning) for name, unit, meaning in entries}


QUANTITIES = _vocabulary(
    # a normal impact's signals (DESIGN.md: x along the grain's travel, S2 >= 0)
    ("t", "s", "time from the first touch"),
    ("contact_force", "N", "contact force S2 between grain and sensor (>= 0)"),
    ("sensor_force", "N", "sensor signal S1 = k1 x1 + c1 v1"),
    ("x1", "m", "sensor displacement"),
    ("v1", "m/s", "sensor velocity"),
    ("x2", "m", "grain displacement"),
    ("v2", "m/s", "grain velocity"),
    # a normal impact's headline numbers
    ("velocity", "m/s", "grain speed towards the sensor at the touch"),
    ("contact_time", "s", "duration of the first contact (exact event times)"),
    ("peak_contact_force", "N", "largest contact force S2 in the first contact"),
    (
        "sensor_response_time",
        "s",
        "duration of the sensor signal's first main lobe, read as an experimenter would",
    ),
    ("peak_sensor_force", "N", "largest sensor signal S1 in its first main lobe"),
    ("impulse", "N*s", "integral of the contact force S2 over time"),
    ("restitution", "-", "rebound speed over impact speed (normal components)"),
    ("rebound_velocity", "m/s", "grain speed away from the sensor after the contact"),
    ("contacts", "-", "number of contacts (a bounce back onto the sensor adds one)"),
    ("energy_balance", "J", "energy in minus energy out and dissipated: zero when exact"),
    ("waveform_rms_error", "N", "RMS difference of two aligned sensor signals"),
    ("waveform_max_error", "N", "largest difference of two aligned sensor signals"),
    # an oblique impact
    ("normal_force", "N", "normal contact force (>= 0)"),
    ("tangential_force", "N", "tangential contact force on the grain"),
    ("angle", "rad", "angle of incidence from the surface normal"),
    ("spin", "rad/s", "grain angular velocity at the touch"),
    (
        "tangential_velocity",
        "m/s",
        "tangential velocity of the grain's centre (a signal; as a number, after the contact)",
    ),
    (
        "angular_velocity",
        "rad/s",
        "grain angular velocity (a signal; as a number, after the contact)",
    ),
    ("slip", "m/s", "contact-point slip vt - R w (R - d with the contact lever arm)"),
    ("rebound_angle", "rad", "angle of the centre's rebound velocity from the normal"),
    ("tangential_restitution", "-", "contact-point slip after over before"),
    ("peak_normal_force", "N", "largest normal contact force"),
    ("peak_tangential_force", "N", "largest magnitude of the tangential force"),
    # the study's errors: how far the sensor's reading is from the contact's truth
    ("time_error", "%", "sensor_response_time over contact_time, minus one"),
    ("force_error", "%", "peak_sensor_force over peak_contact_force, minus one"),
    # a measured impact (campaigns)
    ("onset", "s", "time the signal leaves its baseline noise"),
    ("onset_uncertainty", "s", "standard deviation of a fitted onset under the record's noise"),
    ("noise", "N", "standard deviation of the signal's baseline"),
    ("significance", "-", "peak signal over baseline noise"),
    ("velocity_change", "m/s", "impulse over grain mass: (1 + e) v"),
    # a set-up's bodies and contact (the batch frames' input columns)
    ("m1", "kg", "sensor mass (inf: an immovable wall)"),
    ("k1", "N/m", "sensor stiffness (inf: an immovable wall)"),
    ("c1", "N*s/m", "sensor damping"),
    ("m2", "kg", "grain mass"),
    ("k2", "N/m", "linear contact stiffness (LinearViscoelastic.stiffness)"),
    ("c2", "N*s/m", "linear contact damping (LinearViscoelastic.damping)"),
    ("k_hertz", "N/m**1.5", "Hertz stiffness kH of F = kH d**1.5"),
    ("damping", "N*s/m**1.25", "Hertz damping eta of F = kH d**1.5 + eta d**0.25 d'"),
    ("v0", "m/s", "grain speed towards the sensor at the touch (a batch row's velocity)"),
    ("radius", "m", "grain radius (the tangential force's lever arm)"),
    ("k_mindlin", "N/m**1.5", "Mindlin's tangential stiffness coefficient: kt = k_mindlin sqrt(d)"),
    ("friction", "-", "Coulomb friction coefficient mu"),
    # an oblique impact's other rebound numbers (the batch's oblique frame)
    ("contact_rebound_angle", "rad", "angle of the contact point's rebound velocity"),
    ("phases", "-", "number of stick and slide phases of the contact"),
)
"""The vocabulary: name -> :class:`Quantity`."""

DEPRECATED = {
    "response_time": "sensor_response_time",
    "peak_signal": "peak_sensor_force",
}
"""Old names of the same quantities -> the name to use (read with a DeprecationWarning)."""


def quantity(name):
    """The :class:`Quantity` called ``name`` (an old name of :data:`DEPRECATED` warns).

    Raises
    ------
    ParameterError
        For a name not in the vocabulary, suggesting the nearest.
    """
    return _lookup(name)


def _lookup(name, stacklevel=3):
    """:func:`quantity`; ``stacklevel`` points the warning at the public caller's caller."""
    if not isinstance(name, str):
        raise ParameterError(f"a quantity's name must be text (str); got {name!r}")
    if name in DEPRECATED:
        new = DEPRECATED[name]
        warnings.warn(
            f"the quantity {name!r} is now called {new!r} (contactlab.quantities)",
            DeprecationWarning,
            stacklevel=stacklevel,
        )
        name = new
    if name not in QUANTITIES:
        near = difflib.get_close_matches(str(name), QUANTITIES, n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise ParameterError(f"unknown quantity {name!r}{hint}; see contactlab.quantities")
    return QUANTITIES[name]


def column(name):
    """The column name ``"name [unit]"`` of a quantity, e.g. ``contact_time [s]``."""
    return _lookup(name, stacklevel=4).column


def columns(*names):
    """Column names of several quantities, in order (a tuple)."""
    return tuple(_lookup(name, stacklevel=4).column for name in names)
