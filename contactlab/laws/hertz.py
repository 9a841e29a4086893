"""The Hertz family: elastic Hertz, Tsuji's damped Hertz, Kuwabara-Kono, Hunt-Crossley."""

import math
from functools import partial

import numpy as np

from contactlab import analytic
from contactlab.errors import ParameterError
from contactlab.laws.base import (
    PowerForm,
    SmoothLaw,
    force_function,
    one_sided,
    read_only,
    signed_power,
)
from contactlab.laws.closed_form import (
    ANTYPOV_2011,
    HUNT_CROSSLEY_1975,
    JOHNSON_1985,
    RAMIREZ_1999,
    ClosedForm,
    closed_form,
)
from contactlab.laws.granular import DAMPING_FORMS, GranularModel
from contactlab.laws.kratos_form import DAMPING_FORMS as KRATOS_DAMPING
from contactlab.laws.kratos_form import kratos_hertz
from contactlab.quantities import column
from contactlab.validation import (
    check_non_negative,
    check_number,
    check_positive,
    check_probability,
)

__all__ = [
    "Hertz",
    "HertzDamped",
    "HuntCrossley",
    "KuwabaraKono",
    "hertz_damped_force",
    "hertz_force",
    "hunt_crossley_force",
    "kuwabara_kono_force",
]


def _hertz_raw(overlap, k_hertz):
    return k_hertz * signed_power(overlap, 1.5)


@force_function()
def hertz_force(overlap, k_hertz):
    """Hertz elastic sphere-flat force ``kH d**1.5`` [N] (0 for ``d <= 0``).

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    k_hertz : float
        Hertz stiffness ``kH = 4/3 E* sqrt(R*)`` [N/m**1.5].

    References
    ----------
    Hertz H. (1882) J. reine angew. Math. 92, 156-171.
    Johnson K.L. (1985) Contact Mechanics, Cambridge University Press, ch. 4.
    """
    overlap = np.asarray(overlap, dtype=float)
    return one_sided(overlap, _hertz_raw(overlap, k_hertz))


def _hertz_damped_raw(overlap, rate, k_hertz, damping):
    root = abs(overlap) ** 0.25  # one power serves both terms: d**1.5 = d |d|**0.5
    return (k_hertz * overlap * root + damping * rate) * root


@force_function()
def hertz_damped_force(overlap, rate, k_hertz, damping):
    """Damped Hertz force of Tsuji et al. / EDEM / LIGGGHTS ``kH d**1.5 + eta d**0.25 d'`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    damping : float
        Damping coefficient ``eta = alpha sqrt(m* kH)`` [N*s/m**1.25].

    References
    ----------
    Tsuji Y., Tanaka T., Ishida T. (1992) Powder Technol. 71, 239-250.
    DOI 10.1016/0032-5910(92)88030-L
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return one_sided(overlap, _hertz_damped_raw(overlap, rate, k_hertz, damping))


def _kuwabara_kono_raw(overlap, rate, k_hertz, dissipation):
    return k_hertz * (signed_power(overlap, 1.5) + 1.5 * dissipation * abs(overlap) ** 0.5 * rate)


@force_function()
def kuwabara_kono_force(overlap, rate, k_hertz, dissipation):
    """Viscoelastic Hertz force ``kH (d**1.5 + 1.5 A d**0.5 d')`` [N].

    Parameters
    ----------
    overlap, rate, k_hertz
        Overlap [m], its rate [m/s] and kH [N/m**1.5], as for :func:`hertz_damped_force`.
    dissipation : float
        Dissipation constant ``A`` [s].

    References
    ----------
    Kuwabara G., Kono K. (1987) Jpn. J. Appl. Phys. 26, 1230. DOI 10.1143/JJAP.26.1230
    Brilliantov N.V. et al. (1996) Phys. Rev. E 53, 5382. DOI 10.1103/PhysRevE.53.5382
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return one_sided(overlap, _kuwabara_kono_raw(overlap, rate, k_hertz, dissipation))


def _hunt_crossley_raw(overlap, rate, stiffness, exponent, damping):
    return stiffness * signed_power(overlap, exponent) * (1.0 + 1.5 * damping * rate)


@force_function()
def hunt_crossley_force(overlap, rate, stiffness, exponent, damping):
    """Hunt-Crossley force ``k d**n (1 + 1.5 chi d')`` [N].

    Parameters
    ----------
    overlap, rate : array_like
        Overlap [m] and its rate [m/s], as for :func:`hertz_damped_force`.
    stiffness : float
        Stiffness ``k`` [N/m**n].
    exponent : float
        Exponent ``n`` [-] (1.5 for Hertz).
    damping : float
        Damping ``chi`` [s/m]; for small ``chi v`` the restitution is ``1 - chi v``.

    References
    ----------
    Hunt K.H., Crossley F.R.E. (1975) J. Appl. Mech. 42, 440-445. DOI 10.1115/1.3423596
    """
    overlap, rate = np.asarray(overlap, dtype=float), np.asarray(rate, dtype=float)
    return one_sided(overlap, _hunt_crossley_raw(overlap, rate, stiffness, exponent, damping))


def _lammps_hertz(law, damping, coefficient, effective_mass, effective_radius):
    """A Hertz-family law as LAMMPS' ``hertz kH/sqrt(R*)`` with the given damping."""
    stiffness = law.k_hertz / math.sqrt(effective_radius)
    return GranularModel(
        law=law,
        normal="hertz",
        stiffness=stiffness,
        damping=damping,
        damping_coefficient=coefficient,
        effective_mass=effective_mass,
        effective_radius=effective_radius,
    )


class Hertz(SmoothLaw):
    """Hertz elastic contact ``kH d**1.5``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness ``kH = 4/3 E* sqrt(R*)`` [N/m**1.5].

    See Also
    --------
    hertz_force
    """

    name = "hertz"
    dem_export = "hertz"
    """DEM exporters write it as E* and restitution 1 (:mod:`contactlab.inverse.export`)."""
    units = read_only(k_hertz="N/m**1.5")
    stiffness_parameters = ("k_hertz",)
    typical = read_only(k_hertz=(1e6, 1e9, "log"))
    """kH = 4/3 E* sqrt(R*): the paper's 5 mm grain has 1.5e6; dry hard grains reach 1e9."""

    def __init__(self, k_hertz):
        self._keep(k_hertz=(check_positive, k_hertz))

    @classmethod
    def from_material(cls, material, other=analytic.RIGID_FLAT):
        """Hertz law from material data; a rigid flat unless a second body is given.

        Parameters
        ----------
        material : contactlab.analytic.Material
            The grain's ``(youngs_modulus [Pa], poisson_ratio [-], radius [m])``
            (:meth:`contactlab.Grain.material`).
        other : contactlab.analytic.Material, default RIGID_FLAT
            The second body (another grain, a compliant plate), entering through
            ``1/E* = (1-nu1**2)/E1 + (1-nu2**2)/E2`` and ``1/R* = 1/R1 + 1/R2``.
        """
        modulus, radius = analytic.contact_modulus_radius(material, other)
        return cls(k_hertz=analytic.hertz_stiffness(modulus, radius))

    def _resized(self, mass, grain, velocity):
        """The law for ``grain`` (another size): from its material data."""
        return type(self).from_material(grain.material())

    def _raw(self, overlap, rate):
        return _hertz_raw(overlap, self.k_hertz)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5)

    def _lammps_model(self, effective_mass, effective_radius):
        """LAMMPS: ``hertz kH/sqrt(R*) 0``, ``damping velocity`` (:mod:`contactlab.laws.lammps`)."""
        return _lammps_hertz(self, "velocity", 0.0, effective_mass, effective_radius)

    def _kratos_model(self, effective_mass, effective_radius, wall):
        """Kratos: ``DEM_D_Hertz_viscous_Coulomb``, ``E* = 3 kH / (4 sqrt(R*))``,
        ``gamma = 0`` (:mod:`contactlab.laws.kratos`)."""
        return kratos_hertz(self, effective_mass, effective_radius)

    def _damping_ratio(self, mass):
        """Kratos' damping ratio [-]: 0 (:func:`contactlab.laws.damping_ratio`)."""
        return 0.0

    def _batch_contact(self):
        """The batch solver of this law and its contact columns:
        :func:`contactlab.batch.hertz_impacts` with zero damping."""
        return "hertz", {column("k_hertz"): self.k_hertz, column("damping"): 0.0}

    def _closed_forms(self, mass, velocity):
        """Contact time, peak force (Hertz; Johnson 1985) and restitution 1 on a wall."""
        args = dict(k_hertz=self.k_hertz, mass=mass, velocity=velocity)
        return (
            closed_form("contact_time", analytic.hertz_contact_time, JOHNSON_1985, **args),
            closed_form("peak_contact_force", analytic.hertz_max_force, JOHNSON_1985, **args),
            ClosedForm("restitution", 1.0, "1 (elastic: no dissipation)", JOHNSON_1985),
        )


class _HertzDashpot(SmoothLaw):
    """A Hertz spring ``kH`` > 0 [N/m**1.5] with a dashpot ``damping`` >= 0 (its form and
    unit the subclass's): :class:`HertzDamped`, :class:`HertzViscous`."""

    stiffness_parameters = ("k_hertz",)

    def __init__(self, k_hertz, damping):
        self._keep(k_hertz=(check_positive, k_hertz), damping=(check_non_negative, damping))


class HertzDamped(_HertzDashpot):
    """Damped Hertz contact of Tsuji et al. (EDEM, LIGGGHTS): ``kH d**1.5 + eta d**0.25 d'``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    damping : float
        ``eta = alpha sqrt(m* kH)`` [N*s/m**1.25], >= 0.

    Notes
    -----
    With this form the restitution depends only on ``alpha``, not on the impact velocity.
    See :func:`hertz_damped_force`.
    """

    name = "hertz_damped"
    dem_export = "hertz"
    """DEM exporters write it as E* and the Tsuji restitution (:mod:`contactlab.inverse.export`)."""
    units = read_only(k_hertz="N/m**1.5", damping="N*s/m**1.25")
    typical = read_only(k_hertz=(1e6, 1e9, "log"), damping=(0.0, 2.0, "linear"))
    """Damping factor alpha up to about 0.3 for the paper's grain."""

    @classmethod
    def from_material(cls, material, restitution, mass, other=analytic.RIGID_FLAT):
        """Hertz-Mindlin normal law as EDEM and LIGGGHTS build it.

        Parameters
        ----------
        material, other : contactlab.analytic.Material
            The grain's and the optional second body's, as for :meth:`Hertz.from_material`.
        restitution : float
            Target restitution in (0, 1] [-].
        mass : float
            Effective mass [kg].

        Notes
        -----
        The EDEM mapping ``alpha = sqrt(5) (-ln e) / sqrt(pi**2 + ln(e)**2)`` assumes the
        overlap-zero contact end, under which it is exact (Antypov & Elliott 2011). This
        toolkit's one-sided contact ends when the force reaches zero and realises a larger
        restitution: 0.3 -> 0.397, 0.5 -> 0.550, 0.7 -> 0.718, 0.9 -> 0.902
        (:func:`contactlab.analytic.tsuji_restitution` with ``convention="force"``).
        """
        check_probability("restitution", restitution, low_open=True)
        mass = check_positive("mass", mass, "kg")
        k_hertz = Hertz.from_material(material, other).k_hertz
        return cls(k_hertz, analytic.tsuji_damping_coefficient(k_hertz, mass, restitution))

    def _resized(self, mass, grain, velocity):
        """The law for ``grain`` (another size): kH from its material data, and this law's
        damping factor ``eta / sqrt(m kH)`` for a grain of ``mass`` [kg] (so its
        restitution)."""
        factor = self.damping / math.sqrt(mass * self.k_hertz)
        k_hertz = Hertz.from_material(grain.material()).k_hertz
        return type(self)(k_hertz, factor * math.sqrt(grain.mass * k_hertz))

    def _raw(self, overlap, rate):
        return _hertz_damped_raw(overlap, rate, self.k_hertz, self.damping)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5, self.damping, 0.25)

    def _lammps_model(self, effective_mass, effective_radius):
        """LAMMPS: ``hertz kH/sqrt(R*) e_L``, ``damping coeff_restitution``, with ``e_L``
        the input whose damping force is ``eta d**0.25 d'`` exactly
        (:mod:`contactlab.laws.lammps`)."""
        alpha = self.damping / math.sqrt(effective_mass * self.k_hertz)
        s = alpha / math.sqrt(5.0)
        if s >= 1.0:
            raise ParameterError(
                f"law HertzDamped: damping = {self.damping:.6g} N*s/m**1.25 is alpha = "
                f"eta/sqrt(m* kH) = {alpha:.6g} >= sqrt(5) for m* = {effective_mass:.6g} kg; "
                "LAMMPS' coeff_restitution damping reaches alpha < sqrt(5) only (its tsuji "
                "damping alpha < 1.80): no LAMMPS input holds this law"
            )
        restitution = math.exp(-math.pi * s / math.sqrt(1.0 - s * s))
        return _lammps_hertz(
            self, "coeff_restitution", restitution, effective_mass, effective_radius
        )

    def _kratos_model(self, effective_mass, effective_radius, wall):
        """Kratos: ``DEM_D_Hertz_viscous_Coulomb``, ``E* = 3 kH / (4 sqrt(R*))``,
        ``gamma = eta / (2 sqrt(1.5 m* kH))``, since ``2 gamma sqrt(m* Kn) = eta d**0.25``
        with ``Kn = 1.5 kH d**0.5`` (:mod:`contactlab.laws.kratos`)."""
        return kratos_hertz(self, effective_mass, effective_radius)

    def _damping_ratio(self, mass):
        """Kratos' damping ratio ``eta / (2 sqrt(1.5 m* kH))`` [-] on a grain of ``mass``
        [kg] (:func:`contactlab.laws.damping_ratio`; ``Kn = 1.5 kH sqrt(d)``)."""
        return self.damping / (2.0 * math.sqrt(1.5 * mass * self.k_hertz))

    def _batch_contact(self):
        """The batch solver of this law and its contact columns:
        :func:`contactlab.batch.hertz_impacts`, ``k_hertz`` and ``damping``."""
        return "hertz", {column("k_hertz"): self.k_hertz, column("damping"): self.damping}

    def _closed_forms(self, mass, velocity):
        """Restitution on a wall: a function of ``alpha`` only (Antypov & Elliott 2011)."""
        alpha = self.damping / math.sqrt(mass * self.k_hertz)
        restitution = analytic.tsuji_restitution
        return (
            closed_form("restitution", restitution, ANTYPOV_2011, alpha=alpha, convention="force"),
        )


class KuwabaraKono(SmoothLaw):
    """Viscoelastic Hertz contact (Kuwabara-Kono, Brilliantov): ``kH (d**1.5 + 1.5 A d**0.5 d')``.

    Parameters
    ----------
    k_hertz, dissipation : float
        Hertz stiffness [N/m**1.5] and dissipation constant ``A`` >= 0 [s].

    See Also
    --------
    kuwabara_kono_force, contactlab.analytic.kuwabara_kono_restitution
    """

    name = "kuwabara_kono"
    units = read_only(k_hertz="N/m**1.5", dissipation="s")
    stiffness_parameters = ("k_hertz",)
    typical = read_only(k_hertz=(1e6, 1e9, "log"), dissipation=(0.0, 1e-5, "linear"))
    """Dissipation constant A up to 10 us."""
    kratos_refusal = f"its damping 1.5 A kH d**0.5 d' scales as d**0.5; {KRATOS_DAMPING}"

    def __init__(self, k_hertz, dissipation):
        self._keep(k_hertz=(check_positive, k_hertz), dissipation=(check_non_negative, dissipation))

    def _raw(self, overlap, rate):
        return _kuwabara_kono_raw(overlap, rate, self.k_hertz, self.dissipation)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5, 1.5 * self.k_hertz * self.dissipation, 0.5)

    def _lammps_model(self, effective_mass, effective_radius):
        """LAMMPS: ``hertz kH/sqrt(R*) eta``, ``damping viscoelastic`` with
        ``eta = 1.5 A kH / (m* sqrt(R*))`` (:mod:`contactlab.laws.lammps`)."""
        coefficient = (
            1.5 * self.dissipation * self.k_hertz / (effective_mass * math.sqrt(effective_radius))
        )
        return _lammps_hertz(self, "viscoelastic", coefficient, effective_mass, effective_radius)

    def _closed_forms(self, mass, velocity):
        """Restitution on a wall: the two-term series of Ramirez et al. (1999)."""
        args = dict(
            k_hertz=self.k_hertz, dissipation=self.dissipation, mass=mass, velocity=velocity
        )
        x = analytic.kuwabara_kono_parameter(**args)
        return (
            closed_form(
                "restitution",
                analytic.kuwabara_kono_restitution,
                RAMIREZ_1999,
                atol=0.5 * x**2.5,
                atol_reason=(
                    f"0.5 x**2.5 (x = {x:.4g}): the two-term series leaves an O(x**2.5) "
                    "remainder at the force-zero end (measured 0.24 x**2.5)"
                ),
                **args,
            ),
        )


class HuntCrossley(SmoothLaw):
    """Hunt-Crossley contact ``k d**n (1 + 1.5 chi d')``.

    Parameters
    ----------
    stiffness : float
        ``k`` [N/m**n].
    exponent : float
        ``n`` in [1, 3] [-] (1.5 for Hertz).
    damping : float
        ``chi`` [s/m], >= 0.

    See Also
    --------
    hunt_crossley_force, contactlab.analytic.hunt_crossley_restitution
    """

    name = "hunt_crossley"
    lammps_refusal = f"its damping k chi d**n d' scales as d**n; {DAMPING_FORMS}"
    kratos_refusal = f"its damping k chi d**n d' scales as d**n; {KRATOS_DAMPING}"
    units = read_only(stiffness="N/m**n", exponent="-", damping="s/m")
    stiffness_parameters = ("stiffness",)
    typical = read_only(
        stiffness=(1e6, 1e9, "log"), exponent=(1.5, 1.5, "linear"), damping=(0.0, 0.5, "linear")
    )
    """Hertzian exponent; restitution 1 - chi v for small chi v."""

    def __init__(self, stiffness, exponent, damping):
        self._keep(
            stiffness=(check_positive, stiffness),
            exponent=(partial(check_number, low=1.0, high=3.0, low_open=False), exponent),
            damping=(check_non_negative, damping),
        )

    def _raw(self, overlap, rate):
        return _hunt_crossley_raw(overlap, rate, self.stiffness, self.exponent, self.damping)

    def power_form(self):
        k, n = self.stiffness, self.exponent
        return PowerForm(k, n, 1.5 * k * self.damping, n, signed_damping=True)

    def _closed_forms(self, mass, velocity):
        """Restitution on a wall, ``1 - chi v`` to first order (Hunt & Crossley 1975)."""
        restitution = analytic.hunt_crossley_restitution
        return (
            closed_form(
                "restitution",
                restitution,
                HUNT_CROSSLEY_1975,
                damping=self.damping,
                velocity=velocity,
            ),
        )
