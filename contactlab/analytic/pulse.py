"""The paper's perfectly plastic trapezoidal pulse (Eqs. 7-8)."""

from contactlab.validation import check_number, check_positive

__all__ = ["plastic_trapezoid_amplitude"]


def plastic_trapezoid_amplitude(mass, velocity, contact_time, ramp_time):
    """Plateau force of the paper's perfectly plastic trapezoidal pulse.

    Parameters
    ----------
    mass : float
        Grain mass [kg].
    velocity : float
        Impact speed v [m/s].
    contact_time : float
        Total pulse duration t_k [s].
    ramp_time : float
        Duration of each linear rise and fall, in [0, t_k / 2] [s]; 0 is the rectangle of
        Eq. (7), t_k / 2 a triangle.

    Returns
    -------
    float
        F = m v / (t_k - t_r) [N], so that the impulse equals m v (restitution 0).

    References
    ----------
    .. [1] W. Keska, J. Marcinkiewicz, L. Gierz, Z. Staszak, J. Selech, K. Koszela,
       "Simulation verification of the contact parameter influence on the forces' course of
       cereal grain impact against a stiff surface", Appl. Sci. 11, 466 (2021), Eqs. (7)-(8).
       DOI: 10.3390/app11020466
    """
    m = check_positive("mass", mass, "kg")
    v = check_positive("velocity", velocity, "m/s")
    t_k = check_positive("contact_time", contact_time, "s")
    t_r = check_number("ramp_time", ramp_time, low=0.0, high=0.5 * t_k, low_open=False, unit="s")
    return m * v / (t_k - t_r)
