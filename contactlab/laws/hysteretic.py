"""Walton-Braun hysteretic linear contact: stiffer unloading than loading."""

import numpy as np

from contactlab import analytic
from contactlab.laws.base import (
    Branch,
    ContactLaw,
    force_function,
    one_sided,
    overlap_reaches,
    rate_turns,
    read_only,
    with_history,
)
from contactlab.laws.closed_form import WALTON_BRAUN_1986, closed_form
from contactlab.validation import check_number, check_positive

__all__ = ["WaltonBraun", "walton_braun_force"]


@force_function("max_overlap")
def walton_braun_force(overlap, max_overlap, loading_stiffness, unloading_stiffness):
    """Walton-Braun hysteretic linear force [N].

    Loading ``k1 d`` while ``d`` is at its maximum; otherwise unloading
    ``k2 (d - d0)`` with the plastic overlap ``d0 = d_max (1 - k1/k2)``.

    Parameters
    ----------
    overlap, max_overlap
        The overlap and the largest overlap reached so far [m], as for
        :func:`~contactlab.laws.linear_plastic_force`.
    loading_stiffness, unloading_stiffness : float
        ``0 < k1 <= k2`` [N/m].

    References
    ----------
    Walton O.R., Braun R.L. (1986) J. Rheol. 30, 949-980. DOI 10.1122/1.549893
    """
    k1 = check_positive("loading_stiffness", loading_stiffness, "N/m")
    k2 = check_number(
        "unloading_stiffness", unloading_stiffness, low=k1, low_open=False, unit="N/m"
    )
    d, d_max = with_history(overlap, max_overlap)
    return one_sided(d, _walton_braun_raw(d, d_max, k1, k2))


def _walton_braun_raw(d, d_max, k1, k2):
    """Loading ``k1 d`` at the largest overlap, else ``k2 (d - d0)``, ``d0 = d_max (1 - k1/k2)``."""
    return np.where(d >= d_max, k1 * d, k2 * (d - d_max * (1.0 - k1 / k2)))


class WaltonBraun(ContactLaw):
    """Walton-Braun hysteretic linear contact (LIGGGHTS hooke/hysteresis, Luding's model).

    Parameters
    ----------
    loading_stiffness, unloading_stiffness : float
        ``k1 > 0`` and ``k2 >= k1`` [N/m]; the restitution on a wall is ``sqrt(k1/k2)``.

    See Also
    --------
    walton_braun_force
    """

    name = "walton_braun"
    lammps_refusal = (
        "its unloading stiffness differs from its loading one (history); LAMMPS' normal "
        "models (hooke, hertz, hertz/material, dmt, jkr) are elastic in the current overlap "
        "and its plastic one (mdr) is a different law"
    )
    kratos_refusal = (
        "its unloading stiffness differs from its loading one (history); Kratos' "
        "DEM_D_Hertz/Linear laws are elastic in the current overlap"
    )
    has_history = True
    piecewise_linear = True
    units = read_only(loading_stiffness="N/m", unloading_stiffness="N/m")
    stiffness_parameters = ("loading_stiffness", "unloading_stiffness")
    typical = read_only(loading_stiffness=(1e3, 1e7, "log"), stiffness_ratio=(0.05, 1.0, "linear"))
    """``stiffness_ratio`` k1/k2: restitution sqrt(k1/k2) from 1 down to 0.22."""

    @classmethod
    def _from_typical(cls, loading_stiffness, stiffness_ratio):
        """The law from values drawn over :attr:`typical` (``k2 = k1 / stiffness_ratio``)."""
        return cls(loading_stiffness, loading_stiffness / stiffness_ratio)

    def __init__(self, loading_stiffness, unloading_stiffness):
        self.loading_stiffness = check_positive(
            "loading_stiffness", loading_stiffness, self.units["loading_stiffness"]
        )
        self.unloading_stiffness = check_number(
            "unloading_stiffness",
            unloading_stiffness,
            low=self.loading_stiffness,
            low_open=False,
            unit="N/m (>= loading_stiffness)",
        )
        self._params = {
            "loading_stiffness": self.loading_stiffness,
            "unloading_stiffness": self.unloading_stiffness,
        }

    def _force(self, overlap, rate, max_overlap):
        d, d_max = with_history(overlap, max_overlap)
        return _walton_braun_raw(d, d_max, self.loading_stiffness, self.unloading_stiffness)

    def _plastic_overlap(self, max_overlap):
        return max_overlap * (1.0 - self.loading_stiffness / self.unloading_stiffness)

    def branch(self, name, max_overlap=0.0):
        k1, k2 = self.loading_stiffness, self.unloading_stiffness
        if name == "load":
            return Branch("load", lambda d, r: k1 * d, (k1, 0.0, 0.0), (rate_turns("unload"),))
        d0 = self._plastic_overlap(max_overlap)
        return Branch(
            "unload",
            lambda d, r: k2 * (d - d0),
            (k2, 0.0, -k2 * d0),
            (overlap_reaches(max_overlap, "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return self._plastic_overlap(max_overlap), "unload"

    def _closed_forms(self, mass, velocity):
        """Restitution ``sqrt(k1/k2)`` and contact time on a wall (Walton & Braun 1986)."""
        args = dict(
            loading_stiffness=self.loading_stiffness,
            unloading_stiffness=self.unloading_stiffness,
        )
        restitution, contact_time = (
            analytic.walton_braun_restitution,
            analytic.walton_braun_contact_time,
        )
        return (
            closed_form("restitution", restitution, WALTON_BRAUN_1986, **args),
            closed_form("contact_time", contact_time, WALTON_BRAUN_1986, mass=mass, **args),
        )
