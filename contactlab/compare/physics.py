"""Is a measured impact physically possible for the grain? Bounds from closed forms.

A grain of mass ``m`` striking at a speed ``v`` in ``[v_low, v_high]`` changes its
velocity by ``(1 + e) v`` with a restitution ``e`` in ``[0, 1]``, so the impulse it gives
the sensor, over its mass, lies in ``[v_low, 2 v_high]``. Its contact force cannot exceed
that of the stiffest contact it could make: an elastic Hertz impact of a rigid sphere of
its radius on a steel face (``E* = 210 GPa / (1 - 0.3**2) = 231 GPa``) at ``v_high``,
``F_max = kH d_max**1.5`` (:func:`contactlab.analytic.hertz_max_force`); a sensor's
signal rings above the force it carries by at most a factor 2 (a step into an undamped
oscillator), which the bound allows for. Real grains are softer by orders of magnitude,
so a reading beyond these bounds is a unit slip (a sensitivity in mV/N given as V/N, a
diameter in mm given as m) or a wrong set-up, never a measurement to believe.
"""

import math

from contactlab.analytic import hertz_max_force, hertz_stiffness
from contactlab.plausibility import RANGES
from contactlab.validation import check_number

__all__ = ["SIGNAL_OVERSHOOT", "STIFFEST_CONTACT_MODULUS", "impact_limits", "physics_problems"]

STIFFEST_CONTACT_MODULUS = 210e9 / (1.0 - 0.3**2)
"""Contact modulus of a rigid sphere on a steel face [Pa] (E = 210 GPa, nu = 0.3)."""

SIGNAL_OVERSHOOT = 2.0
"""Largest ratio of a sensor signal (or a force reconstructed from it) to the force it
carries [-]: a step into an undamped oscillator."""


def impact_limits(grain, speeds=None):
    """Velocity change and peak force that impacts of ``grain`` can produce.

    Parameters
    ----------
    grain : contactlab.Grain
        Its mass [kg] and radius [m] are used.
    speeds : (float, float), optional
        Range of impact speeds [m/s]; default the plausible range of
        :data:`contactlab.plausibility.RANGES` (0.05-50 m/s).

    Returns
    -------
    dict
        ``velocity_change [m/s]``: (low, high); ``peak_force [N]``: the largest force
        signal, the overshoot :data:`SIGNAL_OVERSHOOT` included.
    """
    spec = RANGES["impact_velocity"]
    low, high = (spec.low, spec.high) if speeds is None else speeds
    low = check_number("speeds[0]", low, low=0.0, unit="m/s")
    high = check_number("speeds[1]", high, low=low, low_open=False, unit="m/s")
    stiffest = hertz_stiffness(STIFFEST_CONTACT_MODULUS, grain.radius)
    return {
        "velocity_change [m/s]": (low, 2.0 * high),
        "peak_force [N]": SIGNAL_OVERSHOOT * hertz_max_force(stiffest, grain.mass, high),
    }


def physics_problems(grain, peak_force, velocity_change, speeds=None):
    """What in one measured impact no impact of ``grain`` can produce (empty: plausible).

    Parameters
    ----------
    grain : contactlab.Grain
    peak_force : float
        Peak of the measured signal or reconstructed force [N].
    velocity_change : float
        Measured impulse over the grain's mass [m/s].
    speeds : (float, float), optional
        Range of impact speeds [m/s] (see :func:`impact_limits`).

    Returns
    -------
    list of str
        One sentence per quantity out of bounds, naming the bound and the likely cause.
    """
    limits = impact_limits(grain, speeds)
    low, high = limits["velocity_change [m/s]"]
    problems = []
    if math.isfinite(velocity_change) and not low <= velocity_change <= high:
        problems.append(
            f"velocity change {velocity_change:.3g} m/s (impulse / grain mass "
            f"{grain.mass:.3g} kg) is outside the {low:g}-{high:g} m/s that impacts at "
            f"{low:g}-{high / 2.0:g} m/s give: check the sensitivity's unit (V/N) and the "
            "grain's mass"
        )
    bound = limits["peak_force [N]"]
    if math.isfinite(peak_force) and peak_force > bound:
        problems.append(
            f"peak force {peak_force:.3g} N exceeds {bound:.3g} N, twice what a rigid "
            f"grain of {grain.mass:.3g} kg gives on steel at {high / 2.0:g} m/s: check "
            "the sensitivity's unit (V/N) and the grain's mass"
        )
    return problems
