"""Figures of the inverse methods. matplotlib is imported only when plotting."""

from contactlab.entry_checks import check_shaped
from contactlab.errors import ParameterError
from contactlab.plotting import axes_or_new, finish_force_axes
from contactlab.validation import check_samples

__all__ = ["plot_fit", "plot_identification", "plot_reconstruction"]


def _curve(t_name, t, y_name, y):
    """``t`` [s] and ``y`` as finite 1-D float arrays of one length (ParameterError naming
    the culprit otherwise)."""
    t, y = check_samples(t_name, t, unit="s"), check_samples(y_name, y)
    if t.shape != y.shape:
        raise ParameterError(
            f"{t_name} and {y_name} must have one length; got {t.size} and {y.size} samples"
        )
    return t, y


def plot_identification(t, signal, identification, ax=None, title=None):
    """Trace (thin) and the fitted free ringing over the identification window.

    Parameters
    ----------
    t, signal : array_like
        The trace that was identified: time [s] and signal.
    identification : SensorIdentification
        From :func:`contactlab.inverse.identify_sensor`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    title : str, optional
        Axes title; default the identified resonance and damping ratio.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
        The figure and the axes; the identification window is shaded.
    """
    check_shaped(
        "identification",
        identification,
        ("window", "ringing", "resonance", "damping_ratio"),
        "a SensorIdentification (from identify_sensor)",
    )
    t, signal = _curve("t", t, "signal", signal)
    fig, ax = axes_or_new(ax)
    t0, t1 = identification.window
    inside = (t >= t0) & (t <= t1)
    ax.plot(t * 1e6, signal, lw=0.8, color="tab:red", label="signal")
    ax.plot(
        t[inside] * 1e6,
        identification.ringing(t[inside]),
        lw=1.6,
        color="tab:blue",
        label="fitted free ringing",
    )
    ax.axvspan(t0 * 1e6, t1 * 1e6, color="0.92", zorder=0)
    ax.set_xlabel("time [µs]")
    ax.set_ylabel("signal")
    ax.set_title(
        title
        or f"f1 = {identification.resonance / 1e3:.5g} kHz, "
        f"zeta = {identification.damping_ratio:.3g}"
    )
    ax.legend(loc="upper right", frameon=False)
    return fig, ax


def plot_reconstruction(reconstruction, truth=None, ax=None, title=None):
    """True force (thick), sensor signal (thin) and reconstructed force against time.

    Parameters
    ----------
    reconstruction : ForceReconstruction
        From :func:`contactlab.inverse.reconstruct_force`.
    truth : ImpactResult or (array_like, array_like), optional
        The true contact force: a simulation, or ``(t [s], force [N])``.
    ax : matplotlib.axes.Axes, optional
    title : str, optional
        As for :func:`contactlab.plot_impact`.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
        The figure and the axes the forces and the signal are drawn into.
    """
    check_shaped(
        "reconstruction",
        reconstruction,
        ("t", "signal", "force", "method"),
        "a ForceReconstruction (from reconstruct_force)",
    )
    if truth is not None:
        if hasattr(truth, "contact_force"):
            truth = (truth.t, truth.contact_force)
        elif isinstance(truth, str) or not isinstance(truth, tuple | list) or len(truth) != 2:
            raise ParameterError(
                f"truth must be an ImpactResult or (t [s], force [N]); got {truth!r}"
            )
        t_true, f_true = _curve("truth t", truth[0], "truth force", truth[1])
    fig, ax = axes_or_new(ax)
    if truth is not None:
        ax.plot(t_true * 1e6, f_true, lw=2.6, color="black", label="true contact force $S_2$")
    t_us = reconstruction.t * 1e6
    ax.plot(t_us, reconstruction.signal, lw=0.8, color="tab:red", label="sensor signal $S_1$")
    ax.plot(
        t_us,
        reconstruction.force,
        lw=1.6,
        color="tab:blue",
        label=f"reconstructed $S_2$ ({reconstruction.method})",
    )
    finish_force_axes(ax, title)
    return fig, ax


def plot_fit(fit, ax=None, title=None):
    """Trace (thin), fitted sensor signal and fitted contact force against time.

    Parameters
    ----------
    fit : ContactFit
        From :func:`contactlab.inverse.fit_contact`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    title : str, optional
        Axes title; default the law and the reduced chi-squared.

    Returns
    -------
    (matplotlib.figure.Figure, matplotlib.axes.Axes)
    """
    check_shaped(
        "fit",
        fit,
        ("t", "signal", "model", "onset", "simulation", "quality", "law_name"),
        "a ContactFit (from fit_contact)",
    )
    fig, ax = axes_or_new(ax)
    sim = fit.simulation
    ax.plot(fit.t * 1e6, fit.signal, lw=0.8, color="tab:red", label="measured $S_1$")
    ax.plot(fit.t * 1e6, fit.model, lw=1.6, color="tab:blue", label="fitted $S_1$")
    ax.plot(
        (sim.t + fit.onset) * 1e6,
        sim.contact_force,
        lw=2.6,
        color="black",
        label="fitted contact force $S_2$",
    )
    chi2 = fit.quality.reduced_chi_squared
    verdict = "consistent" if fit.quality.consistent else "NOT consistent"
    finish_force_axes(
        ax, title or f"{fit.law_name}: reduced $\\chi^2$ = {chi2:.3g}, {verdict} with the trace"
    )
    return fig, ax
