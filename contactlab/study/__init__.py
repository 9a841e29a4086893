"""The Monte Carlo error study of Keska et al. (2021) and general parameter sweeps.

* :mod:`contactlab.study.setup`: the base impact, the stiffness scatter, grid parameters;
* :mod:`contactlab.study.points`: the impacts of grid points, one by one or batched;
* :mod:`contactlab.study.sweep`: sweeps and their per-point error statistics;
* :mod:`contactlab.study.execution`: serial, process-parallel and Dask execution;
* :mod:`contactlab.study.paper`: the paper's Figures 5-12 and its conclusions 2-5;
* :mod:`contactlab.study.design_map`: errors over resonance x diameter (a design map);
* :mod:`contactlab.study.plots`: the figures (matplotlib is imported only there).
"""

from contactlab.study.design_map import DesignMap, design_map
from contactlab.study.paper import PAPER_GRID, QUICK_GRID, PaperGrid, paper_study
from contactlab.study.setup import DISTRIBUTIONS, SIZE_DEPENDENCE, Scatter, StudySetup
from contactlab.study.sweep import (
    SweepResult,
    diameter_sweep,
    frequency_sweep,
    point_statistics,
    run_grid,
    simulate_point,
    simulate_points,
)

__all__ = [
    "DISTRIBUTIONS",
    "PAPER_GRID",
    "QUICK_GRID",
    "SIZE_DEPENDENCE",
    "DesignMap",
    "PaperGrid",
    "Scatter",
    "StudySetup",
    "SweepResult",
    "design_map",
    "diameter_sweep",
    "frequency_sweep",
    "paper_study",
    "point_statistics",
    "run_grid",
    "simulate_point",
    "simulate_points",
]
