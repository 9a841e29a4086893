"""Hypothesis strategies for contact-law tests: grains, sensors, laws and impact speeds.

Ranges are physically sensible for seeds and grains striking force sensors; quantities
spanning decades are drawn evenly in log scale. Needs ``hypothesis`` (the ``test`` extra)::

    from hypothesis import given
    from contactlab.testing.strategies import grains, impact_velocities, laws

    @given(grain=grains(), law=laws(), velocity=impact_velocities())
    def test_restitution_is_a_fraction(grain, law, velocity):
        assert 0.0 <= wall_restitution(law, grain.mass, velocity) <= 1.0 + 1e-9
"""

import math
from collections.abc import Mapping

from hypothesis import strategies as st

from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import (
    LAWS,
    Hertz,
    HertzDamped,
    HuntCrossley,
    KuwabaraKono,
    LinearPlastic,
    LinearViscoelastic,
    Mindlin,
    PlasticTrapezoid,
    TangentialSpring,
    Thornton,
    WaltonBraun,
)
from contactlab.validation import check_choice, check_number

__all__ = [
    "LAW_STRATEGIES",
    "grains",
    "hertz_damped_laws",
    "hertz_laws",
    "hunt_crossley_laws",
    "impact_velocities",
    "kuwabara_kono_laws",
    "law_strategy",
    "laws",
    "linear_laws",
    "linear_plastic_laws",
    "normal_impacts",
    "oblique_impacts",
    "plastic_trapezoid_laws",
    "restitution_laws",
    "sensors",
    "tangential_laws",
    "thornton_laws",
    "walton_braun_laws",
]


def _bounds(name, bounds, unit, low=0.0, low_open=True, high=None):
    """Check a ``(low, high)`` pair of bounds inside the quantity's own range; return it as
    floats, so that a strategy asking for impossible values fails when it is built, not
    while drawing."""
    if not isinstance(bounds, tuple) or len(bounds) != 2:
        raise ParameterError(f"{name} must be a (low, high) tuple [{unit}]; got {bounds!r}")
    lo = check_number(f"{name}[0]", bounds[0], low=low, low_open=low_open, high=high, unit=unit)
    hi = check_number(f"{name}[1]", bounds[1], low=lo, low_open=False, high=high, unit=unit)
    return lo, hi


def _log_floats(low, high):
    """Floats spread evenly in log scale over ``[low, high]`` (both > 0)."""
    return st.floats(math.log10(low), math.log10(high)).map(lambda x: min(max(10.0**x, low), high))


def grains(
    diameter=(0.5e-3, 20e-3),
    density=(300.0, 3000.0),
    youngs_modulus=(1e6, 1e10),
    poisson_ratio=(0.1, 0.45),
):
    """Spherical grains with material data (so Hertz-family laws can be built from them).

    Parameters
    ----------
    diameter : (float, float), default (0.5 mm, 20 mm)
        Range of the diameter [m]: poppy seed and sand to beans.
    density : (float, float), default (300, 3000)
        Range of the density [kg/m**3]: light oilseeds and hulled seeds to mineral grains
        (quartz 2650); the paper's grain has 765.
    youngs_modulus : (float, float), default (1 MPa, 10 GPa)
        Range of Young's modulus [Pa], drawn in log scale: moist soft kernels (the
        paper's grain: 21.6 MPa) to dry hard grains.
    poisson_ratio : (float, float), default (0.1, 0.45)
        Range of the Poisson ratio [-].

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of :class:`contactlab.Grain`.
    """
    return st.builds(
        Grain,
        diameter=st.floats(*_bounds("diameter", diameter, "m")),
        density=st.floats(*_bounds("density", density, "kg/m**3")),
        youngs_modulus=_log_floats(*_bounds("youngs_modulus", youngs_modulus, "Pa")),
        poisson_ratio=st.floats(*_bounds("poisson_ratio", poisson_ratio, "-", low=-1.0, high=0.5)),
    )


def sensors(
    resonance=(10e3, 300e3),
    mass=(0.1e-3, 10e-3),
    damping_ratio=(0.0, 0.1),
    rigid=False,
):
    """Force sensors (moving mass on a spring and damper), optionally an immovable wall.

    Parameters
    ----------
    resonance : (float, float), default (10 kHz, 300 kHz)
        Range of the undamped resonance [Hz], log scale: the paper studies 20-200 kHz,
        commercial piezoelectric sensors have 20-70 kHz.
    mass : (float, float), default (0.1 g, 10 g)
        Range of the moving mass [kg], log scale (the paper's steel disc: 1.233 g).
    damping_ratio : (float, float), default (0, 0.1)
        Range of the damping ratio [-] (quartz sensors: 0.01-0.05).
    rigid : bool, default False
        Whether :meth:`contactlab.Sensor.rigid` may be drawn too.

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of :class:`contactlab.Sensor`.
    """
    moving = st.builds(
        Sensor.from_resonance,
        resonance=_log_floats(*_bounds("resonance", resonance, "Hz")),
        mass=_log_floats(*_bounds("mass", mass, "kg")),
        damping_ratio=st.floats(*_bounds("damping_ratio", damping_ratio, "-", low_open=False)),
    )
    return st.one_of(moving, st.builds(Sensor.rigid)) if rigid else moving


def impact_velocities(low=0.1, high=10.0):
    """Impact speeds [m/s]: drops of 0.5 mm to 5 m, and throwers (up to 10 m/s in the paper).

    Parameters
    ----------
    low, high : float, default 0.1, 10
        Range of the speed [m/s].

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of float.
    """
    return st.floats(*_bounds("impact speed", (low, high), "m/s"))


def law_strategy(cls):
    """Laws of class ``cls`` drawn over the ranges it states (``cls.typical``: decades in
    log scale) and built by ``cls._from_typical``.

    Parameters
    ----------
    cls : type
        A law class of :mod:`contactlab.laws`.

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of ``cls`` laws.
    """
    drawn = {
        name: _log_floats(low, high) if scale == "log" else st.floats(low, high)
        for name, (low, high, scale) in cls.typical.items()
    }
    return st.builds(cls._from_typical, **drawn)


def _named(cls):
    def strategy():
        return law_strategy(cls)

    strategy.__name__ = strategy.__qualname__ = f"{cls.name}_laws"
    strategy.__doc__ = (
        f":class:`~contactlab.laws.{cls.__name__}` over its typical ranges "
        f"(``{cls.__name__}.typical``)."
    )
    return strategy


linear_laws = _named(LinearViscoelastic)
hertz_laws = _named(Hertz)
hertz_damped_laws = _named(HertzDamped)
kuwabara_kono_laws = _named(KuwabaraKono)
hunt_crossley_laws = _named(HuntCrossley)
walton_braun_laws = _named(WaltonBraun)
linear_plastic_laws = _named(LinearPlastic)
thornton_laws = _named(Thornton)
plastic_trapezoid_laws = _named(PlasticTrapezoid)


class _LawStrategies(Mapping):
    """Law name -> strategy function, for every law of :data:`contactlab.laws.LAWS`
    (a live view: a law registered there has its strategy here)."""

    def __getitem__(self, name):
        return _named(LAWS[name])

    def __iter__(self):
        return iter(LAWS)

    def __len__(self):
        return len(LAWS)


LAW_STRATEGIES = _LawStrategies()
"""Registry: law name (as in :data:`contactlab.laws.LAWS`) -> strategy function."""


def laws(name=None):
    """Contact laws with valid, physically sensible parameters.

    Parameters
    ----------
    name : str, optional
        A law name from :data:`contactlab.laws.LAWS` for that law only. Default: any law
        that is a force of overlap (every law but the prescribed ``plastic_trapezoid``
        pulse, which has no force-overlap relation to check).

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of contact laws.
    """
    if name is not None:
        return LAW_STRATEGIES[check_choice("law", name, tuple(LAW_STRATEGIES))]()
    return st.one_of(*(law_strategy(cls) for cls in LAWS.values() if not cls.prescribed))


OBLIQUE_NORMAL_LAWS = ("linear", "hertz", "hertz_damped", "kuwabara_kono", "hunt_crossley")
"""The normal laws :func:`contactlab.simulate_oblique` accepts (laws without history)."""


def restitution_laws(grain, velocity, name=None, restitution=(0.05, 1.0)):
    """Normal laws without history for ``grain`` at ``velocity`` [m/s], set by a restitution.

    Linear (stiffness 1e3-1e7 N/m, damping for the restitution on a wall,
    ``LinearViscoelastic.from_restitution``), Hertz from the grain's material, damped Hertz
    (``HertzDamped.from_material`` with the restitution), Kuwabara-Kono with the
    dimensionless dissipation ``x = 1.5 A (kH/m)**0.4 v**0.2`` up to ``-ln(e_min)`` and
    Hunt-Crossley with ``chi v`` up to ``1 / e_min`` (both reach restitutions near
    ``e_min``), Hertz exponent 1.5 and the grain's kH.

    Parameters
    ----------
    grain : Grain
        With material data.
    velocity : float
        Impact speed [m/s] the restitution refers to.
    name : str, optional
        One of :data:`OBLIQUE_NORMAL_LAWS`; default any.
    restitution : (float, float), default (0.05, 1)
        Range of the restitution [-].

    Returns
    -------
    hypothesis.strategies.SearchStrategy
    """
    lo, hi = _bounds("restitution", restitution, "-", high=1.0)
    e = st.floats(lo, hi)
    mass = grain.mass
    k_hertz = Hertz.from_material(grain.material()).k_hertz
    scale = 1.5 * (k_hertz / mass) ** 0.4 * velocity**0.2
    options = {
        "linear": st.builds(
            LinearViscoelastic.from_restitution,
            _log_floats(*LinearViscoelastic.typical["stiffness"][:2]),
            e,
            st.just(mass),
            st.just("force"),
        ),
        "hertz": st.just(Hertz(k_hertz)),
        "hertz_damped": e.map(
            lambda r: HertzDamped.from_material(grain.material(), restitution=r, mass=mass)
        ),
        "kuwabara_kono": st.floats(0.0, -math.log(lo)).map(
            lambda x: KuwabaraKono(k_hertz, x / scale)
        ),
        "hunt_crossley": st.floats(0.0, 1.0 / lo).map(
            lambda chi_v: HuntCrossley(k_hertz, 1.5, chi_v / velocity)
        ),
    }
    if name is not None:
        return options[check_choice("law", name, OBLIQUE_NORMAL_LAWS)]
    return st.one_of(*options.values())


def tangential_laws(grain, friction=(0.0, 1.0)):
    """Tangential laws for ``grain``: a Cundall-Strack spring (stiffness 1e3-1e7 N/m, log
    scale, damping ratio 0-0.5 of ``2 sqrt(m k)``, or none) and Mindlin from the grain's
    material in both history forms.

    Parameters
    ----------
    grain : Grain
        With material data.
    friction : (float, float), default (0, 1)
        Range of the Coulomb friction coefficient [-].

    Returns
    -------
    hypothesis.strategies.SearchStrategy
    """
    mu = st.floats(*_bounds("friction", friction, "-", low_open=False))
    spring = st.builds(
        lambda k, mu, zeta: TangentialSpring(k, mu, zeta * 2.0 * math.sqrt(grain.mass * k)),
        _log_floats(*LinearViscoelastic.typical["stiffness"][:2]),
        mu,
        st.one_of(st.just(0.0), st.floats(0.0, 0.5)),
    )
    mindlin = st.builds(
        lambda mu, history: Mindlin.from_material(grain.material(), mu, history=history),
        mu,
        st.sampled_from(("total", "incremental")),
    )
    return st.one_of(spring, mindlin)


@st.composite
def oblique_impacts(draw, normal=None, sensor_resonance=(5e3, 300e3), spin_ratio=3.0):
    """Oblique impacts over the ranges users have, as keyword arguments of
    :func:`contactlab.simulate_oblique`.

    Grains 1-10 mm (:func:`grains`), a flat or a sensor of 5-300 kHz (:func:`sensors`),
    a normal law of :func:`restitution_laws` (restitution 0.05-1 in a normal impact at the
    impact speed: near grazing incidence the normal speed is far smaller, and a
    Hunt-Crossley damping set for it would be absurd), a tangential law of
    :func:`tangential_laws` (friction 0-1), speed 0.1-10 m/s, incidence in [0, 90) deg and
    spin up to ``spin_ratio`` times ``V / R`` either way.

    Parameters
    ----------
    normal : str, optional
        Only this normal law (a name of :data:`OBLIQUE_NORMAL_LAWS`).
    sensor_resonance : (float, float), default (5 kHz, 300 kHz)
        Range of the sensor resonance [Hz].
    spin_ratio : float, default 3
        Largest ``|spin| R / V`` [-].

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of dicts with ``grain``, ``sensor``, ``normal_law``, ``tangential_law``,
        ``velocity`` [m/s], ``angle`` [rad] and ``spin`` [rad/s].
    """
    grain = draw(grains(diameter=(1e-3, 10e-3)))
    velocity = draw(impact_velocities(0.1, 10.0))
    angle = draw(st.floats(0.0, math.pi / 2, exclude_max=True))
    ratio = check_number("spin_ratio", spin_ratio, low=0.0, low_open=False, unit="-")
    return {
        "grain": grain,
        "sensor": draw(sensors(resonance=sensor_resonance, rigid=True)),
        "normal_law": draw(restitution_laws(grain, velocity, normal)),
        "tangential_law": draw(tangential_laws(grain)),
        "velocity": velocity,
        "angle": angle,
        "spin": draw(st.floats(-ratio, ratio)) * velocity / grain.radius,
    }


def normal_impacts(sensor_resonance=(5e3, 300e3)):
    """Normal impacts over the ranges users have, as keyword arguments of
    :func:`contactlab.simulate_impact`: grains 1-10 mm, a flat or a sensor of
    ``sensor_resonance`` [Hz], every law of :data:`LAW_STRATEGIES` (the prescribed pulse
    included), 0.1-10 m/s.

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of dicts with ``grain``, ``sensor``, ``law`` and ``velocity`` [m/s].
    """
    return st.fixed_dictionaries(
        {
            "grain": grains(diameter=(1e-3, 10e-3)),
            "sensor": sensors(resonance=sensor_resonance, rigid=True),
            "law": st.one_of(laws(), laws("plastic_trapezoid")),
            "velocity": impact_velocities(0.1, 10.0),
        }
    )
