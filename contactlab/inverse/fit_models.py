"""The fittable laws: parameters, units, coordinate transforms, starting guesses."""

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import expit, logit

from contactlab import analytic
from contactlab.laws import Hertz, HertzDamped, LinearViscoelastic, WaltonBraun

__all__ = ["FIT_MODELS", "TRANSFORMS", "FitModel"]

TRANSFORMS = {
    # name: (to coordinate, from coordinate, d value / d coordinate); numpy functions so
    # that an unbounded confidence limit maps to 0 or inf instead of overflowing
    "log": (np.log, np.exp, np.exp),
    "logit": (logit, expit, lambda x: expit(x) * (1.0 - expit(x))),
}


@dataclass(frozen=True)
class FitModel:
    """How one contact law is fitted: its parameters, transforms, guess and law object.

    ``guess(grain, velocity, contact_time, restitution)`` gives starting values from a
    reconstructed pulse; ``build(values, grain)`` makes the law from fitted values;
    ``overlap_rebound(values, grain)``, for a law with a viscous damper, is the rebound on
    a rigid wall [-] of the same parameters in a DEM code whose damper may pull until the
    overlap is zero (MercuryDPM; the fitted law's own contact ends at zero force).
    """

    law: str
    parameters: tuple
    units: tuple
    transforms: tuple
    guess: object
    build: object
    overlap_rebound: object = None


def _hertz_stiffness(modulus, grain):
    return analytic.hertz_stiffness(modulus, grain.radius)


def _hertz_modulus_guess(grain, velocity, contact_time):
    """E* [Pa] of an elastic Hertz impact on a flat lasting ``contact_time`` [s].

    The Hertz contact time scales as ``E***(-2/5)``: invert it from a reference modulus.
    """
    reference = 1e6
    k_hertz = _hertz_stiffness(reference, grain)
    t_ref = analytic.hertz_contact_time(k_hertz, grain.mass, velocity)
    return reference * (t_ref / contact_time) ** 2.5


def _linear_guess(grain, velocity, contact_time, restitution):
    k = grain.mass * (math.pi / contact_time) ** 2
    c = analytic.linear_damping_from_restitution(k, restitution, grain.mass, convention="force")
    return {"stiffness": k, "damping": c}


def _hertz_damped_build(values, grain):
    k_hertz = _hertz_stiffness(values["effective_modulus"], grain)
    damping = analytic.tsuji_damping_coefficient(k_hertz, grain.mass, values["restitution"])
    return HertzDamped(k_hertz, damping)


def _walton_braun_guess(grain, velocity, contact_time, restitution):
    # t_c = (pi/2) sqrt(m/k1) (1 + e) with e = sqrt(k1/k2)
    k1 = grain.mass * (math.pi * (1.0 + restitution) / (2.0 * contact_time)) ** 2
    return {"loading_stiffness": k1, "restitution": restitution}


FIT_MODELS = {
    "linear": FitModel(
        "linear",
        ("stiffness", "damping"),
        ("N/m", "N*s/m"),
        ("log", "log"),
        _linear_guess,
        lambda v, grain: LinearViscoelastic(v["stiffness"], v["damping"]),
        lambda v, grain: analytic.linear_restitution(
            v["stiffness"], v["damping"], grain.mass, convention="overlap"
        ),
    ),
    "hertz": FitModel(
        "hertz",
        ("effective_modulus",),
        ("Pa",),
        ("log",),
        lambda grain, v, tc, e: {"effective_modulus": _hertz_modulus_guess(grain, v, tc)},
        lambda v, grain: Hertz(_hertz_stiffness(v["effective_modulus"], grain)),
    ),
    "hertz_damped": FitModel(
        "hertz_damped",
        ("effective_modulus", "restitution"),
        ("Pa", "-"),
        ("log", "logit"),
        lambda grain, v, tc, e: {
            "effective_modulus": _hertz_modulus_guess(grain, v, tc),
            "restitution": e,
        },
        _hertz_damped_build,
        # the Tsuji mapping realises its restitution exactly when contact ends at zero
        # overlap (analytic.tsuji_damping_factor)
        lambda v, grain: v["restitution"],
    ),
    "walton_braun": FitModel(
        "walton_braun",
        ("loading_stiffness", "restitution"),
        ("N/m", "-"),
        ("log", "logit"),
        _walton_braun_guess,
        lambda v, grain: WaltonBraun(
            v["loading_stiffness"], v["loading_stiffness"] / v["restitution"] ** 2
        ),
    ),
}
"""Fittable laws: registry name -> :class:`FitModel`.

``hertz_damped`` is fitted in the parameters the DEM codes take: the effective modulus
``E*`` [Pa] (Hertz stiffness ``4/3 E* sqrt(R)`` on the flat sensor) and the restitution
``e`` that the Tsuji/EDEM/LIGGGHTS mapping turns into the damping (overlap convention),
so the fitted pair goes into those codes unchanged. ``walton_braun`` is fitted as the
loading stiffness and ``e = sqrt(k_load / k_unload)``.
"""
