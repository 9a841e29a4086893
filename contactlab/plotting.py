"""Plots of impacts and studies. matplotlib is imported only here, only when plotting."""

from contactlab.errors import ParameterError

__all__ = ["axes_or_new", "finish_force_axes", "plot_impact", "plot_oblique"]


def axes_or_new(ax, figsize=(7.0, 4.0)):
    """``(figure, ax)`` for the given axes, or for new axes in a new figure when None.

    Parameters
    ----------
    ax : matplotlib.axes.Axes or None
    figsize : (float, float)
        Size of a new figure [inch].
    """
    from matplotlib.axes import Axes

    if ax is not None and not isinstance(ax, Axes):
        raise ParameterError(f"ax must be matplotlib axes or None; got {ax!r}")
    if ax is None:
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=figsize, layout="constrained")
        return fig, ax
    return ax.figure, ax


def finish_force_axes(ax, title=None, t_us=None):
    """Zero line, axis labels (time [µs], force [N]), title and legend of a force plot.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    title : str, optional
        Axes title.
    t_us : array_like, optional
        Time axis [µs]; the x range is set to its ends when given.
    """
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("time [µs]")
    ax.set_ylabel("force [N]")
    if t_us is not None:
        ax.set_xlim(t_us[0], t_us[-1])
    if title:
        ax.set_title(title)
    ax.legend(loc="upper right", frameon=False)


def _force_plot(t, curves, ax, title):
    """Forces against time in microseconds, one line per ``(force [N], line width,
    colour, label)`` of ``curves`` (``t`` [s]); returns ``(figure, axes)``."""
    fig, ax = axes_or_new(ax)
    t_us = t * 1e6
    for force, width, color, label in curves:
        ax.plot(t_us, force, lw=width, color=color, label=label)
    finish_force_axes(ax, title, t_us)
    return fig, ax


def plot_impact(result, ax=None, title=None):
    """Contact force S2 (thick line) and sensor signal S1 (thin line) against time.

    Parameters
    ----------
    result : ImpactResult or any object with ``t``, ``contact_force``, ``sensor_force``
        The impact to draw; time is shown in microseconds, forces in newtons.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    title : str, optional
        Axes title.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
        The figure and the axes the two forces are drawn into.
    """
    curves = [
        (result.contact_force, 2.6, "black", "contact force $S_2$"),
        (result.sensor_force, 1.0, "tab:red", "sensor signal $S_1$"),
    ]
    return _force_plot(result.t, curves, ax, title)


def plot_oblique(result, ax=None, title=None):
    """Normal force (thick), tangential force and sensor signal of an oblique impact.

    Parameters
    ----------
    result : ObliqueResult
        The impact to draw; time in microseconds, forces in newtons.
    ax : matplotlib.axes.Axes, optional
    title : str, optional
        As for :func:`plot_impact`.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
        The figure and the axes; the sensor signal is left out for a rigid sensor.
    """
    curves = [
        (result.normal_force, 2.6, "black", "normal force $S_2$"),
        (result.tangential_force, 1.6, "tab:blue", "tangential force"),
    ]
    if not result.sensor.is_rigid:
        curves.append((result.sensor_force, 1.0, "tab:red", "sensor signal $S_1$"))
    return _force_plot(result.t, curves, ax, title)
