"""Elastic-perfectly-plastic contacts: a linear spring with a force cap, and Thornton's Hertz."""

import math

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
    signed_power,
    with_history,
)
from contactlab.laws.closed_form import ENERGY_BALANCE, THORNTON_1997, ClosedForm, closed_form
from contactlab.validation import check_positive

__all__ = ["LinearPlastic", "Thornton", "linear_plastic_force", "thornton_force"]


@force_function("max_overlap")
def linear_plastic_force(overlap, max_overlap, stiffness, yield_force):
    """Linear spring with a force cap (elastic-perfectly-plastic, linear) [N].

    ``min(k d, Fy)`` on loading; elastic unloading with slope ``k`` from the largest force
    reached.

    Parameters
    ----------
    overlap : array_like
        Overlap [m].
    max_overlap : array_like or None
        Largest overlap reached so far [m]; ``None`` means a virgin loading path.
    stiffness : float
        Spring stiffness ``k`` [N/m].
    yield_force : float
        Force cap ``Fy`` [N].
    """
    d, d_max = with_history(overlap, max_overlap)
    return one_sided(d, _linear_plastic_raw(d, d_max, stiffness, yield_force))


def _linear_plastic_raw(d, d_max, stiffness, yield_force):
    """``min(k d, Fy)`` on loading, elastic unloading from the largest force reached."""
    f_max = np.minimum(stiffness * d_max, yield_force)
    return np.minimum(f_max + stiffness * (d - d_max), yield_force)


@force_function("max_overlap")
def thornton_force(overlap, max_overlap, effective_modulus, effective_radius, yield_pressure):
    """Thornton (1997) elastic-perfectly-plastic Hertz force [N].

    Hertz up to the yield overlap ``dy``, then ``Fy + pi py R* (d - dy)``; unloading is
    Hertzian with an enlarged radius ``Rp`` from the plastic overlap ``dp``.

    Parameters
    ----------
    overlap, max_overlap
        As for :func:`linear_plastic_force` [m].
    effective_modulus, effective_radius, yield_pressure : float
        ``E*`` [Pa], ``R*`` [m] and the limiting contact pressure ``py`` [Pa].

    References
    ----------
    Thornton C. (1997) J. Appl. Mech. 64, 383-386. DOI 10.1115/1.2787319
    """
    d, d_max = with_history(overlap, max_overlap)
    return one_sided(
        d, _thornton_raw(d, d_max, effective_modulus, effective_radius, yield_pressure)
    )


def _thornton_loading(d, modulus, radius, yield_pressure):
    k_hertz = 4.0 / 3.0 * modulus * math.sqrt(radius)
    d_y = analytic.thornton_yield_overlap(modulus, radius, yield_pressure)
    f_y = analytic.thornton_yield_force(modulus, radius, yield_pressure)
    plastic = f_y + math.pi * yield_pressure * radius * (d - d_y)
    return np.where(d <= d_y, k_hertz * signed_power(d, 1.5), plastic)


def _thornton_unloading(d_max, modulus, radius, yield_pressure):
    """Unloading curve ``(kp, dp)``: ``F = kp (d - dp)**1.5`` from ``d_max``."""
    d_max = np.asarray(d_max, dtype=float)
    d_y = analytic.thornton_yield_overlap(modulus, radius, yield_pressure)
    f_y = analytic.thornton_yield_force(modulus, radius, yield_pressure)
    f_max = np.asarray(_thornton_loading(d_max, modulus, radius, yield_pressure))
    with np.errstate(divide="ignore", invalid="ignore"):
        contact_radius_cubed = ((2.0 * f_max + f_y) / (2.0 * math.pi * yield_pressure)) ** 1.5
        r_p = 4.0 * modulus * contact_radius_cubed / (3.0 * f_max)
        k_p = 4.0 / 3.0 * modulus * np.sqrt(np.where(d_max > d_y, r_p, radius))
        d_p = np.where(d_max > d_y, d_max - (f_max / k_p) ** (2.0 / 3.0), 0.0)
    return k_p, d_p


def _thornton_raw(d, d_max, modulus, radius, yield_pressure):
    k_p, d_p = _thornton_unloading(d_max, modulus, radius, yield_pressure)
    loading = _thornton_loading(d, modulus, radius, yield_pressure)
    return np.where(d >= d_max, loading, k_p * signed_power(d - d_p, 1.5))


class LinearPlastic(ContactLaw):
    """Linear spring with a force cap: elastic-perfectly-plastic, linear.

    Parameters
    ----------
    stiffness : float
        ``k`` [N/m], > 0.
    yield_force : float
        Force cap ``Fy`` [N], > 0. On a wall, ``e = min(1, Fy / (v sqrt(k m)))``.

    See Also
    --------
    linear_plastic_force
    """

    name = "linear_plastic"
    lammps_refusal = (
        "its force is capped at a yield force with a history of the largest overlap; no "
        "LAMMPS normal model has a force cap"
    )
    kratos_refusal = "its force is capped at a yield force; Kratos' elastic laws have no cap"
    has_history = True
    piecewise_linear = True
    units = read_only(stiffness="N/m", yield_force="N")
    stiffness_parameters = ("stiffness",)
    typical = read_only(stiffness=(1e3, 1e7, "log"), yield_force=(0.05, 20.0, "linear"))
    """The paper's impacts peak at a few N."""

    def __init__(self, stiffness, yield_force):
        self._keep(stiffness=(check_positive, stiffness), yield_force=(check_positive, yield_force))

    def _force(self, overlap, rate, max_overlap):
        d, d_max = with_history(overlap, max_overlap)
        return _linear_plastic_raw(d, d_max, self.stiffness, self.yield_force)

    def branch(self, name, max_overlap=0.0):
        k, f_y = self.stiffness, self.yield_force
        if name == "load":
            return Branch(
                "load",
                lambda d, r: k * d,
                (k, 0.0, 0.0),
                (rate_turns("unload"), overlap_reaches(f_y / k, "yield")),
            )
        if name == "yield":
            return Branch(
                "yield",
                lambda d, r: np.full_like(d, f_y),
                (0.0, 0.0, f_y),
                (rate_turns("unload"),),
            )
        f_max = min(k * max_overlap, f_y)
        return Branch(
            "unload",
            lambda d, r: f_max + k * (d - max_overlap),
            (k, 0.0, f_max - k * max_overlap),
            (overlap_reaches(max_overlap, "yield" if f_max >= f_y else "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return max_overlap - min(self.stiffness * max_overlap, self.yield_force) / self.stiffness, (
            "unload"
        )

    def _closed_forms(self, mass, velocity):
        """Restitution, contact time and peak force on a wall (energy balance)."""
        args = dict(
            stiffness=self.stiffness, yield_force=self.yield_force, mass=mass, velocity=velocity
        )
        elastic_peak = velocity * math.sqrt(self.stiffness * mass)
        restitution = analytic.linear_plastic_restitution
        contact_time = analytic.linear_plastic_contact_time
        return (
            closed_form("restitution", restitution, ENERGY_BALANCE, **args),
            closed_form("contact_time", contact_time, ENERGY_BALANCE, **args),
            ClosedForm(
                "peak_contact_force",
                min(self.yield_force, elastic_peak),
                f"min(Fy, v sqrt(k m*)) = min({self.yield_force:.6g}, {elastic_peak:.6g})",
                ENERGY_BALANCE,
            ),
        )


class Thornton(ContactLaw):
    """Thornton (1997) elastic-perfectly-plastic Hertz contact.

    Parameters
    ----------
    effective_modulus : float
        ``E*`` [Pa].
    effective_radius : float
        ``R*`` [m].
    yield_pressure : float
        Limiting contact pressure ``py`` [Pa].

    See Also
    --------
    thornton_force, contactlab.analytic.thornton_restitution
    """

    name = "thornton"
    lammps_refusal = (
        "its Hertz loading turns to a limiting contact pressure and unloads along a "
        "history-dependent Hertz curve; LAMMPS' mdr model is a different plastic law"
    )
    kratos_refusal = (
        "its Hertz loading turns to a limiting contact pressure; Kratos' plastic laws "
        "(DEM_D_Conical_damage, ...) are different laws"
    )
    has_history = True
    units = read_only(effective_modulus="Pa", effective_radius="m", yield_pressure="Pa")
    stiffness_parameters = ("effective_modulus",)
    typical = read_only(
        effective_modulus=(1e6, 1e8, "log"),
        effective_radius=(5e-4, 5e-3, "log"),
        yield_pressure=(1e5, 1e7, "log"),
    )

    def __init__(self, effective_modulus, effective_radius, yield_pressure):
        self._keep(
            effective_modulus=(check_positive, effective_modulus),
            effective_radius=(check_positive, effective_radius),
            yield_pressure=(check_positive, yield_pressure),
        )

    @classmethod
    def from_material(cls, material, yield_pressure, other=analytic.RIGID_FLAT):
        """Thornton law from the grain's :class:`~contactlab.analytic.Material` and the
        yield pressure [Pa]; a rigid flat unless ``other`` (as for
        :meth:`~contactlab.laws.Hertz.from_material`) is given."""
        modulus, radius = analytic.contact_modulus_radius(material, other)
        return cls(modulus, radius, yield_pressure)

    @property
    def _material(self):
        return self.effective_modulus, self.effective_radius, self.yield_pressure

    def _force(self, overlap, rate, max_overlap):
        d, d_max = with_history(overlap, max_overlap)
        return _thornton_raw(d, d_max, *self._material)

    def branch(self, name, max_overlap=0.0):
        modulus, radius, p_y = self._material
        d_y = analytic.thornton_yield_overlap(modulus, radius, p_y)
        if name == "load":
            k_hertz = analytic.hertz_stiffness(modulus, radius)
            return Branch(
                "load",
                lambda d, r: k_hertz * signed_power(d, 1.5),
                exits=(rate_turns("unload"), overlap_reaches(d_y, "yield")),
            )
        if name == "yield":
            f_y = analytic.thornton_yield_force(modulus, radius, p_y)
            k_p = math.pi * p_y * radius
            return Branch(
                "yield",
                lambda d, r: f_y + k_p * (d - d_y),
                (k_p, 0.0, f_y - k_p * d_y),
                (rate_turns("unload"),),
            )
        k_u, d_p = (float(v) for v in _thornton_unloading(max_overlap, *self._material))
        return Branch(
            "unload",
            lambda d, r: k_u * signed_power(d - d_p, 1.5),
            exits=(overlap_reaches(max_overlap, "yield" if max_overlap > d_y else "load"),),
            loading=False,
        )

    def reentry(self, max_overlap):
        if max_overlap <= 0.0:
            return 0.0, "load"
        return float(_thornton_unloading(max_overlap, *self._material)[1]), "unload"

    def _closed_forms(self, mass, velocity):
        """Restitution on a wall (Thornton 1997)."""
        modulus, radius, p_y = self._material
        return (
            closed_form(
                "restitution",
                analytic.thornton_restitution,
                THORNTON_1997,
                effective_modulus=modulus,
                effective_radius=radius,
                yield_pressure=p_y,
                mass=mass,
                velocity=velocity,
            ),
        )
