"""Batched oblique impacts: sweeps over angle, spin, speed and parameters, one row each.

:func:`oblique_impacts` solves every row of a frame as :func:`contactlab.simulate_oblique`
solves a spinning grain striking a flat or a sensor at an angle, through Tsuji's damped
Hertz normal law (:class:`~contactlab.laws.HertzDamped`; ``damping = 0`` is elastic
Hertz) and a :class:`~contactlab.laws.Mindlin` tangential law, and adds the rebound
numbers as :class:`~contactlab.ObliqueResult` defines them. The rows run through the
single solver's own compiled phase loop (:mod:`contactlab.batch.oblique_kernel`) without
its output grid; rows the kernel hands back are solved by
:func:`contactlab.simulate_oblique`, and a row it refuses gets NaN and its reason.
"""

import math

import numpy as np

from contactlab.analytic.tangential import SOLID_SPHERE_INERTIA
from contactlab.batch.frame import impact_columns, input_column
from contactlab.batch.oblique_kernel import solve_rows
from contactlab.batch.rows import DEFAULT_CHUNK, run_kernel, solve_frame
from contactlab.bodies import Grain, Sensor
from contactlab.errors import ParameterError
from contactlab.laws import DAMPING_FORMS, HISTORY_FORMS, HertzDamped, Mindlin
from contactlab.plausibility import internal
from contactlab.quantities import columns
from contactlab.solver.conventions import LEVER_ARMS
from contactlab.solver.oblique import simulate_oblique
from contactlab.validation import check_choice, check_inertia_factor, check_number

__all__ = ["OBLIQUE_INPUTS", "OBLIQUE_RESULTS", "oblique_impacts"]

OBLIQUE_INPUTS = (
    *impact_columns(
        input_column("k_hertz"),
        input_column("damping", low_open=False),
        input_column("k_mindlin"),
        input_column("friction", low_open=False),
    ),
    input_column("radius"),
    input_column("angle", low_open=False, below=math.pi / 2),
    input_column("spin", signed=True),
)
"""Input columns of :func:`oblique_impacts`, in the kernel's order."""

OBLIQUE_RESULTS = columns(
    "contact_time",
    "restitution",
    "tangential_velocity",
    "angular_velocity",
    "rebound_angle",
    "contact_rebound_angle",
    "tangential_restitution",
    "phases",
)
"""Columns :func:`oblique_impacts` adds: the :class:`~contactlab.ObliqueResult` attributes
of the same names (``phases``: the number of stick and slide phases)."""


def _single(row, kappa, history, damping, lever_arm, rtol):
    """One row by :func:`contactlab.simulate_oblique`, in the order of OBLIQUE_RESULTS."""
    m1, k1, c1, m2, k_hertz, eta, k_mindlin, mu, v0, radius, angle, spin = row
    with internal():
        sensor = Sensor.rigid() if math.isinf(k1) else Sensor(mass=m1, stiffness=k1, damping=c1)
        res = simulate_oblique(
            Grain.from_mass(m2, diameter=2.0 * radius),
            sensor,
            HertzDamped(k_hertz, eta),
            Mindlin(k_mindlin, mu, history, damping),
            v0,
            angle,
            spin=spin,
            rtol=rtol,
            inertia_factor=kappa,
            lever_arm=lever_arm,
            audit=False,
        )
    return [
        len(res.phases) if name == "phases [-]" else getattr(res, name.split()[0])
        for name in OBLIQUE_RESULTS
    ]


def _solver(kappa, history, damping, lever_arm, rtol):
    options = np.array(
        [
            float(history != "total"),
            float(history == "incremental_rescaled"),
            float(damping == "tied"),
            float(lever_arm == "contact"),
        ]
    )

    def solve(arrays, lo, hi, out, failures):
        columns = [np.ascontiguousarray(arrays[c.name][lo:hi]) for c in OBLIQUE_INPUTS]
        for i in run_kernel(solve_rows, columns, (kappa, options, rtol), out):
            row = [float(col[i]) for col in columns]
            try:
                out[i] = _single(row, kappa, history, damping, lever_arm, rtol)
            except (ValueError, ArithmeticError, RuntimeError) as exc:
                out[i] = math.nan
                failures[lo + i] = f"{type(exc).__name__}: {exc}"

    return solve


def oblique_impacts(
    frame,
    *,
    history="total",
    damping="none",
    lever_arm="radius",
    inertia_factor=SOLID_SPHERE_INERTIA,
    rtol=1e-9,
    chunk=DEFAULT_CHUNK,
    threads=1,
):
    """Oblique Hertz-Mindlin impacts, one per row, with the single solver's numbers.

    Parameters
    ----------
    frame : pandas.DataFrame
        One row per impact with the columns of :data:`OBLIQUE_INPUTS`: ``m1 [kg]``,
        ``k1 [N/m]``, ``c1 [N*s/m]`` (the sensor along the normal; ``k1 = inf`` for a rigid
        flat), ``m2 [kg]`` (grain mass), ``k_hertz [N/m**1.5]`` and
        ``damping [N*s/m**1.25]`` (``kH d**1.5 + eta d**0.25 d'``), ``k_mindlin
        [N/m**1.5]`` and ``friction [-]`` (:class:`~contactlab.laws.Mindlin`),
        ``v0 [m/s]`` (impact speed), ``radius [m]`` (grain radius), ``angle [rad]``
        (incidence from the normal, in [0, pi/2)) and ``spin [rad/s]`` (signed as in
        :func:`contactlab.simulate_oblique`); other columns are kept.
    history : {"total", "incremental", "incremental_rescaled"}, default "total"
        Mindlin's history rule (:class:`~contactlab.laws.Mindlin`).
    damping : {"none", "tied"}, default "none"
        Mindlin's tangential damping.
    lever_arm : {"radius", "contact"}, default "radius"
        Arm of the torque and the contact-point slip (:func:`contactlab.simulate_oblique`).
    inertia_factor : float, default 0.4
        ``I / (m R**2)`` [-].
    rtol : float, default 1e-9
        Relative tolerance of the integration (the single solver's default).
    chunk : int, default 100 000
        Rows solved at a time.
    threads : int or None, default 1
        Threads solving chunks side by side; ``None`` uses every core.

    Returns
    -------
    pandas.DataFrame
        A copy of ``frame`` with :data:`OBLIQUE_RESULTS` added; a row that could not be
        solved has NaN there and its reason in an ``error`` column.

    Raises
    ------
    ParameterError
        For a missing or bad column (the message names it and the first bad row) or a bad
        option.

    Notes
    -----
    Each row is ``simulate_oblique(Grain.from_mass(m2, diameter=2 radius), Sensor(m1, k1,
    c1), HertzDamped(k_hertz, damping), Mindlin(k_mindlin, friction, history, damping),
    v0, angle, spin=spin, rtol=rtol, ...)``: the same compiled steps and events, so the
    numbers agree with the single solver's to rounding.
    """
    history = check_choice("history", history, HISTORY_FORMS)
    damping = check_choice("damping", damping, DAMPING_FORMS)
    if history == "total" and damping == "tied":
        raise ParameterError(
            "history='total' with damping='tied' is not supported (beside a damped normal "
            "law the solver cannot decide the phase at the touch, Mindlin.for_contact); use "
            "history='incremental' or 'incremental_rescaled' with damping='tied'"
        )
    lever_arm = check_choice("lever_arm", lever_arm, LEVER_ARMS)
    kappa = check_inertia_factor("inertia_factor", inertia_factor)
    rtol = check_number("rtol", rtol, low=1e-14, high=1e-3, low_open=False)
    solve = _solver(kappa, history, damping, lever_arm, rtol)
    return solve_frame(
        frame, OBLIQUE_INPUTS, solve, chunk=chunk, threads=threads, results=OBLIQUE_RESULTS
    )
