"""Hertz-family impacts: elastic Hertz, Tsuji damping, Kuwabara-Kono, Hunt-Crossley."""

import math

from scipy.optimize import brentq
from scipy.special import beta, gamma

from contactlab.analytic.conventions import check_convention, check_restitution
from contactlab.analytic.linear import _LINEAR_SOLUTIONS, _damping_ratio_from_restitution
from contactlab.errors import ParameterError
from contactlab.validation import (
    check_non_negative,
    check_positive,
)

__all__ = [
    "HERTZ_TIME_FACTOR",
    "HUNT_CROSSLEY_SERIES",
    "KUWABARA_KONO_C1",
    "KUWABARA_KONO_C2",
    "KUWABARA_KONO_MAX_PARAMETER",
    "hertz_contact_time",
    "hertz_max_force",
    "hertz_max_overlap",
    "hunt_crossley_restitution",
    "hunt_crossley_restitution_linearised",
    "kuwabara_kono_parameter",
    "kuwabara_kono_restitution",
    "tsuji_damping_coefficient",
    "tsuji_damping_factor",
    "tsuji_restitution",
]


#: Hertz contact time in units of d_max / v: 2 * integral_0^1 du / sqrt(1 - u^(5/2)).
HERTZ_TIME_FACTOR = 2.0 * math.sqrt(math.pi) * gamma(7 / 5) / gamma(9 / 10)

#: First two coefficients of the Kuwabara-Kono restitution series (Ramirez et al. 1999).
KUWABARA_KONO_C1 = 0.8 * 1.25**0.6 * beta(3 / 5, 3 / 2)
KUWABARA_KONO_C2 = 0.6 * KUWABARA_KONO_C1**2

#: Largest Kuwabara-Kono parameter accepted: the two-term series has its minimum there.
KUWABARA_KONO_MAX_PARAMETER = KUWABARA_KONO_C1 / (2.0 * KUWABARA_KONO_C2)


def _hertz_impact(k_hertz, mass, velocity):
    """``(kH [N/m^1.5], m* [kg], v [m/s])`` of a Hertz impact, each checked positive."""
    return (
        check_positive("k_hertz", k_hertz, "N/m^1.5"),
        check_positive("mass", mass, "kg"),
        check_positive("velocity", velocity, "m/s"),
    )


def hertz_max_overlap(k_hertz, mass, velocity):
    """Largest overlap of an elastic Hertz impact.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5] (:func:`hertz_stiffness`).
    mass : float
        Effective mass m* [kg].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        d_max [m].

    Notes
    -----
    Energy balance m v^2 / 2 = (2/5) kH d_max^(5/2) gives
    d_max = (5 m v^2 / (4 kH))^(2/5) = (15 m v^2 / (16 E* sqrt(R*)))^(2/5).

    References
    ----------
    .. [1] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, Sec. 11.1.
    """
    k, m, v = _hertz_impact(k_hertz, mass, velocity)
    return (1.25 * m * v**2 / k) ** 0.4


def hertz_max_force(k_hertz, mass, velocity):
    """Peak force F_max = kH d_max^(3/2) [N] of an elastic Hertz impact of kH [N/m^1.5],
    m* [kg] and v [m/s], with d_max from :func:`hertz_max_overlap` (same arguments)."""
    return k_hertz * hertz_max_overlap(k_hertz, mass, velocity) ** 1.5


def hertz_contact_time(k_hertz, mass, velocity):
    """Duration of an elastic Hertz impact.

    Parameters
    ----------
    k_hertz, mass, velocity : float
        kH [N/m^1.5], m* [kg], v [m/s], as for :func:`hertz_max_overlap`.

    Returns
    -------
    float
        Contact time t_c [s].

    Notes
    -----
    With u = d/d_max the speed is v sqrt(1 - u^(5/2)), so

    t_c = 2 (d_max/v) integral_0^1 du / sqrt(1 - u^(5/2))
        = 2 sqrt(pi) Gamma(7/5) / Gamma(9/10) * d_max / v = 2.943275 d_max / v
        = 2.868266 (m*^2 / (R* E*^2 v))^(1/5).

    The grain of the reference paper (E = 2 * 9 MPa * 1.2, nu = 0.2, 765 kg/m^3, rigid
    flat, v = 2 m/s) gives 180.6 us for a 5.0 mm diameter and 90.3 us for 2.5 mm.

    References
    ----------
    .. [1] H. Hertz, "Ueber die Beruehrung fester elastischer Koerper", J. reine angew.
       Math. 92, 156-171 (1882). DOI: 10.1515/crll.1882.92.156
    .. [2] K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, Eq. (11.24).
    """
    d_max = hertz_max_overlap(k_hertz, mass, velocity)
    return HERTZ_TIME_FACTOR * d_max / velocity


def tsuji_damping_factor(restitution, convention="overlap"):
    """Damping factor alpha of the Tsuji/EDEM/LIGGGHTS damped Hertz law for a restitution.

    The law is F = kH d^(3/2) + alpha sqrt(m* kH) d^(1/4) d'.

    Parameters
    ----------
    restitution : float
        Target coefficient of restitution, in (0, 1] [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends. ``"overlap"`` returns the factor the DEM codes use.

    Returns
    -------
    float
        alpha [-].

    Notes
    -----
    ``"overlap"``: alpha = sqrt(5) (-ln e) / sqrt(pi^2 + ln^2 e), the EDEM/LIGGGHTS formula
    (LIGGGHTS writes gamma_n = 2 sqrt(5/6) beta sqrt(S_n m*) with S_n = 2 E* sqrt(R* d)).
    It realises e *exactly*, at every speed, when contact ends at zero overlap: with
    w = u^(5/4) and d(sigma) = u^(1/4) d(tau) the scaled law (see :func:`tsuji_restitution`)
    becomes the linear oscillator w'' + alpha w' + (5/4) w = 0, whose damping ratio is
    alpha / sqrt(5) (Antypov & Elliott 2011). The one-sided force of that oscillator is
    the law's force divided by u^(1/4), so ``"force"`` maps onto the linear ``"force"``
    result too: alpha = sqrt(5) zeta_force(e), from :func:`linear_damping_from_restitution`.

    References
    ----------
    .. [1] Y. Tsuji, T. Tanaka, T. Ishida, "Lagrangian numerical simulation of plug flow of
       cohesionless particles in a horizontal pipe", Powder Technol. 71, 239-250 (1992).
       DOI: 10.1016/0032-5910(92)88030-L
    .. [2] D. Antypov, J. A. Elliott, "On an analytical solution for the damped Hertzian
       spring", EPL 94, 50004 (2011). DOI: 10.1209/0295-5075/94/50004
    """
    e = check_restitution(restitution)
    return math.sqrt(5.0) * _damping_ratio_from_restitution(e, check_convention(convention))


def tsuji_damping_coefficient(k_hertz, mass, restitution, convention="overlap"):
    """Damping coefficient eta of F = kH d^(3/2) + eta d^(1/4) d' for a restitution.

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    mass : float
        Effective mass m* [kg].
    restitution : float
        Target coefficient of restitution, in (0, 1] [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends; see :func:`tsuji_damping_factor`.

    Returns
    -------
    float
        eta = alpha sqrt(m* kH) [N*s/m^1.25].
    """
    k = check_positive("k_hertz", k_hertz, "N/m^1.5")
    m = check_positive("mass", mass, "kg")
    return tsuji_damping_factor(restitution, convention) * math.sqrt(m * k)


def tsuji_restitution(alpha, convention="overlap"):
    """Restitution realised by the Tsuji/EDEM damped Hertz law for a damping factor alpha.

    Parameters
    ----------
    alpha : float
        Damping factor in F = kH d^(3/2) + alpha sqrt(m* kH) d^(1/4) d' [-].
    convention : {"overlap", "force"}, default "overlap"
        When contact ends (see the module docstring).

    Returns
    -------
    float
        Coefficient of restitution [-]; 0 under ``"overlap"`` for alpha >= sqrt(5) (the
        overlap never returns to zero).

    Notes
    -----
    Scaling d = L u, t = (L/v) tau with L^(5/2) = m* v^2 / kH turns the law into
    u'' = -(u^(3/2) + alpha u^(1/4) u'), u(0) = 0, u'(0) = 1, so e depends on alpha only:
    not on kH, m* or v. With w = u^(5/4) and d(sigma) = u^(1/4) d(tau) this is exactly the
    linear oscillator w'' + alpha w' + (5/4) w = 0 (u' = (4/5) dw/dsigma), so e is the
    linear spring-dashpot result (:func:`linear_restitution`) at zeta = alpha / sqrt(5),
    under the same convention. This is exact; no integration is needed. The test suite
    checks it against direct integration of m x'' = -(kH x^1.5 + eta x^0.25 x')
    (DOP853, rtol 1e-11). Realised e for alpha from :func:`tsuji_damping_factor`
    (``"overlap"`` mapping):

    ========  ==========  ===========  ========
    target e  alpha       "overlap"    "force"
    ========  ==========  ===========  ========
    0.3       0.800193    0.3          0.397140
    0.5       0.481769    0.5          0.550283
    0.7       0.252247    0.7          0.718201
    0.9       0.0749495   0.9          0.902026
    ========  ==========  ===========  ========

    So the EDEM mapping assumes contact ends at zero overlap; with a one-sided (``"force"``)
    contact the grain rebounds faster than asked (Thornton et al. 2013 report the same
    dependence on alpha only).

    References
    ----------
    .. [1] D. Antypov, J. A. Elliott, "On an analytical solution for the damped Hertzian
       spring", EPL 94, 50004 (2011). DOI: 10.1209/0295-5075/94/50004
    .. [2] C. Thornton, S. J. Cummins, P. W. Cleary, "An investigation of the comparative
       behaviour of alternative contact force models during inelastic collisions",
       Powder Technol. 233, 30-46 (2013). DOI: 10.1016/j.powtec.2012.08.012
    """
    a = check_non_negative("alpha", alpha, "-")
    _, log_e = _LINEAR_SOLUTIONS[check_convention(convention)](a / math.sqrt(5.0))
    return math.exp(log_e)


def kuwabara_kono_parameter(k_hertz, dissipation, mass, velocity):
    """Dimensionless dissipation of F = kH (d^(3/2) + (3/2) A d^(1/2) d').

    Parameters
    ----------
    k_hertz : float
        Hertz stiffness kH [N/m^1.5].
    dissipation : float
        Dissipative constant A [s].
    mass, velocity : float
        m* [kg] and v [m/s], as for :func:`hertz_max_overlap`.

    Returns
    -------
    float
        x = (3/2) A (kH/m*)^(2/5) v^(1/5) [-].

    Notes
    -----
    Scaling d = L u, t = (L/v) tau with L^(5/2) = m* v^2 / kH gives
    u'' = -(u^(3/2) + x u^(1/2) u'): the restitution depends on x alone.
    """
    a = check_non_negative("dissipation", dissipation, "s")
    k, m, v = _hertz_impact(k_hertz, mass, velocity)
    return 1.5 * a * (k / m) ** 0.4 * v**0.2


def kuwabara_kono_restitution(k_hertz, dissipation, mass, velocity):
    """Restitution of the Kuwabara-Kono viscoelastic Hertz law (small-dissipation series).

    Parameters
    ----------
    k_hertz, dissipation, mass, velocity : float
        kH [N/m^1.5], A [s], m* [kg], v [m/s], as for :func:`kuwabara_kono_parameter`.

    Returns
    -------
    float
        e = 1 - C1 x + C2 x^2 [-], x from :func:`kuwabara_kono_parameter`.

    Raises
    ------
    ParameterError
        If x > C1 / (2 C2) = 0.7225, where the two-term series turns upwards.

    Notes
    -----
    C1 = sqrt(pi) Gamma(3/5) / (2^(1/5) 5^(2/5) Gamma(21/10)) = 1.1534489 (first-order
    dissipated energy along the elastic Hertz path) and C2 = (3/5) C1^2 = 0.7982666; the
    published values are 1.15344 and 0.79826.

    The series is the expansion of the ``"overlap"`` convention. Against direct integration
    (DOP853, rtol 1e-12) its error is about +0.52 x^3 (the next term):

    =====  ==============  =================
    x      e - "overlap"   e - "force"
    =====  ==============  =================
    0.01   +5.2e-7         -2.1e-6
    0.05   +6.3e-5         -7.4e-5
    0.1    +4.9e-4         -2.2e-4
    0.2    +3.7e-3         +2.8e-4
    0.5    +4.9e-2         +2.8e-2
    =====  ==============  =================

    Under ``"force"`` the realised e is larger by about 0.26 x^(5/2) (for small x), an
    error of lower order than the series' own; the smaller ``"force"`` errors near
    x = 0.1-0.2 are a cancellation, not a better match.

    References
    ----------
    .. [1] G. Kuwabara, K. Kono, "Restitution coefficient in a collision between two
       spheres", Jpn. J. Appl. Phys. 26, 1230-1233 (1987). DOI: 10.1143/JJAP.26.1230
    .. [2] T. Schwager, T. Poeschel, "Coefficient of normal restitution of viscous particles
       and cooling rate of granular gases", Phys. Rev. E 57, 650-654 (1998).
       DOI: 10.1103/PhysRevE.57.650
    .. [3] R. Ramirez, T. Poeschel, N. V. Brilliantov, T. Schwager, "Coefficient of
       restitution of colliding viscoelastic spheres", Phys. Rev. E 60, 4465-4472 (1999).
       DOI: 10.1103/PhysRevE.60.4465
    """
    x = kuwabara_kono_parameter(k_hertz, dissipation, mass, velocity)
    if x > KUWABARA_KONO_MAX_PARAMETER:
        raise ParameterError(
            f"dissipation gives the Kuwabara-Kono parameter x = {x:g}, outside the range of "
            f"the series x <= {KUWABARA_KONO_MAX_PARAMETER:.4f}; integrate the law instead"
        )
    return 1.0 - KUWABARA_KONO_C1 * x + KUWABARA_KONO_C2 * x**2


def _x_minus_log1p(w):
    """w - ln(1 + w) for w > -1, free of the cancellation the direct form has at small |w|."""
    if abs(w) > 0.25:
        return w - math.log1p(w)
    return math.fsum((-w) ** k / k for k in range(2, 40))


HUNT_CROSSLEY_SERIES = 1e-6
"""Below this ``y = 1.5 chi v`` [-], :func:`hunt_crossley_restitution` is the series
``e = 1 - 2/3 y + 4/9 y**2``, whose remainder (about ``y**3 / 3``) is below 1e-18."""


def _hunt_crossley_impact(damping, velocity):
    """``(chi [s/m], v [m/s])`` of a Hunt-Crossley impact, checked."""
    return check_non_negative("damping", damping, "s/m"), check_positive(
        "velocity", velocity, "m/s"
    )


def hunt_crossley_restitution(damping, velocity):
    """Exact restitution of the Hunt-Crossley law F = k d^n (1 + (3/2) chi d').

    Parameters
    ----------
    damping : float
        Hunt-Crossley damping chi [s/m].
    velocity : float
        Impact speed v [m/s].

    Returns
    -------
    float
        Coefficient of restitution [-]; independent of k, n and the mass.

    Notes
    -----
    With lam = (3/2) chi, m v dv/dx = -k x^n (1 + lam v) separates; the first integral
    G(v) = v/lam - ln(1 + lam v)/lam^2 gives G(v_in) = G(-v_out) exactly, i.e. with
    y = lam v_in and z = lam v_out: y - ln(1 + y) = -z - ln(1 - z), solved by Brent's
    method for s = -ln(1 - z) (so that z -> 1 stays resolved). Since lam |d'| <= z < 1
    throughout, the force is positive until d = 0: both contact-end conventions give this
    result. For y >~ 40, z = 1 to double
    precision and e = 1/y. For small y, e = 1 - chi v + O((chi v)^2)
    (:func:`hunt_crossley_restitution_linearised`); below :data:`HUNT_CROSSLEY_SERIES`
    the series ``z / y = 1 - 2/3 y + 4/9 y^2 + O(y^3)`` (from ``z^2/2 + z^3/3 + ... =
    y^2/2 - y^3/3 + ...``) is exact to rounding.

    References
    ----------
    .. [1] K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping
       in vibroimpact", J. Appl. Mech. 42, 440-445 (1975). DOI: 10.1115/1.3423596
    """
    chi, v = _hunt_crossley_impact(damping, velocity)
    y = 1.5 * chi * v
    if y < HUNT_CROSSLEY_SERIES:
        # the root s ~ y lies far below Brent's [0, 1] bracket (y = 1e-151 did not converge
        # in 100 iterations; below 1e-154 the target underflows): the series instead
        return 1.0 - y * (2.0 / 3.0 - 4.0 / 9.0 * y)
    target = _x_minus_log1p(y)

    def excess(s):
        z = -math.expm1(-s)  # z = 1 - exp(-s); then -z - ln(1 - z) = s - z
        return (s - z if z > 0.25 else _x_minus_log1p(-z)) - target

    s = brentq(excess, 0.0, target + 1.0, xtol=1e-300)
    return -math.expm1(-s) / y


def hunt_crossley_restitution_linearised(damping, velocity):
    """Small-damping restitution of the Hunt-Crossley law, e = 1 - chi v.

    Parameters
    ----------
    damping, velocity : float
        chi [s/m], v [m/s], as for :func:`hunt_crossley_restitution`.

    Returns
    -------
    float
        1 - chi v [-].

    Raises
    ------
    ParameterError
        If chi v >= 1 (the linearised value would not be positive).

    Notes
    -----
    First-order expansion of :func:`hunt_crossley_restitution`: z = y (1 - 2y/3 + ...) with
    y = (3/2) chi v, hence e = 1 - chi v. This is Hunt & Crossley's lambda = (3/2) alpha
    relation with alpha = chi (the factor 3/2 in the law is chosen for it).

    References
    ----------
    .. [1] K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping
       in vibroimpact", J. Appl. Mech. 42, 440-445 (1975). DOI: 10.1115/1.3423596
    """
    chi, v = _hunt_crossley_impact(damping, velocity)
    if chi * v >= 1.0:
        raise ParameterError(
            f"damping * velocity must be < 1 for the linearised restitution; got {chi * v!r}"
        )
    return 1.0 - chi * v
