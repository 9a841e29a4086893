"""The paper's perfectly plastic contact: a prescribed trapezoidal force pulse (Eqs. 7-8)."""

import numpy as np

from contactlab import analytic
from contactlab.laws.base import ContactLaw, force_function, read_only
from contactlab.laws.closed_form import KESKA_2021, ClosedForm, closed_form
from contactlab.validation import KeywordChecked, check_number, check_positive

__all__ = ["PlasticTrapezoid", "plastic_trapezoid_force"]


@force_function()
def plastic_trapezoid_force(time, amplitude, contact_time, ramp_time):
    """The paper's perfectly plastic pulse: a trapezoid in time [N].

    Parameters
    ----------
    time : array_like
        Time since first touch [s].
    amplitude : float
        Plateau force [N]; ``m2 v0 / (contact_time - ramp_time)`` gives impulse ``m2 v0``.
    contact_time : float
        Total duration, ramps included [s].
    ramp_time : float
        Duration of the linear rise and of the linear fall [s] (0 gives a rectangle).

    References
    ----------
    Keska W. et al. (2021) Applied Sciences 11, 11 (Eqs. 7-8).
    """
    check_number("contact_time", contact_time, unit="s")  # scalars: the pulse has one shape
    ramp_time = check_number("ramp_time", ramp_time, low=0.0, low_open=False, unit="s")
    time = np.asarray(time, dtype=float)
    if ramp_time == 0.0:
        shape = ((time >= 0) & (time < contact_time)).astype(float)
    else:
        shape = np.clip(np.minimum(time, contact_time - time) / ramp_time, 0.0, 1.0)
    return amplitude * shape


class PlasticTrapezoid(KeywordChecked):
    """The paper's perfectly plastic contact: a prescribed trapezoidal force pulse.

    Parameters
    ----------
    contact_time : float
        Total pulse duration ``t_k``, ramps included [s].
    ramp_time : float, default 0
        Duration of the linear rise and of the linear fall [s], at most half the pulse.

    Notes
    -----
    The force is a function of time, not of overlap (Eqs. 7-8 of the paper, with the
    trapezoid the authors used instead of the rectangle). Its plateau is sized so that
    the impulse equals the grain's momentum ``m2 v0`` exactly: the grain stops
    (restitution 0). It is solved exactly (first-order hold) and never re-contacts.
    """

    name = "plastic_trapezoid"
    lammps_refusal = "it prescribes the force in time, not as a function of the overlap"
    kratos_refusal = lammps_refusal
    prescribed = True
    has_history = False
    piecewise_linear = True
    units = read_only(contact_time="s", ramp_time="s")
    stiffness_parameters = ()
    typical = read_only(contact_time=(10e-6, 500e-6, "log"), ramp_fraction=(0.0, 1.0, "linear"))
    """``ramp_fraction``: the ramps' share of half the pulse."""

    @classmethod
    def _from_typical(cls, contact_time, ramp_fraction):
        """The pulse from values drawn over :attr:`typical`."""
        return cls(contact_time, ramp_fraction * 0.5 * contact_time)

    def __init__(self, contact_time, ramp_time=0.0):
        self.contact_time = check_positive("contact_time", contact_time, self.units["contact_time"])
        self.ramp_time = check_number(
            "ramp_time",
            ramp_time,
            low=0.0,
            high=0.5 * self.contact_time,
            low_open=False,
            unit="s (at most contact_time/2)",
        )
        self._params = {"contact_time": self.contact_time, "ramp_time": self.ramp_time}

    parameters = ContactLaw.parameters
    __repr__ = ContactLaw.__repr__
    __eq__ = ContactLaw.__eq__
    __hash__ = ContactLaw.__hash__

    def amplitude(self, mass, velocity):
        """Plateau force [N] for a grain of ``mass`` [kg] at ``velocity`` [m/s]."""
        return analytic.plastic_trapezoid_amplitude(
            mass, velocity, self.contact_time, self.ramp_time
        )

    def pieces(self, mass, velocity):
        """Straight pieces of the pulse: ``(t_start [s], t_end [s], F_start [N], F_end [N])``.

        A rectangle (``ramp_time = 0``) is one piece; a trapezoid is rise, plateau, fall
        (the plateau is dropped when the ramps meet).
        """
        amp, r, t = self.amplitude(mass, velocity), self.ramp_time, self.contact_time
        if r == 0.0:
            return [(0.0, t, amp, amp)]
        pieces = [(0.0, r, 0.0, amp), (r, t - r, amp, amp), (t - r, t, amp, 0.0)]
        return [p for p in pieces if p[1] > p[0]]

    def force_at(self, time, mass, velocity):
        """Contact force [N] at ``time`` [s] after first touch (see plastic_trapezoid_force)."""
        return plastic_trapezoid_force(
            time, self.amplitude(mass, velocity), self.contact_time, self.ramp_time
        )

    def restitution(self, mass, velocity):
        """Always 0: the impulse equals the grain's momentum."""
        check_positive("mass", mass, "kg")
        check_positive("velocity", velocity, "m/s")
        return 0.0

    def _closed_forms(self, mass, velocity):
        """Plateau force, the prescribed duration and restitution 0 (Keska et al. 2021)."""
        return (
            closed_form(
                "peak_contact_force",
                analytic.plastic_trapezoid_amplitude,
                KESKA_2021,
                mass=mass,
                velocity=velocity,
                contact_time=self.contact_time,
                ramp_time=self.ramp_time,
            ),
            ClosedForm(
                "contact_time", self.contact_time, "t_k (the prescribed duration)", KESKA_2021
            ),
            ClosedForm(
                "restitution",
                0.0,
                "0 (the impulse equals the grain's momentum m v)",
                KESKA_2021,
                atol=1e-12,
                atol_reason="an exact zero has no relative scale; 1e-12 is 1e4 times the roundoff",
            ),
        )
