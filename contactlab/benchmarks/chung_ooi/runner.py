"""Run the nine Chung & Ooi tests: contactlab (and LAMMPS) against theory, figures, one table.

What each test grades and its tolerance: :mod:`~contactlab.benchmarks.chung_ooi.grading`
(tolerances), :mod:`~contactlab.benchmarks.chung_ooi.normal` (tests 1, 2, 3, 9),
:mod:`~contactlab.benchmarks.chung_ooi.oblique` (4, 5, 6),
:mod:`~contactlab.benchmarks.chung_ooi.pairs` (7, 8).

LAMMPS' column: pass ``lammps``, a callable with the signature of
:func:`dem_check.engines.lammps.oblique.lammps_oblique` (``contactlab benchmark chung-ooi
--lammps`` does). It runs the sphere-on-plane tests 4, 5 and 6, where LAMMPS holds the
same laws on a wall; the pair tests run through the exact reduction here only.

DEM engines (``engines``, ``contactlab benchmark chung-ooi --engines lammps,kratos``):
each :class:`EngineRunner` runs the normal tests 1, 2, 3 and 9 (graded beside contactlab,
:mod:`~contactlab.benchmarks.chung_ooi.normal`) and, when it has an ``oblique``, test 4,
reported beside (:func:`~contactlab.benchmarks.chung_ooi.oblique.oblique_test`).
"""

from dataclasses import dataclass
from pathlib import Path

from contactlab.benchmarks.chung_ooi import attribution, normal, oblique, pairs
from contactlab.benchmarks.chung_ooi.cases import CASES, DISAGREEMENTS
from contactlab.benchmarks.chung_ooi.figures import DRAW, save_attribution_figure, save_figure
from contactlab.benchmarks.chung_ooi.grading import ENGINES
from contactlab.plausibility import internal
from contactlab.validation import check_choice

__all__ = ["EngineRunner", "run_chung_ooi"]

_LAMMPS_TESTS = (4, 5, 6)
"""Tests LAMMPS runs (a sphere on a rigid wall)."""


@dataclass(frozen=True)
class EngineRunner:
    """A DEM engine's runs for the benchmark.

    Attributes
    ----------
    normal : callable
        ``normal(grain, law, speed)``: a normal impact on a rigid plane, returning an object
        with ``contact_time`` [s], ``peak_contact_force`` [N] and ``restitution`` [-] (e.g.
        ``dem_check.drop_test`` on ``Sensor.rigid()``).
    oblique : callable, optional
        ``oblique(grain, normal_law, tangential_law, speed, angle, spin=...)`` as
        :func:`dem_check.engines.kratos.kratos_oblique`; runs test 4, reported.
    """

    normal: object
    oblique: object = None


def _run_case(case, material, lammps, engines):
    number = case.number
    normals = {name: runner.normal for name, runner in engines.items()}
    if number in (1, 2):
        return normal.hertz_test(case, material, pair=number == 1, engines=normals)
    if number in (3, 9):
        return normal.restitution_test(case, material, pair=number == 9, engines=normals)
    if number == 4:
        obliques = {n: r.oblique for n, r in engines.items() if r.oblique is not None}
        return oblique.oblique_test(case, material, lammps, reported=obliques)
    if number == 5:
        return oblique.tangential_speed_test(case, material, lammps)
    if number == 6:
        return oblique.spin_test(case, material, lammps)
    if number == 7:
        return pairs.pair_spin_test(case, material)
    return pairs.unequal_pair_test(case, material)


def run_chung_ooi(out=None, lammps=None, engines=None, tests=None):
    """Run the tests; write one figure per test and ``chung_ooi.csv`` into ``out``.

    Parameters
    ----------
    out : str or path-like, optional
        Output folder (created); no files are written when None.
    lammps : callable, optional
        LAMMPS' oblique impact (:func:`dem_check.engines.lammps.oblique.lammps_oblique`);
        without it the LAMMPS column reads "not run" in tests 4-6.
    engines : dict, optional
        ``{name: EngineRunner}`` for names of
        :data:`~contactlab.benchmarks.chung_ooi.grading.ENGINES`.
    tests : iterable of int, optional
        The test numbers to run (default all nine).

    Returns
    -------
    dict
        ``rows`` (one per graded number: test, material, quantity, contactlab, theory,
        each engine's value and error, relative_error, tolerance, lammps_tolerance,
        not_graded, passed; :func:`~contactlab.benchmarks.chung_ooi.grading.row`),
        ``not_run`` ({test: reason}), ``disagreements`` ({test: what the sources say and
        what is used}), ``figures`` (paths) and ``markdown`` (the table).
    """
    rows, not_run, figures, found = [], {}, [], []
    if out is not None:
        Path(out).mkdir(parents=True, exist_ok=True)
    chosen = None if tests is None else {check_choice("tests", n, range(1, 10)) for n in tests}
    for case in CASES:
        if chosen is not None and case.number not in chosen:
            continue
        if case.not_run:
            not_run[case.number] = case.not_run
            continue
        engine = lammps if case.number in _LAMMPS_TESTS else None
        curves = {}
        for material in case.materials:
            # the benchmark's spheres (0.1-0.2 m, up to 17 kg) are no grains: no warnings
            with internal():
                got, curves[material.name] = _run_case(case, material, engine, engines or {})
            rows.extend(got)
            attributions = curves[material.name].get("attribution", []) if case.number == 4 else []
            found += attributions
            if out is not None and attributions:
                figures.append(save_attribution_figure(case, material.name, attributions, out))
        if out is not None:
            figures.append(save_figure(case, DRAW[case.number](case, curves), out))
    if out is not None:
        _write_tables(out, rows, found)
    return {
        "rows": rows,
        "not_run": not_run,
        "disagreements": dict(DISAGREEMENTS),
        "figures": figures,
        "attribution": found,
        "markdown": _markdown(rows, not_run),
        "attribution_markdown": attribution.markdown(found),
    }


def _write_tables(out, rows, found):
    """``chung_ooi.csv`` (the graded rows) and, when engines ran test 4,
    ``chung_ooi_attribution.csv`` (every variant at every angle)."""
    import pandas as pd

    from contactlab.tables import write_csv

    write_csv(pd.DataFrame(rows), Path(out) / "chung_ooi.csv")
    if found:
        table = [r for item in found for r in item.table()]
        attribution_csv = Path(out) / "chung_ooi_attribution.csv"
        write_csv(pd.DataFrame(table), attribution_csv)


def _number(value, missing="not run"):
    return missing if value is None else f"{value:.8g}"


def _error(value):
    return "" if value is None else f"{value:.1e}"


_LABELS = {"lammps": "LAMMPS", "kratos": "Kratos"}


def _engine_cells(r, name):
    value, error = _number(r[name]), _error(r[f"{name}_error"])
    if r[name] is not None and name in r["not_graded"].split(","):
        error += " (reported)"
    return [value, error]


def _markdown(rows, not_run):
    heads = [f"{_LABELS[n]} | {_LABELS[n]} error" for n in ENGINES]
    lines = [
        f"| test | material | quantity | contactlab | theory | error | {' | '.join(heads)} "
        "| tol. | engine tol. | pass |",
        "|" + "---|" * (9 + 2 * len(ENGINES)),
    ]
    for r in rows:
        engine_cells = [cell for name in ENGINES for cell in _engine_cells(r, name)]
        lines.append(
            f"| {r['test']} | {r['material']} | {r['quantity']} | {_number(r['contactlab'])} | "
            f"{_number(r['theory'], 'no closed form')} | {_error(r['relative_error'])} | "
            f"{' | '.join(engine_cells)} | {r['tolerance']:.0e} | "
            f"{r['lammps_tolerance']:.0e} | {'pass' if r['passed'] else 'FAIL'} |"
        )
    for number, reason in not_run.items():
        lines.append(f"| {number} | - | not run: {reason} |" + " |" * (6 + 2 * len(ENGINES)))
    return "\n".join(lines)
