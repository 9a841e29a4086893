"""Normal contact laws between a grain and a flat (or another grain).

One module per family, each a plain vectorised force function first and a class that
gathers and checks its parameters:

* :mod:`~contactlab.laws.base`: the sign convention, :class:`ContactLaw`, branches;
* :mod:`~contactlab.laws.linear`: linear spring-dashpot (Kelvin-Voigt);
* :mod:`~contactlab.laws.hertz`: Hertz, damped Hertz (Tsuji), Kuwabara-Kono, Hunt-Crossley;
* :mod:`~contactlab.laws.hysteretic`: Walton-Braun;
* :mod:`~contactlab.laws.plastic`: linear spring with a force cap, Thornton;
* :mod:`~contactlab.laws.pulse`: the paper's prescribed trapezoid;
* :mod:`~contactlab.laws.tangential`: tangential laws (Cundall-Strack spring, Mindlin).

:data:`LAWS` maps the names used in TOML files and on the command line to the classes.
"""

from contactlab.errors import ParameterError
from contactlab.laws.base import Branch, ContactLaw, Exit, SmoothLaw
from contactlab.laws.hertz import (
    Hertz,
    HertzDamped,
    HuntCrossley,
    KuwabaraKono,
    hertz_damped_force,
    hertz_force,
    hunt_crossley_force,
    kuwabara_kono_force,
)
from contactlab.laws.hertz_viscous import HertzViscous
from contactlab.laws.hysteretic import WaltonBraun, walton_braun_force
from contactlab.laws.linear import LinearViscoelastic, linear_viscoelastic_force
from contactlab.laws.plastic import LinearPlastic, Thornton, linear_plastic_force, thornton_force
from contactlab.laws.pulse import PlasticTrapezoid, plastic_trapezoid_force
from contactlab.laws.tangential import (
    COULOMB_CAPS,
    DAMPING_FORMS,
    HISTORY_FORMS,
    TANGENTIAL_LAWS,
    Mindlin,
    TangentialLaw,
    TangentialSpring,
    damping_ratio,
    mindlin_stiffness,
)
from contactlab.validation import check_choice

__all__ = [
    "COULOMB_CAPS",
    "DAMPING_FORMS",
    "HISTORY_FORMS",
    "LAWS",
    "TANGENTIAL_LAWS",
    "Branch",
    "ContactLaw",
    "Exit",
    "Hertz",
    "HertzDamped",
    "HertzViscous",
    "HuntCrossley",
    "KuwabaraKono",
    "LinearPlastic",
    "LinearViscoelastic",
    "Mindlin",
    "PlasticTrapezoid",
    "SmoothLaw",
    "TangentialLaw",
    "TangentialSpring",
    "Thornton",
    "WaltonBraun",
    "damping_ratio",
    "get_law",
    "hertz_damped_force",
    "hertz_force",
    "hunt_crossley_force",
    "kuwabara_kono_force",
    "linear_plastic_force",
    "linear_viscoelastic_force",
    "mindlin_stiffness",
    "plastic_trapezoid_force",
    "thornton_force",
    "walton_braun_force",
]

LAWS = {
    cls.name: cls
    for cls in (
        LinearViscoelastic,
        Hertz,
        HertzDamped,
        HertzViscous,
        KuwabaraKono,
        HuntCrossley,
        WaltonBraun,
        LinearPlastic,
        Thornton,
        PlasticTrapezoid,
    )
}
"""Registry: law name (as used in TOML files and on the command line) -> class."""


def get_law(name, **parameters):
    """Build a law by registry name, e.g. ``get_law("linear", stiffness=1e5, damping=1.0)``.

    An unknown name raises :class:`~contactlab.errors.ParameterError` listing the valid
    ones (with a near-match suggestion).
    """
    cls = LAWS[check_choice("law", name, tuple(LAWS))]
    if not isinstance(parameters, dict):
        raise ParameterError("law parameters must be keyword arguments")
    return cls(**parameters)
