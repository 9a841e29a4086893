"""An impact-plate flow sensor's calibration curve and its error, ASABE S587 style.

An impact-plate yield sensor turns the mean force of a stream into a mass flow rate. Here
the sensor's **output** is the mean of ``S1`` over the stream's steady part (from the
lead time to the end). :func:`calibration_curve` runs the case at ``fractions`` of a
capacity [kg/s] twice with different seeds: the first set fits the straight line ``flow
= a output + b`` (least squares), the second is the test: the error at each fraction is
``(predicted - true) / true`` of the test run, as ASABE S587 reports it at 25, 50, 75
and 100 % of capacity.
"""

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from contactlab.entry_checks import check_callable, check_instance, check_shaped
from contactlab.errors import ParameterError
from contactlab.validation import check_number, check_values
from dem_check.stream.result import STREAM_RESULT, run_stream

__all__ = ["Calibration", "calibration_curve", "plate_output"]


def plate_output(result):
    """Mean sensor signal S1 [N] over the stream's steady part (after its lead time)."""
    check_shaped("result", result, ("steps", "lead"), STREAM_RESULT)
    steps = result.steps
    steady = steps["t [s]"] >= result.lead
    return float(steps.loc[steady, "sensor_force [N]"].mean())


@dataclass(frozen=True)
class Calibration:
    """A calibration: ``flow [kg/s] = slope * output [N] + intercept``.

    Attributes
    ----------
    slope : float
        [kg/(s*N)].
    intercept : float
        [kg/s].
    table : pandas.DataFrame
        Per fraction: ``fraction``, ``flow [kg/s]``, ``calibration_output [N]``,
        ``test_output [N]``, ``predicted_flow [kg/s]``, ``error [%]``.
    """

    slope: float
    intercept: float
    table: pd.DataFrame


def calibration_curve(case, capacity, fractions=(0.25, 0.5, 0.75, 1.0), run=None, seeds=(1, 2)):
    """Calibrate the plate on mass flows ``fractions * capacity`` and test it (module
    docstring).

    Parameters
    ----------
    case : StreamCase
        Its flow becomes a steady mass flow of each rate.
    capacity : float
        [kg/s].
    fractions : sequence of float
    run : callable, optional
        ``run(case) -> StreamResult`` (default :func:`~dem_check.stream.result.run_stream`).
    seeds : (int, int)
        Seeds of the calibration and the test runs.

    Returns
    -------
    Calibration
    """
    from dem_check.stream.case import StreamCase

    check_instance("case", case, StreamCase, "read_case or DEFAULT_CASE.with_")
    capacity = check_number("capacity", capacity, low=0.0, unit="kg/s")
    fractions = check_values("fractions", fractions, unit="-")
    run = check_callable("run", run, "run(case) -> StreamResult") or run_stream
    if (
        not isinstance(seeds, tuple | list)
        or len(seeds) != 2
        or seeds[0] == seeds[1]
        or not all(isinstance(s, int) and not isinstance(s, bool) and s >= 0 for s in seeds)
    ):
        raise ParameterError(f"seeds must be two different integers >= 0; got {seeds!r}")
    flows = fractions * capacity
    outputs = {}
    for seed in seeds:
        outputs[seed] = np.array(
            [
                plate_output(
                    run(
                        case.with_(
                            seed=seed,
                            flow=replace(case.flow, kind="mass", rate=float(f), profile="steady"),
                        )
                    )
                )
                for f in flows
            ]
        )
    fit, test = outputs[seeds[0]], outputs[seeds[1]]
    slope, intercept = np.polyfit(fit, flows, 1)
    predicted = slope * test + intercept
    table = pd.DataFrame(
        {
            "fraction": np.asarray(fractions, dtype=float),
            "flow [kg/s]": flows,
            "calibration_output [N]": fit,
            "test_output [N]": test,
            "predicted_flow [kg/s]": predicted,
            "error [%]": 100.0 * (predicted - flows) / flows,
        }
    )
    return Calibration(float(slope), float(intercept), table)
