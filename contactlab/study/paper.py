"""The whole reproduction of Keska et al. (2021) in one call: figures, tables, verdicts.

:func:`paper_study` writes into one folder

* ``fig5`` ... ``fig9`` (.png, .svg): the impact courses of the presets in
  ``contactlab/data/presets``;
* ``fig10``, ``fig11``: errors against sensor resonance for d = 5.0 and 2.5 mm;
* ``fig12``: errors against grain diameter at 40 kHz; ``fig12_resonances``: the RMS force
  error against diameter for every resonance of the diameter sweep;
* ``error_vs_frequency.csv``, ``error_vs_diameter.csv``: one row per grid point
  (``*_impacts.csv``: one row per impact);
* ``summary.md``: the paper's conclusions 2-5, each reproduced or not, with the numbers.

Both sweeps run twice: with the paper's contact damping ``c2 = 1 N*s/m`` and with an
elastic contact (``c2 = 0``), because the damper's force step at first touch decides
whether the errors vanish at high resonance (see ``summary.md``). Each figure has one
panel per variant.
"""

import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from contactlab.config import list_presets, load_preset
from contactlab.entry_checks import check_flag
from contactlab.study import conclusions as concl
from contactlab.study.plots import check_formats, plot_error_family, plot_errors, save_figure
from contactlab.study.setup import Scatter, StudySetup
from contactlab.study.sweep import run_grid
from contactlab.validation import check_count, check_number, check_path, check_values

__all__ = ["PAPER_GRID", "QUICK_GRID", "PaperGrid", "PaperStudyResult", "paper_study"]


@dataclass(frozen=True)
class PaperGrid:
    """Grids of the paper study (the paper does not give its own).

    Attributes
    ----------
    resonances : tuple of float
        Sensor resonances of Figures 10-11 [Hz].
    sweep_diameters : tuple of float
        Grain diameters of Figures 10 and 11 [m].
    diameters : tuple of float
        Grain diameters of Figure 12 [m].
    diameter_resonances : tuple of float
        Sensor resonances of the diameter sweep [Hz]: 40 kHz (Figure 12), 70 kHz
        (commercial sensors), 200 kHz and above (special designs), for conclusions 4-5.
    dampings : tuple of float
        Contact damping variants [N*s/m]: the paper's 1.0 and an elastic contact.
    repetitions : int
        Impacts per grid point.
    """

    resonances: tuple
    sweep_diameters: tuple = (5.0e-3, 2.5e-3)
    diameters: tuple = tuple(np.round(np.arange(1.0, 10.01, 0.5), 2) * 1e-3)
    diameter_resonances: tuple = (40e3, 70e3, 200e3, 300e3)
    dampings: tuple = (1.0, 0.0)
    repetitions: int = 10

    def __post_init__(self):
        units = {"resonances": "Hz", "sweep_diameters": "m", "diameters": "m",
                 "diameter_resonances": "Hz"}  # fmt: skip
        for name, unit in units.items():
            values = check_values(name, getattr(self, name), unit=unit)
            object.__setattr__(self, name, tuple(values.tolist()))
        dampings = check_values("dampings", self.dampings, low_open=False, unit="N*s/m")
        object.__setattr__(self, "dampings", tuple(dampings.tolist()))
        object.__setattr__(self, "repetitions", check_count("repetitions", self.repetitions))

    @property
    def impacts(self):
        """Number of impacts of the whole study [-]."""
        per_variant = len(self.resonances) * len(self.sweep_diameters) + len(self.diameters) * len(
            self.diameter_resonances
        )
        return per_variant * len(self.dampings) * self.repetitions


PAPER_GRID = PaperGrid(resonances=tuple(np.geomspace(10e3, 300e3, 32)))
"""The full study: 32 resonances from 10 to 300 kHz (log-spaced), 19 diameters from 1 to
10 mm, 10 repetitions: 2 800 impacts."""

QUICK_GRID = PaperGrid(
    resonances=tuple(np.geomspace(10e3, 300e3, 5)),
    diameters=(1.0e-3, 2.0e-3, 5.0e-3, 8.0e-3),
    repetitions=3,
)
"""A coarse version for tests and previews (a few seconds)."""


@dataclass
class PaperStudyResult:
    """What :func:`paper_study` computed and wrote.

    Attributes
    ----------
    frequency, diameter : SweepResult
        The two sweeps.
    conclusions : list of Conclusion
        Verdicts on conclusions 2-5, per damping variant.
    presets : dict
        Preset name -> summary of its impact (``ImpactResult.summary()``, Figures 5-9).
    files : list of pathlib.Path
        Everything written.
    seconds : float
        Wall-clock time of the whole study [s].
    """

    frequency: object
    diameter: object
    conclusions: list
    presets: dict
    files: list = field(default_factory=list)
    seconds: float = 0.0

    def summary(self):
        """JSON-ready summary: verdicts, impact count, time and files."""
        return {
            "impacts": len(self.frequency.impacts) + len(self.diameter.impacts),
            "seconds [s]": self.seconds,
            "conclusions": [c.to_dict() for c in self.conclusions],
            "files": [str(p) for p in self.files],
        }


def _preset_figure(name, out, formats):
    """Simulate and draw one preset; returns (name, summary dict, files)."""
    res = load_preset(name).simulate()
    fig, _ = res.plot(title=f"{name}: {type(res.law).__name__}, {res.sensor.resonance / 1e3:g} kHz")
    return name, res.summary(), save_figure(fig, out / name, formats)


def _variant_panels(points, select, x, title, stem, formats, family=None):
    """One figure, one panel per damping variant, for the rows matching ``select``."""
    import matplotlib.pyplot as plt

    dampings = sorted(points["damping [N*s/m]"].unique(), reverse=True)
    fig, axes = plt.subplots(1, len(dampings), figsize=(6.0 * len(dampings), 4.4), sharey=True)
    for ax, damping in zip(np.atleast_1d(axes), dampings, strict=True):
        rows = points[points["damping [N*s/m]"] == damping]
        for column, value in select.items():
            rows = rows[np.isclose(rows[column], value)]
        panel = f"{title}\n{concl.variant_label(damping)}"
        if family is None:
            plot_errors(rows, x, ax=ax, title=panel)
        else:
            plot_error_family(rows, x, family, ax=ax, title=panel)
    # fixed margins: a layout engine would lay the figure out again at every save
    fig.subplots_adjust(left=0.06, right=0.99, bottom=0.12, top=0.86, wspace=0.06)
    return save_figure(fig, stem, formats)


def _figures(out, frequency, diameter, grid, formats):
    """Draw Figures 5-12; returns the preset summaries and the files written."""
    presets, files = {}, []
    for name in list_presets():
        name, summary, paths = _preset_figure(name, out, formats)
        presets[name] = summary
        files += paths
    for number, d in zip((10, 11), grid.sweep_diameters, strict=True):
        title = f"Figure {number}: errors against resonance, d = {d * 1e3:g} mm"
        args = (frequency.points, {"diameter [m]": d}, "resonance [Hz]", title)
        files += _variant_panels(*args, out / f"fig{number}", formats)
    title = "Figure 12: errors against grain diameter, 40 kHz sensor"
    args = (diameter.points, {"resonance [Hz]": 40e3}, "diameter [m]", title)
    files += _variant_panels(*args, out / "fig12", formats)
    title = "Peak-force error (RMS) against diameter per sensor resonance"
    args = (diameter.points, {}, "diameter [m]", title, out / "fig12_resonances", formats)
    files += _variant_panels(*args, "resonance [Hz]")
    return presets, files


def paper_study(
    out,
    *,
    quick=False,
    workers=1,
    client=None,
    seed=0,
    progress=None,
    tolerance=10.0,
    formats=("png", "svg"),
):
    """Reproduce the paper's Figures 5-12 and check its conclusions 2-5.

    Parameters
    ----------
    out : str or pathlib.Path
        Output folder (created).
    quick : bool, default False
        Use :data:`QUICK_GRID` (a few seconds) instead of :data:`PAPER_GRID`.
    workers : int, default 1
        Local worker processes for the sweeps.
    client : dask.distributed.Client or str, optional
        Run the sweeps on a Dask cluster instead.
    seed : int, default 0
        Root seed: the frequency sweep draws from ``seed``, the diameter sweep from
        ``seed + 1``.
    progress : bool, optional
        tqdm progress bars (default: only on an interactive terminal).
    tolerance : float, default 10
        RMS error [%] that counts as adequate measurement in the verdicts.
    formats : tuple of str, default ("png", "svg")
        Figure formats (any matplotlib writes).

    Returns
    -------
    PaperStudyResult
    """
    start = time.perf_counter()
    tolerance = check_number("tolerance", tolerance, low=0.0, unit="%")
    formats = check_formats(formats)
    seed = check_count("seed", seed, low=0)
    quick = check_flag("quick", quick)
    progress = check_flag("progress", progress, optional=True)
    out = Path(check_path("out", out))
    out.mkdir(parents=True, exist_ok=True)
    grid = QUICK_GRID if quick else PAPER_GRID
    setup = replace(StudySetup.paper(), scatter=Scatter(repetitions=grid.repetitions))
    options = dict(workers=workers, client=client, progress=progress)
    frequency = run_grid(
        setup,
        {
            "law.damping": grid.dampings,
            "grain.diameter": grid.sweep_diameters,
            "sensor.resonance": grid.resonances,
        },
        seed=seed,
        **options,
    )
    diameter = run_grid(
        setup,
        {
            "law.damping": grid.dampings,
            "sensor.resonance": grid.diameter_resonances,
            "grain.diameter": grid.diameters,
        },
        seed=seed + 1,
        **options,
    )
    # figures here, serially: worker processes would each import matplotlib first
    presets, files = _figures(out, frequency, diameter, grid, formats)
    files += frequency.to_csv(out, "error_vs_frequency")
    files += diameter.to_csv(out, "error_vs_diameter")
    verdicts = concl.evaluate_conclusions(frequency, diameter, tolerance)
    result = PaperStudyResult(frequency, diameter, verdicts, presets)
    settings = {
        "grid": "quick (coarse preview)" if quick else "full",
        "impacts": f"{len(frequency.impacts) + len(diameter.impacts)}",
        "grain": (
            f"paper's: {setup.grain.density:g} kg/m^3, linear contact k2 = "
            f"{setup.law.stiffness:g} N/m (mean), v0 = {setup.velocity:g} m/s"
        ),
        "sensor": (
            f"steel disc 10 mm x 2 mm ({setup.sensor.mass * 1e3:.3f} g), damping ratio "
            f"{setup.sensor.damping_ratio:g}"
        ),
        "scatter": (
            f"{grid.repetitions} repetitions, stiffness {setup.scatter.distribution} within "
            f"+-{100 * setup.scatter.spread:g} % of the mean, seed {seed}"
        ),
        "resonances (Figures 10-11)": (
            f"{len(grid.resonances)} from {grid.resonances[0] / 1e3:g} to "
            f"{grid.resonances[-1] / 1e3:g} kHz, log-spaced"
        ),
        "diameters (Figure 12)": (
            f"{len(grid.diameters)} from {grid.diameters[0] * 1e3:g} to "
            f"{grid.diameters[-1] * 1e3:g} mm at "
            + ", ".join(f"{f / 1e3:g}" for f in grid.diameter_resonances)
            + " kHz"
        ),
        "errors": (
            "std = population standard deviation over the repetitions (the paper's measure); "
            "mean and RMS also in the CSV files"
        ),
        "adequate": f"RMS error within {tolerance:g} %",
    }
    text = concl.render_summary(
        verdicts,
        concl.trends(frequency),
        concl.differences(frequency, presets, setup),
        settings,
    )
    path = out / "summary.md"
    path.write_text(text, encoding="utf-8")
    files.append(path)
    result.files = files
    result.seconds = time.perf_counter() - start
    return result
