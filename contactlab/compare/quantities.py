"""The compared quantities, their units, error bases and default tolerances.

=======================  ======  ==========================  ===========================
quantity                 unit    error measured as           default tolerance
=======================  ======  ==========================  ===========================
contact_time             s       relative, ``(a - b) / b``   0.005
peak_contact_force       N       relative                    0.01
peak_sensor_force        N       relative                    0.01
sensor_response_time     s       relative                    0.01
restitution              -       absolute, ``a - b``         0.01
waveform_rms_error       N       relative to b's S1 peak     0.02
waveform_max_error       N       relative to b's S1 peak     0.05
=======================  ======  ==========================  ===========================

``b`` is the reference (the model). The tolerances are sized for the engine bench at its
default step (errors of 0.1-0.3 %, restitution low by ``~k2 dt`` / 3; see
``docs/dem_check.md``); a measured trace with noise needs looser ones, passed by name
(:func:`noise_tolerances` widens them by the trace's noise).
"""

import difflib
from dataclasses import dataclass

from contactlab import quantities as vocabulary
from contactlab.errors import ParameterError
from contactlab.validation import check_number

__all__ = [
    "DEFAULT_TOLERANCES",
    "QUANTITIES",
    "Quantity",
    "checked_tolerances",
    "merged_tolerances",
    "noise_tolerances",
]


@dataclass(frozen=True)
class Quantity:
    """One compared quantity.

    Attributes
    ----------
    unit : str
        SI unit of the values and of ``abs_error``.
    basis : {"relative", "absolute", "peak"}
        What the tolerance bounds: ``|a - b| / |b|``, ``|a - b|``, or an error over the
        peak of b's sensor signal.
    tolerance : float
        Default tolerance.
    reason : str
        Why the default has that size.
    """

    unit: str
    basis: str
    tolerance: float
    reason: str


def _compared(name, basis, tolerance, reason):
    """A table entry; the unit is the vocabulary's (:mod:`contactlab.quantities`)."""
    return name, Quantity(vocabulary.quantity(name).unit, basis, tolerance, reason)


QUANTITIES = dict(
    [
        _compared(
            "contact_time",
            "relative",
            0.005,
            "engine at 500 steps per contact: 0.1-0.2 %; measured: n/a",
        ),
        _compared(
            "peak_contact_force",
            "relative",
            0.01,
            "engine at its default step: 0.1-0.3 % (first-order in dt)",
        ),
        _compared(
            "peak_sensor_force",
            "relative",
            0.01,
            "engine at its default step: 0.1-0.2 % (first-order in dt)",
        ),
        _compared(
            "sensor_response_time",
            "relative",
            0.01,
            "the lobe's ends are read on the step grid: ~0.2 %",
        ),
        _compared(
            "restitution",
            "absolute",
            0.01,
            "implicit contact damping k2 dt lowers it by ~0.003 at 1e-7 s",
        ),
        _compared(
            "waveform_rms_error",
            "peak",
            0.02,
            "peak and phase errors of 0.1-0.3 % give an RMS error ~0.5 %",
        ),
        _compared(
            "waveform_max_error",
            "peak",
            0.05,
            "the largest difference sits on the steepest slope: ~1 %",
        ),
    ]
)
"""The compared quantities, in table order."""

DEFAULT_TOLERANCES = {name: q.tolerance for name, q in QUANTITIES.items()}
"""Default tolerance of each quantity (see :data:`QUANTITIES` for the basis)."""


def checked_tolerances(tolerances):
    """``tolerances`` (None: none) as a dict after checking each name is a quantity of
    :data:`QUANTITIES` (an unknown one raises listing the valid ones) and each value a
    finite number >= 0 (on the quantity's basis)."""
    if tolerances is not None and not isinstance(tolerances, dict):
        raise ParameterError(
            f"tolerances must be a dict of quantity name -> tolerance; got {tolerances!r}"
        )
    checked = {}
    for name, value in (tolerances or {}).items():
        if name not in DEFAULT_TOLERANCES:
            near = difflib.get_close_matches(str(name), DEFAULT_TOLERANCES, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise ParameterError(
                f"unknown tolerance {name!r}{hint}; valid names: {', '.join(DEFAULT_TOLERANCES)}"
            )
        checked[name] = check_number(f"tolerance {name}", value, low=0.0, low_open=False)
    return checked


def merged_tolerances(tolerances):
    """Defaults updated with ``tolerances``; unknown names raise listing the valid ones."""
    return {**DEFAULT_TOLERANCES, **checked_tolerances(tolerances)}


def noise_tolerances(noise, peak):
    """Default tolerances widened for a measured signal with baseline noise.

    The largest sample near a noisy peak overshoots the true peak by about two to three
    standard deviations, and the largest of thousands of noisy differences reaches four
    to five; the RMS difference contains the noise itself. So, on the bases of
    :data:`QUANTITIES`: ``peak_sensor_force`` gets ``+ 4 noise / peak``,
    ``waveform_max_error`` ``+ 5 noise / peak`` and ``waveform_rms_error``
    ``+ 2 noise / peak``; the others keep their defaults.

    Parameters
    ----------
    noise : float
        Standard deviation of the trace's baseline [N].
    peak : float
        Peak of the reference sensor signal [N], > 0.

    Returns
    -------
    dict
        Tolerance by quantity name.
    """
    noise = check_number("noise", noise, low=0.0, low_open=False, unit="N")
    peak = check_number("peak", peak, low=0.0, unit="N")
    widen = {"peak_sensor_force": 4.0, "waveform_max_error": 5.0, "waveform_rms_error": 2.0}
    return {
        name: tolerance + widen.get(name, 0.0) * noise / peak
        for name, tolerance in DEFAULT_TOLERANCES.items()
    }
