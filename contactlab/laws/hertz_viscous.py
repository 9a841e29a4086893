"""Hertz contact with a linear dashpot: LAMMPS' ``hertz`` with ``damping velocity``."""

from scipy.special import beta

from contactlab import analytic
from contactlab.laws.base import PowerForm, read_only, signed_power
from contactlab.laws.closed_form import JOHNSON_1985, ClosedForm
from contactlab.laws.hertz import _HertzDashpot, _lammps_hertz
from contactlab.laws.kratos_form import DAMPING_FORMS

__all__ = ["HertzViscous"]


class HertzViscous(_HertzDashpot):
    """Hertz contact with a linear dashpot, ``kH d**1.5 + c d'``.

    Parameters
    ----------
    k_hertz, damping : float
        Hertz stiffness [N/m**1.5] and dashpot coefficient ``c`` >= 0 [N*s/m].

    Notes
    -----
    LAMMPS' granular ``hertz kH/sqrt(R*) c`` with ``damping velocity`` holds it exactly.
    Its restitution depends on ``y = c d_max / (m v)`` alone (``d_max`` the elastic Hertz
    overlap): scaling the overlap by ``d_max`` and time by ``d_max / v`` leaves one
    parameter.
    """

    name = "hertz_viscous"
    units = read_only(k_hertz="N/m**1.5", damping="N*s/m")
    typical = read_only(k_hertz=(1e6, 1e9, "log"), damping=(0.0, 0.05, "linear"))
    """Dashpots up to y = 0.06 for the paper's grain (restitution down to about 0.9)."""

    def _raw(self, overlap, rate):
        return self.k_hertz * signed_power(overlap, 1.5) + self.damping * rate

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5, self.damping, 0.0)

    def _lammps_model(self, effective_mass, effective_radius):
        """LAMMPS: ``hertz kH/sqrt(R*) c``, ``damping velocity``."""
        return _lammps_hertz(self, "velocity", self.damping, effective_mass, effective_radius)

    kratos_refusal = (
        f"its dashpot c d' on a Hertz spring scales as d**0; {DAMPING_FORMS}, tied to the "
        "law's own stiffness"
    )

    def _closed_forms(self, mass, velocity):
        """Restitution to first order in ``y = c d_max / (m v)``: the dashpot's work along
        the elastic Hertz path, ``1 - e = (4/5) B(2/5, 3/2) y``."""
        d_max = analytic.hertz_max_overlap(self.k_hertz, mass, velocity)
        y = self.damping * d_max / (mass * velocity)
        return (
            ClosedForm(
                "restitution",
                1.0 - 0.8 * beta(0.4, 1.5) * y,
                f"1 - (4/5) B(2/5, 3/2) y, y = c d_max / (m v) = {y:.6g}",
                JOHNSON_1985,
                atol=1.5 * y ** (5.0 / 3.0),
                atol_reason=(
                    f"1.5 y**(5/3) (y = {y:.4g}): the contact ends where kH d**1.5 = c d', "
                    "the dashpot's work lost there is O(y**(5/3)) (measured 0.571-0.847 "
                    "y**(5/3) for y = 1e-4 to 0.04)"
                ),
            ),
        )
