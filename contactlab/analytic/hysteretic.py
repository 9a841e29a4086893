"""Walton-Braun hysteretic linear impacts: restitution and contact time."""

import math

from contactlab.validation import (
    check_number,
    check_positive,
)

__all__ = ["walton_braun_contact_time", "walton_braun_restitution"]


def _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness):
    k1 = check_positive("loading_stiffness", loading_stiffness, "N/m")
    k2 = check_number(
        "unloading_stiffness", unloading_stiffness, low=k1, low_open=False, unit="N/m"
    )
    return k1, k2


def walton_braun_restitution(loading_stiffness, unloading_stiffness):
    """Restitution of the Walton-Braun hysteretic linear law.

    Parameters
    ----------
    loading_stiffness : float
        Loading stiffness k1 [N/m].
    unloading_stiffness : float
        Unloading stiffness k2 >= k1 [N/m].

    Returns
    -------
    float
        e = sqrt(k1 / k2) [-].

    Notes
    -----
    Loading F = k1 d up to d_max = v sqrt(m/k1); unloading F = k2 (d - d0), released
    energy (k1 d_max)^2 / (2 k2).

    References
    ----------
    .. [1] O. R. Walton, R. L. Braun, "Viscosity, granular-temperature, and stress
       calculations for shearing assemblies of inelastic, frictional disks", J. Rheol. 30,
       949-980 (1986). DOI: 10.1122/1.549893
    """
    k1, k2 = _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness)
    return math.sqrt(k1 / k2)


def walton_braun_contact_time(loading_stiffness, unloading_stiffness, mass):
    """Contact time of the Walton-Braun hysteretic linear law.

    Parameters
    ----------
    loading_stiffness, unloading_stiffness : float
        k1 and k2 >= k1 [N/m], as for :func:`walton_braun_restitution`.
    mass : float
        Effective mass m* [kg].

    Returns
    -------
    float
        t_c = (pi/2) (sqrt(m/k1) + sqrt(m/k2)) [s]: a quarter period on each branch.

    References
    ----------
    .. [1] O. R. Walton, R. L. Braun, J. Rheol. 30, 949-980 (1986). DOI: 10.1122/1.549893
    """
    k1, k2 = _walton_braun_stiffnesses(loading_stiffness, unloading_stiffness)
    m = check_positive("mass", mass, "kg")
    return 0.5 * math.pi * (math.sqrt(m / k1) + math.sqrt(m / k2))
