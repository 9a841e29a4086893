"""Figures of the error study (Figures 10-12 of Keska et al. 2021) and of the presets.

matplotlib is imported only inside these functions. Colours follow the paper: red for the
contact-time error, green for the peak-force error. Solid lines are the paper's measure
(standard deviation over the repetitions), dashed lines the RMS error, which includes the
bias the standard deviation does not see.
"""

from collections.abc import Iterable

import numpy as np

from contactlab.plotting import axes_or_new

__all__ = [
    "check_formats",
    "plot_design_map",
    "plot_error_family",
    "plot_errors",
    "save_figure",
]

_COLOURS = {"time": "tab:red", "force": "tab:green"}
_LABELS = {"time": "contact-time error", "force": "peak-force error"}
_MEASURES = {
    "std": ("", "-", "std (paper)"),
    "rms": ("_rms", "--", "RMS"),
    "mean": ("_mean", ":", "mean"),
}
_FAMILY_LABELS = {
    "resonance [Hz]": lambda v: f"{v / 1e3:g} kHz sensor",
    "diameter [m]": lambda v: f"d = {v * 1e3:g} mm",
}
_AXES = {
    "resonance [Hz]": (1e-3, "sensor resonance frequency [kHz]", "log"),
    "diameter [m]": (1e3, "grain diameter [mm]", "linear"),
}


def _style(ax, xscale, xlabel, ylabel, title):
    """Scales, plain-number tick labels (no mathtext: cheaper and easier to read), major grid."""
    from matplotlib.ticker import FuncFormatter

    plain = FuncFormatter(lambda v, _: f"{v:g}")
    ax.set_xscale(xscale)
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(plain)
    ax.xaxis.set_minor_formatter(FuncFormatter(lambda v, _: ""))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, color="0.9", lw=0.5)
    if title:
        ax.set_title(title)
    ax.legend(fontsize="small", frameon=False)


def _x(column):
    from contactlab.validation import check_choice

    return _AXES[check_choice("x", column, tuple(_AXES))]


def plot_errors(points, x, ax=None, measures=("std", "rms"), title=None):
    """Both errors of one series of grid points against resonance or diameter.

    Parameters
    ----------
    points : pandas.DataFrame
        Per-point statistics (:attr:`SweepResult.points`), already restricted to one
        series (one diameter for a frequency sweep, one resonance for a diameter sweep).
    x : {"resonance [Hz]", "diameter [m]"}
        Column on the horizontal axis (drawn in kHz or mm).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure when None.
    measures : tuple of {"std", "rms", "mean"}
        Statistics to draw; each error gets one line per measure.
    title : str, optional
        Axes title.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
    """
    scale, label, xscale = _x(x)
    fig, ax = axes_or_new(ax, figsize=(7.0, 4.2))
    data = points.sort_values(x)
    for error in ("time", "force"):
        for measure in measures:
            suffix, style, name = _MEASURES[measure]
            ax.plot(
                data[x] * scale,
                data[f"{error}_error{suffix} [%]"].abs(),
                style,
                color=_COLOURS[error],
                marker="." if measure == "std" else None,
                label=f"{_LABELS[error]}, {name}",
            )
    _style(ax, xscale, label, "error [%]", title)
    return fig, ax


def plot_error_family(points, x, family, error="force", measure="rms", ax=None, title=None):
    """One error against ``x``, one line per value of a ``family`` column.

    Parameters
    ----------
    points, x, ax, title
        As for :func:`plot_errors`.
    family : str
        Column whose values get one line each (e.g. ``"resonance [Hz]"``).
    error : {"time", "force"}
        Which error.
    measure : {"std", "rms", "mean"}
        Which statistic (``mean`` is drawn as its absolute value).

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
    """
    scale, label, xscale = _x(x)
    suffix, _, name = _MEASURES[measure]
    fig, ax = axes_or_new(ax, figsize=(7.0, 4.2))
    for value, group in points.groupby(family, sort=True):
        data = group.sort_values(x)
        ax.plot(
            data[x] * scale,
            data[f"{error}_error{suffix} [%]"].abs(),
            marker=".",
            label=_FAMILY_LABELS.get(family, lambda v: f"{family} = {v:g}")(value),
        )
    _style(ax, xscale, label, f"{_LABELS[error]}, {name} [%]", title)
    return fig, ax


def plot_design_map(design_map, points=(), tolerance=10.0, color_limit=100.0):
    """Force and contact-time errors over resonance x diameter, side by side.

    Parameters
    ----------
    design_map : DesignMap
        From :func:`contactlab.study.design_map`.
    points : sequence of (float, float)
        ``(resonance [Hz], diameter [m])`` operating points to mark.
    tolerance : float, default 10
        Error [%] drawn as the dashed ``+-tolerance`` contours.
    color_limit : float, default 100
        Largest error [%] the colours resolve; beyond it they saturate (the colour bar
        says so with its arrows; the table keeps every value).

    Returns
    -------
    (matplotlib.figure.Figure, numpy.ndarray of matplotlib.axes.Axes)
    """
    import matplotlib.pyplot as plt

    f_khz, d_mm = design_map.resonances / 1e3, design_map.diameters * 1e3
    fig, axes = plt.subplots(1, 2, figsize=(12.0, 4.6), layout="constrained", sharey=True)
    for ax, column, name in zip(
        axes, ("force_error [%]", "time_error [%]"), ("peak force", "contact time"), strict=True
    ):
        values = design_map.grid(column)
        limit = min(float(np.nanmax(np.abs(values))), color_limit)
        mesh = ax.pcolormesh(
            f_khz, d_mm, values, cmap="RdBu_r", vmin=-limit, vmax=limit, shading="nearest"
        )
        fig.colorbar(mesh, ax=ax, label=f"{name} error [%]", extend="both")
        lines = ax.contour(
            f_khz, d_mm, values, levels=[-tolerance, tolerance], colors="k", linestyles="--"
        )
        ax.clabel(lines, fmt="%+g %%", fontsize=7)
        ax.set_xscale("log")
        ax.set_xlabel("sensor resonance [kHz]")
        ax.set_title(f"{name}: sensor reading vs true contact")
        if len(points):
            marks = np.asarray(points, dtype=float)
            ax.plot(marks[:, 0] / 1e3, marks[:, 1] * 1e3, "k*", ms=9, label="operating points")
            ax.legend(loc="upper right", frameon=True, fontsize=8)
    axes[0].set_ylabel("grain diameter [mm]")
    fig.suptitle(design_map.law, fontsize=9)
    return fig, axes


def check_formats(formats):
    """Return ``formats`` as a tuple after checking each is a file format matplotlib writes.

    Called before a long computation, so that a misspelt format fails before it, not after.
    """
    from matplotlib.backend_bases import FigureCanvasBase

    from contactlab.errors import ParameterError
    from contactlab.validation import check_choice

    supported = tuple(FigureCanvasBase.get_supported_filetypes())
    if isinstance(formats, str) or not isinstance(formats, Iterable):
        raise ParameterError(
            f"formats must be a sequence of names such as ('png',); got {formats!r}"
        )
    return tuple(check_choice("formats", fmt, supported) for fmt in formats)


def save_figure(fig, path_stem, formats=("png", "svg")):
    """Save a figure as ``path_stem.<format>`` for each format and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path_stem : pathlib.Path
        File path without suffix.
    formats : tuple of str, default ("png", "svg")
        File formats.

    Returns
    -------
    list of pathlib.Path
    """
    import matplotlib.pyplot as plt

    paths = []
    for fmt in formats:
        path = path_stem.with_suffix(f".{fmt}")
        fig.savefig(path, dpi=150)
        paths.append(path)
    plt.close(fig)
    return paths
