"""One figure per Chung & Ooi test: contactlab's curves, the engines' points, the theory."""

from pathlib import Path

import numpy as np

from contactlab.benchmarks.chung_ooi.oblique import ANGLES, HISTORIES

__all__ = ["DRAW", "save_attribution_figure", "save_figure"]

_STYLE = {"total": "o-", "incremental": "x--"}


def save_figure(case, draw, out):
    """Draw ``case`` with ``draw(ax)`` (``draw(axes)`` when ``draw.panels`` > 1) and save
    ``chung_ooi_test<N>.png`` in ``out``."""
    import matplotlib.pyplot as plt

    panels = getattr(draw, "panels", 1)
    fig, axes = plt.subplots(1, panels, figsize=(6.0 * panels, 4.5), layout="constrained")
    draw(axes)
    fig.suptitle(f"Chung & Ooi test {case.number}\n{case.title}", fontsize=9)
    for ax in np.atleast_1d(axes):
        ax.legend(frameon=False, fontsize=6)
    path = Path(out) / f"chung_ooi_test{case.number}.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _lammps_points(ax, x, y, label):
    if np.isfinite(y).any():
        ax.plot(x, y, "k+", ms=7, label=label)


_ENGINE_STYLE = {"lammps": "--", "kratos": ":"}


def draw_hertz(case, curves):
    """Force against time: contactlab, each engine, and Hertz' contact time and peak."""

    def draw(ax):
        for name, runs in curves.items():
            for run, (t, f) in runs.items():
                if run != "theory":
                    ax.plot(t * 1e6, f, _ENGINE_STYLE.get(run, "-"), label=f"{name}: {run}")
            contact_time, peak = runs["theory"]
            ax.plot(
                [contact_time * 0.5e6, contact_time * 1e6],
                [peak, 0.0],
                "k*",
                ms=8,
                label=f"{name}: Hertz (peak, contact time)",
            )
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("contact force [N]")

    return draw


def draw_restitution(case, curves):
    """Realised against requested restitution: contactlab and each engine."""

    def draw(ax):
        for name, (asked, realised) in curves.items():
            for run, got in realised.items():
                style = "o-" if run == "contactlab" else "x"
                ax.plot(asked, got, style, mfc="none", label=f"{name}: {run}")
        ax.plot([0, 1], [0, 1], "k:", label="requested (theory)")
        ax.set_xlabel("requested restitution [-]")
        ax.set_ylabel("realised restitution [-]")

    return draw


def draw_oblique(case, curves):
    """Two panels, ``vt'/vt`` and ``R w'/vt`` against the angle: theory (gross sliding),
    contactlab's two Mindlin forms, LAMMPS' points, and each other engine (open squares)
    beside contactlab with that engine's rules (dotted)."""
    mu = case.inputs["friction [-]"]

    def draw(axes):
        angles = np.radians(ANGLES)
        for name, forms in curves.items():
            for history in HISTORIES:
                data = forms[history]
                for j, ax in enumerate(axes):
                    ax.plot(ANGLES, data[:, j], _STYLE[history], ms=4, label=f"{name}, {history}")
                    _lammps_points(ax, ANGLES, data[:, 2 + j], f"{name}, LAMMPS {history}")
            for found in forms.get("attribution", ()):
                if found.engine.startswith("lammps"):  # LAMMPS' points are drawn above
                    continue
                for j, ax in enumerate(axes):
                    ax.plot(
                        ANGLES,
                        found.engine_values[:, j],
                        "s",
                        mfc="none",
                        label=f"{name}, {found.engine}",
                    )
                    ax.plot(
                        ANGLES,
                        found.values[found.preset][:, j],
                        ":",
                        label=f"{name}, contactlab with {found.preset}",
                    )
        ratio = 2 * mu / np.tan(angles)  # mu (1 + e) vn / vt with e = 1
        ok = 3.5 * ratio <= 1.0
        sliding = np.array(ANGLES)[ok]
        axes[0].plot(sliding, 1 - ratio[ok], "k-", lw=2, label="gross sliding (theory)")
        # I w' = R mu (1 + e) m vn with I = 0.4 m R**2: R w'/vt = 2.5 ratio
        axes[1].plot(sliding, 2.5 * ratio[ok], "k-", lw=2, label="gross sliding (theory)")
        for ax, label in zip(axes, ("vt'/vt", "R w'/vt"), strict=True):
            ax.set_xlabel("incidence angle [deg]")
            ax.set_ylabel(f"{label} [-]")

    draw.panels = 2
    return draw


def save_attribution_figure(case, material, attributions, out):
    """Each engine's test-4 difference from contactlab under every variant of the rules
    (:mod:`~contactlab.benchmarks.chung_ooi.attribution`): one row per engine, ``vt'/vt``
    and ``R w'/vt`` minus the engine's against the angle; saved as
    ``chung_ooi_test<N>_attribution_<material>.png`` in ``out``."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        len(attributions),
        2,
        figsize=(10.0, 3.2 * len(attributions)),
        layout="constrained",
        squeeze=False,
    )
    for row, found in zip(axes, attributions, strict=True):
        for variant in found.values:
            diff = found.differences(variant)
            style = (
                "k-" if variant == found.preset else "o-" if variant.startswith("only") else "x--"
            )
            for ax, column in zip(row, diff.T, strict=True):
                ax.plot(found.angles, column, style, ms=3, lw=1.0, label=variant)
        for ax, quantity in zip(row, ("vt'/vt", "R w'/vt"), strict=True):
            ax.axhspan(-1e-3, 1e-3, color="0.85", lw=0)  # the engines' tolerance
            ax.set_yscale("symlog", linthresh=1e-4)  # 1e-1 (a rule) to 1e-4 (a step error)
            ax.axhline(0.0, color="k", lw=0.5)
            ax.set_ylabel(f"{quantity} minus {found.engine}'s [-]", fontsize=8)
            ax.set_xlabel("incidence angle [deg]")
        row[0].legend(frameon=False, fontsize=6)
    fig.suptitle(
        f"Chung & Ooi test {case.number}, {material}: contactlab with one rule switched, "
        "against each engine (grey: 1e-3; linear within 1e-4)",
        fontsize=9,
    )
    slug = material.replace(" ", "_")
    path = Path(out) / f"chung_ooi_test{case.number}_attribution_{slug}.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def draw_tangential_speed(case, curves):
    """Chung & Ooi's test 5: ``psi2`` and ``-R w'/(mu vn)`` against ``psi1``,
    contactlab's Mindlin forms, LAMMPS' points and gross sliding's closed form."""
    e = case.inputs["restitution"]

    def draw(ax):
        for name, forms in curves.items():
            for history, data in forms.items():
                ax.plot(data[:, 0], data[:, 1], _STYLE[history], label=f"{name}, psi2, {history}")
                ax.plot(data[:, 0], -data[:, 2], _STYLE[history], label=f"{name}, -R w'/(mu vn)")
                _lammps_points(ax, data[:, 0], data[:, 3], f"{name}, LAMMPS {history}")
                _lammps_points(ax, data[:, 0], -data[:, 4], f"{name}, LAMMPS {history}")
        limit = 3.5 * (1 + e)
        x = np.linspace(limit, 14.0, 50)
        ax.plot(x, (x - limit) / e, "k-", lw=2, label="gross sliding (theory)")
        ax.plot(x, -np.full_like(x, (1 + e) / 0.4), "k-", lw=2)
        ax.set_xlim(0.0, 14.0)  # Chung & Ooi's axes (85 deg lies beyond)
        ax.set_ylim(-6.0, 8.0)
        ax.set_xlabel("psi1 = vt / (mu vn) [-]")
        ax.set_ylabel("psi2 = slip'/(mu vn'), -R w'/(mu vn) [-]")

    return draw


def draw_beta(case, curves):
    """The slip ratio ``beta`` against the scaled slip: contactlab's Mindlin forms, LAMMPS'
    points where measured and gross sliding's ``beta = x - 1``."""

    def draw(ax):
        for name, forms in curves.items():
            for history, data in forms.items():
                ax.plot(data[:, 0], data[:, 1], _STYLE[history], label=f"{name}, {history}")
                if data.shape[1] > 2:
                    _lammps_points(ax, data[:, 0], data[:, 2], f"{name}, LAMMPS {history}")
        x = np.linspace(0.0, 1.0, 50)
        ax.plot(x, x - 1.0, "k-", lw=2, label="gross sliding (theory)")
        ax.set_xlabel("3.5 mu (1 + e) vn / slip [-]")
        ax.set_ylabel("beta = -slip'/slip [-]")

    return draw


def draw_pair_spin(case, curves):
    """Test 7, two identical spheres: spin and tangential velocity after the impact against the
    initial spin, beside the theory ``w1' = w``, ``v1t' = 0``."""

    def draw(ax):
        for name, data in curves.items():
            ax.plot(data[:, 0], data[:, 1], "o-", label=f"{name}: w1' [rad/s]")
            ax.plot(data[:, 0], data[:, 2], "x--", label=f"{name}: v1t' [m/s]")
        top = max(d[:, 0].max() for d in curves.values())
        ax.plot([0, top], [0, top], "k:", label="theory: w1' = w, v1t' = 0")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlabel("initial spin w [rad/s]")
        ax.set_ylabel("after the impact")

    return draw


DRAW = {
    1: draw_hertz,
    2: draw_hertz,
    3: draw_restitution,
    4: draw_oblique,
    5: draw_tangential_speed,
    6: draw_beta,
    7: draw_pair_spin,
    8: draw_beta,
    9: draw_restitution,
}
"""Test number -> ``draw_*(case, curves)`` returning ``draw(ax)``."""
