"""The Hertz family: elastic Hertz, Tsuji's damped Hertz, Kuwabara-Kono, Hunt-Crossley."""

import math

import numpy as np

from contactlab import analytic
from contactlab.laws.base import PowerForm, SmoothLaw, one_sided, signed_power
from contactlab.validation import (
    check_non_negative,
    check_number,
    check_positive,
    check_probability,
    numbers_checked,
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


@numbers_checked()
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


@numbers_checked()
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


@numbers_checked()
def kuwabara_kono_force(overlap, rate, k_hertz, dissipation):
    """Viscoelastic Hertz force ``kH (d**1.5 + 1.5 A d**0.5 d')`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
    k_hertz : float
        Hertz stiffness [N/m**1.5].
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


@numbers_checked()
def hunt_crossley_force(overlap, rate, stiffness, exponent, damping):
    """Hunt-Crossley force ``k d**n (1 + 1.5 chi d')`` [N].

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    rate : array_like
        Overlap rate [m/s].
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

    def __init__(self, k_hertz):
        self.k_hertz = check_positive("k_hertz", k_hertz, "N/m**1.5")
        self._params = {"k_hertz": self.k_hertz}

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        other_radius=math.inf,
    ):
        """Hertz law from material data [Pa, -, m]; a rigid flat unless a second body is given.

        The second body (another grain, a compliant plate) enters through
        ``1/E* = (1-nu1**2)/E1 + (1-nu2**2)/E2`` and ``1/R* = 1/R1 + 1/R2``.
        """
        modulus, radius_eff = analytic.contact_modulus_radius(
            youngs_modulus,
            poisson_ratio,
            radius,
            (other_youngs_modulus, other_poisson_ratio, other_radius),
        )
        return cls(k_hertz=analytic.hertz_stiffness(modulus, radius_eff))

    def _raw(self, overlap, rate):
        return _hertz_raw(overlap, self.k_hertz)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5)


class HertzDamped(SmoothLaw):
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

    def __init__(self, k_hertz, damping):
        self.k_hertz = check_positive("k_hertz", k_hertz, "N/m**1.5")
        self.damping = check_non_negative("damping", damping, "N*s/m**1.25")
        self._params = {"k_hertz": self.k_hertz, "damping": self.damping}

    @classmethod
    def from_material(
        cls,
        youngs_modulus,
        poisson_ratio,
        radius,
        restitution,
        mass,
        other_youngs_modulus=math.inf,
        other_poisson_ratio=0.0,
        other_radius=math.inf,
    ):
        """Hertz-Mindlin normal law as EDEM and LIGGGHTS build it.

        Parameters
        ----------
        youngs_modulus, poisson_ratio, radius : float
            Grain data [Pa, -, m]; the optional second body as in :meth:`Hertz.from_material`.
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
        k_hertz = Hertz.from_material(
            youngs_modulus,
            poisson_ratio,
            radius,
            other_youngs_modulus,
            other_poisson_ratio,
            other_radius,
        ).k_hertz
        return cls(k_hertz, analytic.tsuji_damping_coefficient(k_hertz, mass, restitution))

    def _raw(self, overlap, rate):
        return _hertz_damped_raw(overlap, rate, self.k_hertz, self.damping)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5, self.damping, 0.25)


class KuwabaraKono(SmoothLaw):
    """Viscoelastic Hertz contact (Kuwabara-Kono, Brilliantov): ``kH (d**1.5 + 1.5 A d**0.5 d')``.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness [N/m**1.5].
    dissipation : float
        Dissipation constant ``A`` [s], >= 0.

    See Also
    --------
    kuwabara_kono_force, contactlab.analytic.kuwabara_kono_restitution
    """

    name = "kuwabara_kono"

    def __init__(self, k_hertz, dissipation):
        self.k_hertz = check_positive("k_hertz", k_hertz, "N/m**1.5")
        self.dissipation = check_non_negative("dissipation", dissipation, "s")
        self._params = {"k_hertz": self.k_hertz, "dissipation": self.dissipation}

    def _raw(self, overlap, rate):
        return _kuwabara_kono_raw(overlap, rate, self.k_hertz, self.dissipation)

    def power_form(self):
        return PowerForm(self.k_hertz, 1.5, 1.5 * self.k_hertz * self.dissipation, 0.5)


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

    def __init__(self, stiffness, exponent, damping):
        self.stiffness = check_positive("stiffness", stiffness, "N/m**n")
        self.exponent = check_number("exponent", exponent, low=1.0, high=3.0, low_open=False)
        self.damping = check_non_negative("damping", damping, "s/m")
        self._params = {
            "stiffness": self.stiffness,
            "exponent": self.exponent,
            "damping": self.damping,
        }

    def _raw(self, overlap, rate):
        return _hunt_crossley_raw(overlap, rate, self.stiffness, self.exponent, self.damping)

    def power_form(self):
        k, n = self.stiffness, self.exponent
        return PowerForm(k, n, 1.5 * k * self.damping, n, signed_damping=True)
