"""Linear spring-dashpot (Kelvin-Voigt) contact: the paper's Eq. (6)."""

import math

import numpy as np

from contactlab import analytic
from contactlab.laws.base import PowerForm, SmoothLaw, force_function, one_sided, read_only
from contactlab.laws.closed_form import SCHWAGER_2007, closed_form
from contactlab.laws.granular import GranularModel
from contactlab.laws.hertz import Hertz
from contactlab.laws.kratos_form import LINEAR_LAW, kratos_model, linear_kn_factor
from contactlab.quantities import column
from contactlab.validation import check_choice, check_non_negative, check_positive

__all__ = ["LinearViscoelastic", "linear_viscoelastic_force"]


def _linear_raw(overlap, rate, stiffness, damping):
    return stiffness * overlap + damping * rate


@force_function()
def linear_viscoelastic_force(overlap, rate, stiffness, damping):
    """Linear spring-dashpot (Kelvin-Voigt) contact force, one-sided.

    Parameters
    ----------
    overlap : array_like
        Overlap ``d`` [m], positive in compression.
    rate : array_like
        Overlap rate ``d'`` [m/s], positive while approaching.
    stiffness : float
        Contact stiffness ``k`` [N/m].
    damping : float
        Damping coefficient ``c`` [N*s/m].

    Returns
    -------
    numpy.ndarray
        ``max(k d + c d', 0)`` for ``d > 0``, else 0 [N].

    Notes
    -----
    The paper's Eq. (6), ``S2 = k2 (x2 - x1) + c2 (v2 - v1)`` in the sign convention of
    this module, made one-sided.

    References
    ----------
    Keska W. et al. (2021) Applied Sciences 11, 11 (Eq. 6).
    Cundall P.A., Strack O.D.L. (1979) Geotechnique 29, 47-65. DOI 10.1680/geot.1979.29.1.47
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return one_sided(overlap, _linear_raw(overlap, rate, stiffness, damping))


class LinearViscoelastic(SmoothLaw):
    """Linear spring-dashpot (Kelvin-Voigt) contact, one-sided: ``max(k d + c d', 0)``.

    Parameters
    ----------
    stiffness : float
        Contact stiffness ``k`` [N/m], > 0.
    damping : float, default 0
        Damping coefficient ``c`` [N*s/m], >= 0.

    Notes
    -----
    The paper's Eq. (6). The contact ends when the force reaches zero, before the
    overlap returns to zero when ``c > 0``; :func:`contactlab.analytic.linear_restitution`
    gives both conventions. See :func:`linear_viscoelastic_force`.
    """

    name = "linear"
    dem_export = "linear"
    """DEM exporters write it as stiffness and damping (:mod:`contactlab.inverse.export`)."""
    piecewise_linear = True
    units = read_only(stiffness="N/m", damping="N*s/m")
    stiffness_parameters = ("stiffness",)
    typical = read_only(stiffness=(1e3, 1e7, "log"), damping=(0.0, 5.0, "linear"))
    """DEM practice (the paper's soft and hard grains: 1e4 and 1e5 N/m; damping 1 N*s/m)."""

    def __init__(self, stiffness, damping=0.0):
        self._keep(stiffness=(check_positive, stiffness), damping=(check_non_negative, damping))

    @classmethod
    def from_restitution(cls, stiffness, restitution, mass, convention="overlap"):
        """Damping that gives a restitution coefficient for a grain of ``mass``.

        Parameters
        ----------
        stiffness : float
            Contact stiffness [N/m].
        restitution : float
            Target restitution in (0, 1] [-].
        mass : float
            Effective mass [kg].
        convention : {"overlap", "force"}
            Contact end assumed by the mapping. ``"overlap"`` (default) is the formula of
            LIGGGHTS, MercuryDPM and EDEM, ``zeta = -ln e / sqrt(pi**2 + ln(e)**2)``; it
            assumes the contact ends when the overlap returns to zero. This toolkit's
            solvers end the contact when the force reaches zero, where the same damping
            realises a *larger* restitution
            (``analytic.linear_restitution(k, c, m, "force")``; e.g. 0.5 -> 0.58).
            ``"force"`` inverts the force-zero relation so that the solver realises
            ``restitution`` exactly.
        """
        check_choice("convention", convention, ("overlap", "force"))
        damping = analytic.linear_damping_from_restitution(
            stiffness, restitution, mass, convention=convention
        )
        return cls(stiffness=stiffness, damping=damping)

    def _resized(self, mass, grain, velocity):
        """The law for ``grain`` (another size, from its material data) at ``velocity``:
        the stiffness ``m (pi / t_H)**2`` of the elastic Hertz contact with the same
        rigid-wall contact time ``t_H``, and this law's damping ratio for a grain of
        ``mass`` [kg]."""
        k_hertz = Hertz.from_material(grain.material()).k_hertz
        t_hertz = analytic.hertz_contact_time(k_hertz, grain.mass, velocity)
        stiffness = grain.mass * (math.pi / t_hertz) ** 2
        ratio = self.damping / (2.0 * math.sqrt(self.stiffness * mass))
        return type(self)(stiffness, 2.0 * ratio * math.sqrt(stiffness * grain.mass))

    def _raw(self, overlap, rate):
        return _linear_raw(overlap, rate, self.stiffness, self.damping)

    def power_form(self):
        return PowerForm(self.stiffness, 1.0, self.damping, 0.0)

    def _linear(self):
        return (self.stiffness, self.damping, 0.0)

    def _lammps_model(self, effective_mass, effective_radius):
        """LAMMPS: ``hooke k c``, ``damping velocity`` (:mod:`contactlab.laws.lammps`)."""
        return GranularModel(
            law=self,
            normal="hooke",
            stiffness=self.stiffness,
            damping="velocity",
            damping_coefficient=self.damping,
            effective_mass=effective_mass,
            effective_radius=effective_radius,
        )

    def _kratos_model(self, effective_mass, effective_radius, wall):
        """Kratos: ``DEM_D_Linear_viscous_Coulomb``, ``E*`` from ``Kn = k``
        (:func:`~contactlab.laws.kratos_form.linear_kn_factor`) and ``gamma = c / (2
        sqrt(m* k))`` (:mod:`contactlab.laws.kratos`)."""
        e_star = self.stiffness / (linear_kn_factor(wall) * effective_radius)
        return kratos_model(self, LINEAR_LAW, e_star, effective_mass, effective_radius)

    def _damping_ratio(self, mass):
        """Kratos' damping ratio ``c / (2 sqrt(m* k))`` [-] on a grain of ``mass`` [kg]
        (:func:`contactlab.laws.damping_ratio`; ``Kn = k``)."""
        return self.damping / (2.0 * math.sqrt(mass * self.stiffness))

    def _batch_contact(self):
        """The batch solver of this law and its contact columns:
        :func:`contactlab.batch.linear_impacts`, ``k2 [N/m]`` and ``c2 [N*s/m]``."""
        return "linear", {column("k2"): self.stiffness, column("c2"): self.damping}

    def _closed_forms(self, mass, velocity):
        """Contact time and restitution on a wall (Schwager & Poeschel 2007, force-zero end)."""
        args = dict(stiffness=self.stiffness, damping=self.damping, mass=mass, convention="force")
        return (
            closed_form("contact_time", analytic.linear_contact_time, SCHWAGER_2007, **args),
            closed_form("restitution", analytic.linear_restitution, SCHWAGER_2007, **args),
        )
