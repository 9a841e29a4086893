"""Design map: the sensor's force and contact-time errors over resonance x grain diameter.

Each point of the map is one impact at the set-up's nominal law (no scatter): the grain of
that diameter (same density) strikes a sensor of that resonance (same moving mass and
damping ratio), and the errors are those an experimenter makes reading the sensor
signal's first lobe instead of the true force:

* ``force_error [%] = 100 (peak S1 / peak S2 - 1)``;
* ``time_error [%] = 100 (response time / contact time - 1)``.

These are the definitions of :func:`contactlab.study.simulate_point`
(:func:`~contactlab.study.points.error_percent`). A linear law
(the paper's) is solved for the whole map at once by
:func:`contactlab.batch.linear_impacts` (exact, the single solver's numbers to 1e-9);
any other law goes through :func:`contactlab.study.simulate_point` point by point (both
through :func:`contactlab.study.points.simulate_points`).
"""

from dataclasses import dataclass

import numpy as np
import pandas as pd

from contactlab.errors import ParameterError
from contactlab.study.points import simulate_points
from contactlab.study.setup import StudySetup
from contactlab.validation import check_choice, check_number, check_values

__all__ = [
    "DEFAULT_DIAMETERS",
    "DEFAULT_RESONANCES",
    "PAPER_OPERATING_POINTS",
    "DesignMap",
    "design_map",
]

DEFAULT_RESONANCES = tuple(np.geomspace(10e3, 300e3, 41))
"""Sensor resonances of the default map [Hz]: 10-300 kHz, log-spaced (the study's range)."""

DEFAULT_DIAMETERS = tuple(np.round(np.arange(1.0, 10.001, 0.25), 2) * 1e-3)
"""Grain diameters of the default map [m]: 1-10 mm (Figure 12's range), 0.25 mm apart."""

PAPER_OPERATING_POINTS = tuple(
    (resonance, diameter)
    for diameter in (5.0e-3, 2.5e-3)
    for resonance in (20e3, 40e3, 70e3, 200e3)
)
"""``(resonance [Hz], diameter [m])`` pairs the paper discusses: commercial sensors at 20,
40 and 70 kHz and special designs at 200 kHz (Section 2.2), for its 5 mm grain and the
2.5 mm grain of Figures 10-11."""

_COLUMNS = (
    "contact_time [s]",
    "sensor_response_time [s]",
    "peak_contact_force [N]",
    "peak_sensor_force [N]",
    "force_error [%]",
    "time_error [%]",
)


def _grid(name, values, unit):
    values = check_values(name, values, unit=unit)
    if np.any(np.diff(values) <= 0.0):
        raise ParameterError(f"{name} must be strictly increasing [{unit}]")
    return values


@dataclass(frozen=True)
class DesignMap:
    """Errors of the sensor reading over a resonance x diameter grid.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per grid point: ``resonance [Hz]``, ``diameter [m]``, the impact's
        ``contact_time [s]``, ``sensor_response_time [s]``, ``peak_contact_force [N]``,
        ``peak_sensor_force [N]`` and the two errors ``force_error [%]``,
        ``time_error [%]``; resonance varies fastest.
    resonances, diameters : numpy.ndarray
        The grid axes [Hz], [m].
    law : str
        The set-up's law, as ``repr``.
    """

    table: pd.DataFrame
    resonances: np.ndarray
    diameters: np.ndarray
    law: str

    def grid(self, column):
        """``column`` as an array of shape (diameters, resonances)."""
        check_choice("column", column, tuple(self.table.columns))
        return self.table[column].to_numpy().reshape(self.diameters.size, self.resonances.size)

    def plot(self, tolerance=10.0):
        """Both errors as colour maps, with the ``+-tolerance`` [%] contours and the paper's
        operating points (:data:`PAPER_OPERATING_POINTS`); returns (fig, axes)."""
        from contactlab.study.plots import plot_design_map

        tolerance = check_number("tolerance", tolerance, low=0.0, unit="%")
        return plot_design_map(self, PAPER_OPERATING_POINTS, tolerance)


def design_map(setup=None, resonances=DEFAULT_RESONANCES, diameters=DEFAULT_DIAMETERS):
    """Force and contact-time errors of the sensor reading over resonance x diameter.

    Parameters
    ----------
    setup : StudySetup, optional
        Grain, sensor (its mass and damping ratio are kept), law and impact speed;
        default :meth:`StudySetup.paper` (linear contact, k2 = 1e5 N/m, c2 = 1 N*s/m).
        With ``size_dependence="material"`` the law follows the grain's size.
    resonances : sequence of float, default :data:`DEFAULT_RESONANCES`
        Sensor resonances [Hz], increasing.
    diameters : sequence of float, default :data:`DEFAULT_DIAMETERS`
        Grain diameters [m], increasing.

    Returns
    -------
    DesignMap

    Examples
    --------
    >>> from contactlab.study import design_map
    >>> m = design_map(resonances=[20e3, 200e3], diameters=[2.5e-3, 5e-3])
    >>> m.grid("force_error [%]").shape
    (2, 2)
    """
    if setup is not None and not isinstance(setup, StudySetup):
        raise ParameterError(f"setup must be a StudySetup; got {type(setup).__name__}")
    setup = StudySetup.paper() if setup is None else setup
    resonances = _grid("resonances", resonances, "Hz")
    diameters = _grid("diameters", diameters, "m")
    points = [
        {"grain.diameter": float(d), "sensor.resonance": float(f)}
        for d in diameters
        for f in resonances
    ]
    impacts = simulate_points([(setup, point, [1.0]) for point in points])
    table = pd.DataFrame(
        {
            "resonance [Hz]": [p["sensor.resonance"] for p in points],
            "diameter [m]": [p["grain.diameter"] for p in points],
            **{name: [row[name][0] for row in impacts] for name in _COLUMNS},
        }
    )
    return DesignMap(table, resonances, diameters, repr(setup.law))
